// boxsim's interactive demo: a scene of the thesis stepped by the WebAssembly engine, or by
// Jolt or Rapier (peer_engines.js), and drawn with three.js; side by side, two engines run the
// same scene in two viewports seen from one camera, and a shot goes into both. The engines run
// in a worker (demo_worker.js), which steps at real time and posts the poses after every batch
// of steps; this page draws the latest poses at display rate and sends the worker the user's
// commands, so that a slow technique slows the simulation and not the view. window.boxsimPage
// is the interface the browser test (test/browser_test.mjs) and the browser benchmark
// (test/browser_bench.mjs) drive; its commands answer promises that settle once the worker has
// carried them out.
import * as THREE from 'three';
import { OrbitControls } from './OrbitControls.js';

const FLAG_IMMOVABLE = 1, FLAG_ASLEEP = 2, FLAG_STABLE = 4;  // demo.hpp, BodyFlag
// Where each scene is seen from (m); shots leave from the eye point.
const VIEWS = {
  pyramid: { eye: [10, 6, 15], target: [0, 3.5, 0] },
  clump: { eye: [30, 22, 38], target: [0, 6, 0] },
  die: { eye: [3, 3, 6], target: [0, 0.8, 0] },
  tower: { eye: [8, 7, 14], target: [0, 4, 0] },
  clump_ground: { eye: [14, 10, 18], target: [0, 1.5, 0] },
  pile: { eye: [14, 10, 18], target: [0, 2, 0] },
  clump1000: { eye: [45, 32, 55], target: [0, 8, 0] },
};
// What the status line calls each technique or engine.
const NAMES = { damped: 'damped', impulse: 'impulse', analytic: 'analytic',
                basic_colliding: 'basic colliding', jolt: 'Jolt', rapier: 'Rapier' };

const worker = new Worker(new URL('./demo_worker.js', import.meta.url), { type: 'module' });
const $ = (id) => document.getElementById(id);

const renderer = new THREE.WebGLRenderer({ antialias: true, preserveDrawingBuffer: true });
renderer.setPixelRatio(window.devicePixelRatio);
renderer.setScissorTest(true);
$('view').appendChild(renderer.domElement);
// A three.js scene of its own for each shown run, lit alike.
function makeScene3() {
  const scene3 = new THREE.Scene();
  scene3.background = new THREE.Color(0x2b3038);
  scene3.add(new THREE.HemisphereLight(0xffffff, 0x404040, 1.2));
  const sun = new THREE.DirectionalLight(0xffffff, 1.6);
  sun.position.set(10, 20, 8);
  scene3.add(sun);
  return scene3;
}
const camera = new THREE.PerspectiveCamera(50, 1, 0.1, 1000);
const controls = new OrbitControls(camera, renderer.domElement);
const colours = {
  ground: new THREE.Color(0x59606b), box: new THREE.Color(0xd9a441),
  stable: new THREE.Color(0x6b4a17), asleep: new THREE.Color(0x7d97b8),
};

// `views` holds, per shown run, its three.js scene and meshes. `latest` is the worker's last
// frame of the shown runs (null before the first and after an error), `drawn` the one the
// meshes show. `starting` counts restarts the worker has not yet answered: the worker answers
// in order, so frames that arrive meanwhile are of older runs.
let views = [], settings = null, latest = null, drawn = null, starting = 0;
let shotsLeft = 0, paused = false, frameTimes = [], lastFrame = performance.now();

function fail(message) {
  $('error').textContent = message;
  console.error('boxsim: ' + message);
}

// Requests to the worker, answered by id.
let nextId = 0;
const waiting = new Map();
function call(type, args = {}) {
  const id = nextId++;
  return new Promise((resolve, reject) => {
    waiting.set(id, { resolve, reject });
    worker.postMessage({ type, id, ...args });
  });
}

// A frame of the shown run to draw next.
function show(frame) {
  latest = frame;
  shotsLeft = frame.shotsLeft;
}

worker.addEventListener('message', ({ data }) => {
  if (data.type === 'frame') {
    if (starting === 0) show(data);
  } else if (data.type === 'error') {
    latest = null;
    fail(data.message);
  } else if (data.type === 'reply') {
    const { resolve, reject } = waiting.get(data.id);
    waiting.delete(data.id);
    if (data.error === undefined) resolve(data.value); else reject(new Error(data.error));
  }
});
// The worker's own failures (its script failing to load, say) reach the error line as well.
worker.addEventListener('error', (event) => {
  event.preventDefault();
  fail(event.message || 'the engine\'s worker (demo_worker.js) failed to load');
});

