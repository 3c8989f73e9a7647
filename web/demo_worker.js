// The demo's engine, on a thread of its own: a module worker that owns the WebAssembly engine
// (boxsim_demo.mjs, built from demo.cpp) and the Demo the page shows (demo.js). It steps the
// Demo at real time, as many 1/60 s steps as the clock asks, at most 4 a batch, and posts each
// batch's poses back for the page to draw. A technique slower than real time (basic colliding
// on the pyramid: a few hundred milliseconds a step) then slows the simulation only; the page
// keeps drawing and answering clicks and drags at display rate.
//
// Messages from the page are { type, id, ...arguments }: 'start' (settings), 'shoot' (from,
// direction), 'pause' (paused), 'advance' (n) and 'digests' (scene, method, shot, counts). They
// are handled in order between batches of steps. One with an id is answered by { type: 'reply',
// id, value } or { type: 'reply', id, error }. Unasked, the worker posts a frame,
// { type: 'frame', time, poses, flags, msPerStep, largestDisplacement, shotsLeft }, after every
// batch, and { type: 'error', message } when a step throws; the shown run then ends.
import createBoxsim from './boxsim_demo.mjs';

const DT = 1 / 60;  // s
const BATCH = 4;    // steps a batch at most: a slow technique runs in slow motion, not behind

const ready = createBoxsim();
let Module = null, demo = null, paused = false;
// Wall-clock time of every recent step (ms) and simulated time owed to the clock (s).
let stepTimes = [], owed = 0, last = performance.now();

// The message of an error: a C++ exception reaches JavaScript as the pointer to it.
const messageOf = (error) =>
  typeof error === 'number' && Module ? Module.exceptionMessage(error) : String(error?.message ?? error);

// The shown run's state after its last step: poses and flags are copies (the engine's views
// into its memory are valid only until the next step), transferred with the message.
function frame() {
  return {
    type: 'frame', time: demo.time(), poses: demo.poses().slice(),
    flags: Uint8Array.from(demo.flags()),
    msPerStep: stepTimes.reduce((s, x) => s + x, 0) / Math.max(stepTimes.length, 1),
    largestDisplacement: demo.largestDisplacement(), shotsLeft: demo.shotsLeft(),
  };
}
const transfers = (f) => (f ? [f.poses.buffer, f.flags.buffer] : []);

// The shown run ends at an error; the page reports it.
function stop(error) {
  const message = messageOf(error);
  if (demo) demo.delete();
  demo = null;
  self.postMessage({ type: 'error', message });
}

// One step of the shown run, timed; false when it threw.
function step() {
  const t0 = performance.now();
  try { demo.step(); } catch (error) { stop(error); return false; }
  stepTimes.push(performance.now() - t0);
  if (stepTimes.length > 60) stepTimes.shift();
  return true;
}

// A batch: the steps real time asks for since the last batch. A step slower than real time ends
// its batch, and the time owed is capped at a batch, so that the run does not try to catch up
// with a clock it cannot keep. The next batch is due when another step is owed; commands from
// the page are handled in between.
function tick() {
  const now = performance.now();
  const elapsed = Math.min((now - last) / 1000, 0.25);
  last = now;
  if (demo && !paused) {
    owed += elapsed;
    let stepped = false;
    for (let n = 0; owed >= DT && n < BATCH; ++n) {
      if (!step()) break;
      stepped = true;
      owed -= DT;
      if (stepTimes[stepTimes.length - 1] > 1000 * DT) break;  // slower than real time
    }
    owed = Math.min(owed, BATCH * DT);
    if (stepped && demo) {
      const f = frame();
      self.postMessage(f, transfers(f));
    }
  }
  setTimeout(tick, demo && !paused ? Math.max(0, 1000 * (DT - owed)) : 1000 * DT);
}

const commands = {
  // A new shown run; answers the half extents of its bodies and its first frame.
  start({ settings: s }) {
    if (demo) demo.delete();
    demo = null;
    stepTimes = []; owed = 0;
    demo = new Module.Demo(s.scene, s.method, s.sleep, s.stability, s.filter);
    const halfExtents = Float64Array.from(demo.halfExtents()), f = frame();
    return { value: { halfExtents, frame: f }, transfer: [halfExtents.buffer, ...transfers(f)] };
  },
  // Fires the next shot at the next step; answers whether there was one left.
  shoot({ from, direction }) {
    const fired = Boolean(demo && demo.shoot(...from, ...direction));
    return { value: { fired, shotsLeft: demo ? demo.shotsLeft() : 0 } };
  },
  pause({ paused: value }) {
    paused = value;
    owed = 0;
    return { value: paused };
  },
  // Steps n times at once (for recordings; pause first so real time adds none); answers the
  // frame after them, or null when there is no run.
  advance({ n }) {
    for (let k = 0; k < n && demo; ++k) step();
    const f = demo ? frame() : null;
    return { value: f, transfer: transfers(f) };
  },
  // The digests of a scene of its own (not the one shown) after the given step counts, one
  // shot from the pyramid's eye point along −z after `shot` steps: web_digest's arguments.
  // The shown run waits meanwhile.
  digests({ scene, method, shot, counts }) {
    const own = new Module.Demo(scene, method, true, true, 'none');
    const out = [];
    try {
      let done = 0;
      for (const count of counts) {
        for (; done < count; ++done) {
          if (done === shot) own.shoot(0.5, 4.5, 12, 0, 0, -1);
          own.step();
        }
        out.push(`${done} ${own.stateDigest()}`);
      }
    } finally {
      own.delete();
    }
    last = performance.now();  // the wait is no time owed to the shown run
    return { value: out };
  },
};

// Commands wait for the engine to load; each awaits the same promise, so they keep their order.
self.onmessage = async ({ data: { type, id, ...args } }) => {
  try {
    Module ??= await ready;
    const { value, transfer = [] } = commands[type](args);
    if (id !== undefined) self.postMessage({ type: 'reply', id, value }, transfer);
  } catch (error) {
    if (id !== undefined) self.postMessage({ type: 'reply', id, error: messageOf(error) });
    else self.postMessage({ type: 'error', message: messageOf(error) });
  }
};
// Whatever else throws here (the engine failing to load, say) reaches the page's error line.
self.addEventListener('unhandledrejection', (event) => {
  event.preventDefault();
  self.postMessage({ type: 'error', message: messageOf(event.reason) });
});
tick();
