// The demo's engines, on a thread of their own: a module worker that owns the WebAssembly
// engine (boxsim_demo.mjs, built from demo.cpp), the other engines of the page
// (peer_engines.js: Jolt and Rapier, loaded when first chosen) and the runs the page shows
// (demo.js): one, or two side by side on the same scene, stepped together. It steps them at
// real time, as many 1/60 s steps as the clock asks, at most 4 a batch, and posts each batch's
// poses back for the page to draw. A technique slower than real time (basic colliding on the
// pyramid: a few hundred milliseconds a step) then slows the simulation only; the page keeps
// drawing and answering clicks and drags at display rate.
//
// Messages from the page are { type, id, ...arguments }: 'start' (settings), 'shoot' (from,
// direction), 'pause' (paused), 'advance' (n), 'digests' (scene, method, shot, counts) and
// 'bench' (scene, method, friction, steps, shot). They are handled in order between batches of
// steps. One with an id is answered by { type: 'reply', id, value } or { type: 'reply', id,
// error }. Unasked, the worker posts a frame, { type: 'frame', time, shotsLeft, runs: [{ poses,
// flags, msPerStep, largestDisplacement }, ...] }, after every batch, and { type: 'error',
// message } when a step throws; the shown runs then end.
import createBoxsim from './boxsim_demo.mjs';
import { PEER_ENGINES, makePeerRun } from './peer_engines.js';

const DT = 1 / 60;  // s
const BATCH = 4;    // steps a batch at most: a slow technique runs in slow motion, not behind
// The shot of Fig. 6.6 (pyramid10_shot.json): from the eye point (0.5, 4.5, 12) m along −z,
// as web_digest fires it.
const FIG66_SHOT = [0.5, 4.5, 12, 0, 0, -1];

const ready = createBoxsim();
let Module = null, paused = false;
// The shown runs, each { run, stepTimes } with the wall-clock time of its recent steps (ms);
// simulated time owed to the clock (s).
let runs = [], owed = 0, last = performance.now();

// The message of an error: a C++ exception reaches JavaScript as the pointer to it.
const messageOf = (error) =>
  typeof error === 'number' && Module ? Module.exceptionMessage(error) : String(error?.message ?? error);

// A run of `method` on the settings' scene: a boxsim Demo, or another engine's run with the
// same interface. Sleeping, geometric stability and the display filter are boxsim's: the other
// techniques and engines run with their own defaults.
async function makeRun(method, s) {
  if (PEER_ENGINES.includes(method)) return makePeerRun(method, Module, s.scene, s.friction);
  const damped = method === 'damped';
  return new Module.Demo(s.scene, method, damped ? s.sleep : true, damped ? s.stability : true,
                         s.filter, s.friction);
}

// The shown runs' state after their last step: poses and flags are copies (the engine's views
// into its memory are valid only until the next step), transferred with the message.
function frame() {
  const mean = (a) => a.reduce((s, x) => s + x, 0) / Math.max(a.length, 1);
  return {
    type: 'frame', time: runs[0].run.time(), shotsLeft: runs[0].run.shotsLeft(),
    runs: runs.map(({ run, stepTimes }) => ({
      poses: run.poses().slice(), flags: Uint8Array.from(run.flags()),
      msPerStep: mean(stepTimes), largestDisplacement: run.largestDisplacement(),
    })),
  };
}
const transfers = (f) => (f ? f.runs.flatMap((r) => [r.poses.buffer, r.flags.buffer]) : []);

function endRuns() {
  for (const { run } of runs) run.delete();
  runs = [];
}

// The shown runs end at an error; the page reports it.
function stop(error) {
  const message = messageOf(error);
  endRuns();
  self.postMessage({ type: 'error', message });
}

// One step of every shown run, each timed; false when one threw.
function step() {
  for (const r of runs) {
    const t0 = performance.now();
    try { r.run.step(); } catch (error) { stop(error); return false; }
    r.stepTimes.push(performance.now() - t0);
    if (r.stepTimes.length > 60) r.stepTimes.shift();
  }
  return true;
}

// A batch: the steps real time asks for since the last batch. A step slower than real time ends
// its batch, and the time owed is capped at a batch, so that the runs do not try to catch up
// with a clock they cannot keep. The next batch is due when another step is owed; commands
// from the page are handled in between.
function tick() {
  const now = performance.now();
  const elapsed = Math.min((now - last) / 1000, 0.25);
  last = now;
  if (runs.length && !paused) {
    owed += elapsed;
    let stepped = false;
    for (let n = 0; owed >= DT && n < BATCH; ++n) {
      const t0 = performance.now();
      if (!step()) break;
      stepped = true;
      owed -= DT;
      if (performance.now() - t0 > 1000 * DT) break;  // slower than real time
    }
    owed = Math.min(owed, BATCH * DT);
    if (stepped && runs.length) {
      const f = frame();
      self.postMessage(f, transfers(f));
    }
  }
  setTimeout(tick, runs.length && !paused ? Math.max(0, 1000 * (DT - owed)) : 1000 * DT);
}