// Sleeping and geometric stability are switches of damped integration, the display filter is
// boxsim's: each is offered while a shown run has them (the other engines use their own).
function readSettings() {
  const method = $('method').value, right = $('right').value, shown = [method, right];
  const damped = shown.includes('damped');
  $('sleep').disabled = $('stability').disabled = !damped;
  $('filter').disabled = shown.every((m) => m === 'none' || m === 'jolt' || m === 'rapier');
  return {
    scene: $('scene').value, method, right, filter: $('filter').value,
    friction: Number($('friction').value),
    sleep: damped ? $('sleep').checked : true, stability: damped ? $('stability').checked : true,
  };
}

// Restarts the worker's run with the controls' settings and builds its boxes once it answers.
async function start() {
  settings = readSettings();
  $('error').textContent = '';
  ++starting;
  let answer = null;
  try { answer = await call('start', { settings }); } catch (error) { fail(error.message); }
  if (--starting > 0) return;  // a later restart is on its way
  for (const { meshes } of views)
    for (const mesh of meshes) { mesh.geometry.dispose(); mesh.material.dispose(); }
  views = [];
  latest = drawn = null;
  if (!answer) return;
  const { halfExtents: half, frame: first } = answer;
  for (const run of first.runs) {
    const scene3 = makeScene3(), meshes = [], flags = run.flags;
    for (let i = 0; i < flags.length; ++i) {
      const geometry = new THREE.BoxGeometry(2 * half[3 * i], 2 * half[3 * i + 1], 2 * half[3 * i + 2]);
      const ground = i === 0 && (flags[i] & FLAG_IMMOVABLE);
      const material = new THREE.MeshLambertMaterial({ color: ground ? colours.ground : colours.box });
      const mesh = new THREE.Mesh(geometry, material);
      if (!ground) mesh.add(new THREE.LineSegments(new THREE.EdgesGeometry(geometry),
                                                   new THREE.LineBasicMaterial({ color: 0x222222 })));
      scene3.add(mesh);
      meshes.push(mesh);
    }
    views.push({ scene3, meshes });
  }
  // Side by side, each half is named under it.
  const shown = [settings.method, settings.right].filter((m) => m !== 'none');
  $('labels').replaceChildren(...(shown.length > 1 ? shown : []).map((m) => {
    const label = document.createElement('div');
    label.textContent = NAMES[m] ?? m;
    return label;
  }));
  resize();
  const view = VIEWS[settings.scene];
  camera.position.set(...view.eye);
  controls.target.set(...view.target);
  controls.update();
  show(first);
  draw();
}

// Draws the latest frame, each shown run in its viewport (side by side: the left and right
// halves); the meshes move only when a new frame has arrived.
function draw() {
  if (latest && latest !== drawn) {
    views.forEach(({ meshes }, r) => {
      const { poses, flags } = latest.runs[r];
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
    });
    drawn = latest;
  }
  const width = window.innerWidth / Math.max(views.length, 1), height = window.innerHeight;
  views.forEach(({ scene3 }, r) => {
    renderer.setViewport(r * width, 0, width, height);
    renderer.setScissor(r * width, 0, width, height);
    renderer.render(scene3, camera);
  });
}

// Every display frame: the latest poses drawn, the status line. The frame rate is the page's
// own; ms/step is measured by the worker around its steps.
function frame(now) {
  requestAnimationFrame(frame);
  frameTimes.push(Math.min((now - lastFrame) / 1000, 0.25));
  lastFrame = now;
  if (frameTimes.length > 60) frameTimes.shift();
  draw();
  const mean = (a) => a.reduce((s, x) => s + x, 0) / Math.max(a.length, 1);
  const shown = settings ? [settings.method, settings.right].filter((m) => m !== 'none') : [];
  $('status').textContent = latest ?
    `t ${latest.time.toFixed(2)} s   ` +
    latest.runs.map((r, i) => `${NAMES[shown[i]] ?? shown[i]} ${r.msPerStep.toFixed(2)}`).join(', ') +
    ` ms/step\n${(1 / Math.max(mean(frameTimes), 1e-6)).toFixed(0)} fps   ${shotsLeft} shots left` : '';
}

