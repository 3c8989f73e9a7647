// boxsim's interactive demo: a scene of the thesis stepped by the WebAssembly engine
// (boxsim_demo.mjs, built from demo.cpp) and drawn with three.js. Steps are 1/60 s; the page
// runs as many as real time asks, at most 4 a frame. window.boxsimPage is the interface the
// browser test (test/browser_test.mjs) drives.
import * as THREE from 'three';
import { OrbitControls } from './OrbitControls.js';
import createBoxsim from './boxsim_demo.mjs';

const DT = 1 / 60;  // s
const FLAG_IMMOVABLE = 1, FLAG_ASLEEP = 2, FLAG_STABLE = 4;  // demo.hpp, BodyFlag
// Where each scene is seen from (m); shots leave from the eye point.
const VIEWS = {
  pyramid: { eye: [10, 6, 15], target: [0, 3.5, 0] },
  clump: { eye: [30, 22, 38], target: [0, 6, 0] },
  die: { eye: [3, 3, 6], target: [0, 0.8, 0] },
  tower: { eye: [8, 7, 14], target: [0, 4, 0] },
};

const Module = await createBoxsim();
const $ = (id) => document.getElementById(id);

const renderer = new THREE.WebGLRenderer({ antialias: true, preserveDrawingBuffer: true });
renderer.setPixelRatio(window.devicePixelRatio);
$('view').appendChild(renderer.domElement);
const scene3 = new THREE.Scene();
scene3.background = new THREE.Color(0x2b3038);
scene3.add(new THREE.HemisphereLight(0xffffff, 0x404040, 1.2));
const sun = new THREE.DirectionalLight(0xffffff, 1.6);
sun.position.set(10, 20, 8);
scene3.add(sun);
const camera = new THREE.PerspectiveCamera(50, 1, 0.1, 1000);
const controls = new OrbitControls(camera, renderer.domElement);
const colours = {
  ground: new THREE.Color(0x59606b), box: new THREE.Color(0xd9a441),
  stable: new THREE.Color(0x6b4a17), asleep: new THREE.Color(0x7d97b8),
};

let demo = null, meshes = [], settings = null;
let stepTimes = [], frameTimes = [], lastFrame = performance.now(), owed = 0;

function fail(error) {
  const message = typeof error === 'number' ? Module.exceptionMessage(error) : String(error);
  $('error').textContent = message;
  console.error('boxsim: ' + message);
}

function readSettings() {
  const method = $('method').value, damped = method === 'damped';
  $('sleep').disabled = $('stability').disabled = !damped;
  return {
    scene: $('scene').value, method, filter: $('filter').value,
    sleep: damped ? $('sleep').checked : true, stability: damped ? $('stability').checked : true,
  };
}

function start() {
  settings = readSettings();
  $('error').textContent = '';
  if (demo) demo.delete();
  for (const mesh of meshes) { scene3.remove(mesh); mesh.geometry.dispose(); mesh.material.dispose(); }
  meshes = [];
  try {
    demo = new Module.Demo(settings.scene, settings.method, settings.sleep, settings.stability,
                           settings.filter);
  } catch (error) { demo = null; fail(error); return; }
  const half = demo.halfExtents(), flags = demo.flags();
  for (let i = 0; i < demo.bodyCount(); ++i) {
    const geometry = new THREE.BoxGeometry(2 * half[3 * i], 2 * half[3 * i + 1], 2 * half[3 * i + 2]);
    const ground = i === 0 && (flags[i] & FLAG_IMMOVABLE);
    const material = new THREE.MeshLambertMaterial({ color: ground ? colours.ground : colours.box });
    const mesh = new THREE.Mesh(geometry, material);
    if (!ground) mesh.add(new THREE.LineSegments(new THREE.EdgesGeometry(geometry),
                                                 new THREE.LineBasicMaterial({ color: 0x222222 })));
    scene3.add(mesh);
    meshes.push(mesh);
  }
  const view = VIEWS[settings.scene];
  camera.position.set(...view.eye);
  controls.target.set(...view.target);
  controls.update();
  stepTimes = []; owed = 0;
  draw();
}

function draw() {
  if (!demo) return;
  const poses = demo.poses(), flags = demo.flags();
  for (let i = 0; i < meshes.length; ++i) {
    const mesh = meshes[i], p = 7 * i;
    mesh.position.set(poses[p], poses[p + 1], poses[p + 2]);
    mesh.quaternion.set(poses[p + 3], poses[p + 4], poses[p + 5], poses[p + 6]);
    // A shot not yet fired waits, immovable, far away: hidden.
    mesh.visible = i === 0 || !(flags[i] & FLAG_IMMOVABLE);
    if (i > 0) {
      mesh.material.color.copy(flags[i] & FLAG_STABLE ? colours.stable
                               : flags[i] & FLAG_ASLEEP ? colours.asleep : colours.box);
    }
  }
  renderer.render(scene3, camera);
}