// The measures of the browser benchmark for one run of `scene` under `method`: the wall-clock
// time of each step (ms), and after each step, untimed, the deepest penetration (boxsim's
// separating-axis test on the run's poses, m), the movable bodies asleep and whether all are,
// and the poses after the last step;
// one shot from the pyramid's eye point along −z after `shot` steps (never when negative).
// With `checkMirror`, a boxsim run also measures itself as the other engines are measured, at
// its poses (Demo.penetrationAt), and answers the largest difference from its own measure
// (mirrorGap, m): the yardstick is the same for every engine.
async function bench({ scene, method, friction, steps, shot, checkMirror = false }) {
  const run = await makeRun(method, { scene, friction, sleep: true, stability: true, filter: 'none' });
  const times = [], penetrations = [], asleep = [];
  let mirrorGap = 0, poses = null;
  try {
    for (let k = 0; k < steps; ++k) {
      if (k === shot) run.shoot(...FIG66_SHOT);
      const t0 = performance.now();
      run.step();
      times.push(performance.now() - t0);
      penetrations.push(run.penetration());
      if (checkMirror && run.penetrationAt)
        mirrorGap = Math.max(mirrorGap, Math.abs(run.penetrationAt(run.poses()) - penetrations.at(-1)));
      const flags = run.flags();
      let sleeping = 0, movable = 0;
      for (const f of flags) if (!(f & 1)) { ++movable; if (f & 2) ++sleeping; }
      asleep.push(movable > 0 && sleeping === movable ? -1 : sleeping);
    }
    // The poses after the last step (7 a body, as poses() gives them), copied before the run goes.
    poses = run.poses().slice();
  } finally {
    run.delete();
  }
  return { times, penetrations, asleep, mirrorGap, poses };
}

const commands = {
  // New shown runs: settings.method, and settings.right beside it unless 'none'; answers the
  // half extents of their bodies (the same scene: the same boxes) and their first frame.
  async start({ settings: s }) {
    endRuns();
    owed = 0;
    // Built apart and shown together: the clock steps no run while another is being built.
    const built = [];
    try {
      for (const method of s.right && s.right !== 'none' ? [s.method, s.right] : [s.method])
        built.push({ run: await makeRun(method, s), stepTimes: [] });
    } catch (error) {
      for (const { run } of built) run.delete();
      throw error;
    }
    runs = built;
    const halfExtents = Float64Array.from(runs[0].run.halfExtents()), f = frame();
    last = performance.now();  // building the runs is no time owed
    return { value: { halfExtents, frame: f }, transfer: [halfExtents.buffer, ...transfers(f)] };
  },
  // Fires the next shot into every shown run at the next step; answers whether there was one
  // left.
  shoot({ from, direction }) {
    let fired = false;
    for (const { run } of runs) fired = Boolean(run.shoot(...from, ...direction)) || fired;
    return { value: { fired, shotsLeft: runs.length ? runs[0].run.shotsLeft() : 0 } };
  },
  pause({ paused: value }) {
    paused = value;
    owed = 0;
    return { value: paused };
  },
  // Steps n times at once (for recordings; pause first so real time adds none); answers the
  // frame after them, or null when there is no run.
  advance({ n }) {
    for (let k = 0; k < n && runs.length; ++k) step();
    const f = runs.length ? frame() : null;
    return { value: f, transfer: transfers(f) };
  },
  // The digests of a scene of its own (not the one shown) after the given step counts, one
  // shot from the pyramid's eye point along −z after `shot` steps: web_digest's arguments.
  // The shown runs wait meanwhile.
  digests({ scene, method, shot, counts }) {
    const own = new Module.Demo(scene, method, true, true, 'none', 0);
    const out = [];
    try {
      let done = 0;
      for (const count of counts) {
        for (; done < count; ++done) {
          if (done === shot) own.shoot(...FIG66_SHOT);
          own.step();
        }
        out.push(`${done} ${own.stateDigest()}`);
      }
    } finally {
      own.delete();
    }
    last = performance.now();  // the wait is no time owed to the shown runs
    return { value: out };
  },
  // One run of the browser benchmark (bench() above); the shown runs wait meanwhile.
  async bench(args) {
    const value = await bench(args);
    last = performance.now();
    return { value };
  },
};

// Commands wait for the engine to load and for each other: each is chained after the last, so
// they keep their order even when one awaits an engine's module.
let queue = Promise.resolve();
self.onmessage = ({ data: { type, id, ...args } }) => {
  queue = queue.then(async () => {
    try {
      Module ??= await ready;
      const { value, transfer = [] } = await commands[type](args);
      if (id !== undefined) self.postMessage({ type: 'reply', id, value }, transfer);
    } catch (error) {
      if (id !== undefined) self.postMessage({ type: 'reply', id, error: messageOf(error) });
      else self.postMessage({ type: 'error', message: messageOf(error) });
    }
  });
};
// Whatever else throws here (the engine failing to load, say) reaches the page's error line.
self.addEventListener('unhandledrejection', (event) => {
  event.preventDefault();
  self.postMessage({ type: 'error', message: messageOf(event.reason) });
});
tick();