function resize() {
  renderer.setSize(window.innerWidth, window.innerHeight);
  camera.aspect = window.innerWidth / Math.max(views.length, 1) / window.innerHeight;
  camera.updateProjectionMatrix();
}

// A click (not a drag) shoots a box from the eye point through the clicked point.
let pressed = null;
renderer.domElement.addEventListener('pointerdown', (e) => { pressed = [e.clientX, e.clientY]; });
renderer.domElement.addEventListener('pointerup', (e) => {
  if (!pressed || Math.hypot(e.clientX - pressed[0], e.clientY - pressed[1]) > 4) return;
  // Side by side, each half is a viewport of the same camera: the point within the half clicked.
  const width = window.innerWidth / Math.max(views.length, 1), x = e.clientX % width;
  const ndc = new THREE.Vector2(2 * x / width - 1, 1 - 2 * e.clientY / window.innerHeight);
  const ray = new THREE.Raycaster();
  ray.setFromCamera(ndc, camera);
  page.shoot(camera.position.toArray(), ray.ray.direction.toArray()).catch((error) => fail(error.message));
});

const page = {
  // Pausing stops the worker's clock: recordings step by advance() alone.
  get paused() { return paused; },
  set paused(value) {
    paused = Boolean(value);
    worker.postMessage({ type: 'pause', paused });
  },
  get shotsLeft() { return shotsLeft; },
  settings: () => settings,
  // Changes settings as the controls would, and restarts.
  choose(values) {
    for (const [id, value] of Object.entries(values)) {
      if (typeof value === 'boolean') $(id).checked = value; else $(id).value = value;
    }
    return page.restart();
  },
  // Settles once the worker runs the new scene (time() is then 0).
  restart: () => start(),
  // Fires a shot from `from` along `direction`; settles to whether one was left.
  async shoot(from, direction) {
    const answer = await call('shoot', { from, direction });
    if (starting === 0) shotsLeft = answer.shotsLeft;
    return answer.fired;
  },
  // A shot from the current eye point towards the view's target.
  shootAtTarget() {
    const d = controls.target.clone().sub(camera.position).normalize();
    return page.shoot(camera.position.toArray(), d.toArray());
  },
  // Steps n times at once and draws (for recordings; pause first so real time adds none).
  async advance(n) {
    const after = await call('advance', { n });
    if (after && starting === 0) show(after);
    draw();
  },
  // The latest frame's simulated time (s), and of shown run `run` (0: the left or only one,
  // 1: the right) its largest displacement (m) and the mean wall-clock time of its last 60
  // steps in the worker (ms); NaN before the first frame.
  time: () => (latest ? latest.time : NaN),
  runs: () => (latest ? latest.runs.length : 0),
  largestDisplacement: (run = 0) => (latest ? latest.runs[run].largestDisplacement : NaN),
  msPerStep: (run = 0) => (latest ? latest.runs[run].msPerStep : NaN),
  // The bodies of shown run `run` asleep by its engine's own sleeping, and its movable bodies.
  asleep: (run = 0) => {
    if (!latest) return { asleep: 0, movable: 0 };
    let asleep = 0, movable = 0;
    for (const f of latest.runs[run].flags)
      if (!(f & FLAG_IMMOVABLE)) { ++movable; if (f & FLAG_ASLEEP) ++asleep; }
    return { asleep, movable };
  },
  // One run of the browser benchmark in the worker (demo_worker.js, bench): per step its time
  // (ms), deepest penetration (m) and bodies asleep (−1: all).
  bench: (scene, method, friction, steps, shot, checkMirror = false) =>
    call('bench', { scene, method, friction, steps, shot, checkMirror }),
  // The digests of a scene of its own (not the one shown) after the given step counts, one
  // shot from the pyramid's eye point along −z after `shot` steps: web_digest's arguments.
  // Computed in the worker, which holds the shown run meanwhile.
  digests: (scene, method, shot, counts) => call('digests', { scene, method, shot, counts }),
};
window.boxsimPage = page;

for (const id of ['scene', 'method', 'right', 'friction', 'sleep', 'stability', 'filter']) $(id).addEventListener('change', () => page.restart());
$('restart').addEventListener('click', () => page.restart());
// The controls fold away, so that side by side the left view is not hidden behind them.
$('fold').addEventListener('click', () => {
  $('controls').hidden = !$('controls').hidden;
  $('fold').textContent = $('controls').hidden ? 'show' : 'hide';
});
window.addEventListener('resize', resize);
resize();
start();
requestAnimationFrame(frame);