function step() {
  const t0 = performance.now();
  try { demo.step(); } catch (error) { fail(error); demo = null; return; }
  stepTimes.push(performance.now() - t0);
  if (stepTimes.length > 60) stepTimes.shift();
}

function frame(now) {
  requestAnimationFrame(frame);
  const elapsed = Math.min((now - lastFrame) / 1000, 0.25);
  lastFrame = now;
  frameTimes.push(elapsed);
  if (frameTimes.length > 60) frameTimes.shift();
  if (!demo || page.paused) { draw(); return; }
  owed += elapsed;
  for (let n = 0; owed >= DT && n < 4; ++n) {
    step();
    owed -= DT;
    if (!demo || stepTimes[stepTimes.length - 1] > 1000 * DT) break;  // slower than real time
  }
  owed = Math.min(owed, 4 * DT);
  draw();
  const mean = (a) => a.reduce((s, x) => s + x, 0) / Math.max(a.length, 1);
  $('status').textContent = demo ?
    `t ${demo.time().toFixed(2)} s   ${mean(stepTimes).toFixed(2)} ms/step\n` +
    `${(1 / Math.max(mean(frameTimes), 1e-6)).toFixed(0)} fps   ${page.shotsLeft} shots left` : '';
}

function resize() {
  renderer.setSize(window.innerWidth, window.innerHeight);
  camera.aspect = window.innerWidth / window.innerHeight;
  camera.updateProjectionMatrix();
}

// A click (not a drag) shoots a box from the eye point through the clicked point.
let pressed = null;
renderer.domElement.addEventListener('pointerdown', (e) => { pressed = [e.clientX, e.clientY]; });
renderer.domElement.addEventListener('pointerup', (e) => {
  if (!pressed || Math.hypot(e.clientX - pressed[0], e.clientY - pressed[1]) > 4) return;
  const ndc = new THREE.Vector2(2 * e.clientX / window.innerWidth - 1, 1 - 2 * e.clientY / window.innerHeight);
  const ray = new THREE.Raycaster();
  ray.setFromCamera(ndc, camera);
  page.shoot(camera.position.toArray(), ray.ray.direction.toArray());
});

const page = {
  paused: false,
  shotsLeft: 12,
  settings: () => settings,
  // Changes settings as the controls would, and restarts.
  choose(values) {
    for (const [id, value] of Object.entries(values)) {
      if (typeof value === 'boolean') $(id).checked = value; else $(id).value = value;
    }
    page.restart();
  },
  restart() { page.shotsLeft = 12; start(); },
  shoot(from, direction) {
    if (demo && demo.shoot(...from, ...direction)) --page.shotsLeft;
  },
  // A shot from the current eye point towards the view's target.
  shootAtTarget() {
    const d = controls.target.clone().sub(camera.position).normalize();
    page.shoot(camera.position.toArray(), d.toArray());
  },
  // Steps n times at once and draws (for recordings; pause first so real time adds none).
  advance(n) {
    for (let k = 0; k < n && demo; ++k) step();
    draw();
  },
  time: () => (demo ? demo.time() : NaN),
  largestDisplacement: () => (demo ? demo.largestDisplacement() : NaN),
  msPerStep: () => stepTimes.reduce((s, x) => s + x, 0) / Math.max(stepTimes.length, 1),
  // The digests of a scene of its own (not the one shown) after the given step counts, one
  // shot from the pyramid's eye point along −z after `shot` steps: web_digest's arguments.
  digests(sceneName, method, shot, counts) {
    const own = new Module.Demo(sceneName, method, true, true, 'none');
    const out = [];
    let done = 0;
    for (const count of counts) {
      for (; done < count; ++done) {
        if (done === shot) own.shoot(0.5, 4.5, 12, 0, 0, -1);
        own.step();
      }
      out.push(`${done} ${own.stateDigest()}`);
    }
    own.delete();
    return out;
  },
};
window.boxsimPage = page;

for (const id of ['scene', 'method', 'sleep', 'stability', 'filter']) $(id).addEventListener('change', () => page.restart());
$('restart').addEventListener('click', () => page.restart());
window.addEventListener('resize', resize);
resize();
start();
requestAnimationFrame(frame);
