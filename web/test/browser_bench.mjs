// The browser benchmark: boxsim's damped integration (WebAssembly), Jolt (npm jolt-physics)
// and Rapier (npm @dimforge/rapier3d-compat) on the same scenes in the page's worker, in
// Debian's Chromium, headless; writes the Markdown page docs/web_benchmarks.md.
//
//   node web/test/browser_bench.mjs [--site build-web] [--out docs/web_benchmarks.md]
//                                   [--reps 3] [--scale 1] [--chromium /usr/bin/chromium]
//
// Every scene runs `reps` times under every engine, interleaved (engine A repetition 1, engine
// B repetition 1, ...), each run in the worker (demo_worker.js, bench), one engine at a time.
// A step's time is performance.now() around the engine's step alone (the page is cross-origin
// isolated, so Chromium gives it to 5 µs). Penetration is boxsim's separating-axis test on the
// engine's poses after every step, untimed (Demo.penetrationAt), as bench/peers measures Bullet
// and ODE. `--scale` shortens every scene (a check that the harness runs, not a benchmark).
// The page is written whole or not at all (a temporary file renamed over it).
import { execFileSync } from 'node:child_process';
import { readFileSync, renameSync, writeFileSync } from 'node:fs';
import { cpus, totalmem } from 'node:os';
import { dirname, join, resolve } from 'node:path';
import { fileURLToPath } from 'node:url';
import { launchChromium, option, serve } from './harness.mjs';

const root = resolve(dirname(fileURLToPath(import.meta.url)), '..', '..');
const site = resolve(option('site', 'build-web'));
const out = resolve(option('out', join(root, 'docs', 'web_benchmarks.md')));
const reps = Number(option('reps', '3'));
const scale = Number(option('scale', '1'));
if (!(Number.isInteger(reps) && reps >= 1) || !(scale > 0 && scale <= 1)) {
  console.error('browser_bench: --reps takes a whole number >= 1 and --scale a number in (0, 1]');
  process.exit(2);
}

const DT = 1 / 60;
const FRICTION = 0.5;
// The scenes (demo.hpp, DemoSettings::scene): simulated seconds, and the step after which the
// pyramid's shot leaves the eye point (Fig. 6.6).
const SCENES = [
  { scene: 'pyramid', label: 'pyramid10 shot at 2 s', seconds: 6, shot: 120 },
  { scene: 'clump_ground', label: 'clump100_ground', seconds: 10, shot: -1 },
  { scene: 'pile', label: 'pile343', seconds: 8, shot: -1 },
  { scene: 'clump1000', label: 'clump1000', seconds: 2, shot: -1 },
];
// The engines: each with the peers' friction, and boxsim's frictionless as the thesis beside.
const ENGINES = [
  { method: 'damped', friction: FRICTION, label: 'boxsim damped μ' },
  { method: 'jolt', friction: FRICTION, label: 'Jolt' },
  { method: 'rapier', friction: FRICTION, label: 'Rapier' },
  { method: 'damped', friction: 0, label: 'boxsim damped, frictionless (the thesis)' },
];
const BOXSIM = ENGINES[0].label, THESIS = ENGINES[3].label;

const mean = (a) => a.reduce((s, x) => s + x, 0) / a.length;
const median = (a) => {
  const s = [...a].sort((x, y) => x - y);
  return s.length % 2 ? s[(s.length - 1) / 2] : 0.5 * (s[s.length / 2 - 1] + s[s.length / 2]);
};
const ms = (v) => v.toFixed(v >= 100 ? 0 : v >= 10 ? 1 : v >= 1 ? 2 : 3);
const version = (pkg) =>
  JSON.parse(readFileSync(join(root, 'web', 'node_modules', pkg, 'package.json'), 'utf8')).version;
const git = (...args) => execFileSync('git', ['-C', root, ...args], { encoding: 'utf8' }).trim();

const server = await serve(site);
const browser = await launchChromium();
const results = new Map();  // scene label -> engine label -> { times: [[...] per rep], first }
try {
  const page = await browser.newPage({ viewport: { width: 320, height: 200 } });
  const errors = [];
  page.on('pageerror', (e) => errors.push(String(e)));
  await page.goto(server.url);
  await page.waitForFunction(() => window.boxsimPage && window.boxsimPage.time() >= 0, null,
                             { timeout: 60000 });
  // The shown run pauses: only the benchmark's runs step in the worker.
  await page.evaluate(() => { window.boxsimPage.paused = true; });
  for (const spec of SCENES) {
    const steps = Math.max(1, Math.round(spec.seconds * scale / DT));
    const shot = spec.shot >= 0 ? Math.round(spec.shot * scale) : -1;
    const byEngine = new Map(ENGINES.map((e) => [e.label, { times: [], first: null }]));
    results.set(spec.label, byEngine);
    for (let rep = 0; rep < reps; ++rep) {
      for (const engine of ENGINES) {
        const run = await page.evaluate(
          (a) => window.boxsimPage.bench(...a),
          [spec.scene, engine.method, engine.friction, steps, shot]);
        const entry = byEngine.get(engine.label);
        entry.times.push(run.times);
        if (rep === 0) entry.first = run;
        console.log(`${spec.label}, ${engine.label}, repetition ${rep + 1}: ` +
                    `${ms(mean(run.times))} ms/step`);
      }
    }
  }
  if (errors.length) throw new Error(`the page failed: ${errors.join(' | ')}`);

  // The page.
  const dirty = git('status', '--porcelain', '--', 'src', 'web').length > 0;
  const stamp = [
    `- date: ${new Date().toISOString().slice(0, 16).replace('T', ' ')} UTC`,
    `- commit: ${git('rev-parse', '--short', 'HEAD')}${dirty ? ' with uncommitted changes to src/ or web/' : ''}`,
    `- browser: Chromium ${browser.version()}, headless, WebGL by SwiftShader (the page's drawing is paused)`,
    // Package names in code spans: Doxygen, which builds these pages, reads @name as a command.
    `- packages: \`jolt-physics\` ${version('jolt-physics')}, \`@dimforge/rapier3d-compat\` ` +
      `${version('@dimforge/rapier3d-compat')}, boxsim built by Emscripten (build-web/)`,
    `- machine: ${cpus()[0]?.model ?? 'unknown'}, ${cpus().length} logical cores, ` +
      `${Math.round(totalmem() / 2 ** 30)} GiB`,
    `- command: \`node web/test/browser_bench.mjs --reps ${reps}${scale !== 1 ? ` --scale ${scale}` : ''}\``,
  ];
  const lines = [
    '# boxsim in the browser beside Jolt and Rapier', '',
    'Written by `web/test/browser_bench.mjs`; do not edit by hand. Regenerate with',
    '`cmake --build build --target web_bench` (after `cmake --workflow --preset web`).', '',
    ...stamp, '',
    '## How it is measured', '',
    `Each scene runs ${reps} times under every engine, interleaved, in the demo's Web Worker, one ` +
    'run at a time, Δt = 1/60 s, 1 kg unit cubes, the same boxes, poses, velocities, gravity and ' +
    `restitution for every engine, and Coulomb friction μ = ${FRICTION} on every body (boxsim's ` +
    'thesis-faithful frictionless damped integration in the last row of each scene). Each engine ' +
    'runs as its own documentation advises, sleeping on ([web.md](web.md) says how). A step\'s ' +
    'time is the wall-clock time of the engine\'s step alone. **Mean** ms/step is over every ' +
    'step of every repetition, the median beside it, *rep means* the range of the repetitions\' ' +
    'means (the machine\'s noise); the ratio is the row\'s mean over boxsim damped μ\'s: above 1, ' +
    'boxsim is faster. The physics is measured on the first repetition with one yardstick for ' +
    'every engine, boxsim\'s separating-axis test on the engine\'s poses after each step: ' +
    'penetration is the deepest overlap of any two boxes (ground included), averaged over the ' +
    'steps, after the last step, and the largest of any step; asleep is the boxes the engine ' +
    'holds asleep after the last step, by its own sleeping; *all asleep from* is the time from ' +
    'which every box stays asleep.', '',
    'Scenes: ' + SCENES.map((s) => `${s.label} (${s.scene}, ${(s.seconds * scale).toFixed(2)} s)`).join(', ') +
    '; demo.hpp says how each is built, as the shipped scene files of the impulse chapter.', '',
  ];
  // Per boxsim row (the like-for-like one with μ, the thesis' frictionless one), the peers it is
  // faster and slower than, scene by scene.
  const summary = new Map([[BOXSIM, { win: [], loss: [] }], [THESIS, { win: [], loss: [] }]]);
  const table = ['| scene | engine | mean ms/step | median | rep means | mean ÷ boxsim damped μ\'s | ' +
                 'penetration mean / final / max (mm) | asleep at end | all asleep from (s) |',
                 '|---|---|---|---|---|---|---|---|---|'];
  for (const spec of SCENES) {
    const byEngine = results.get(spec.label);
    const base = mean(byEngine.get(BOXSIM).times.flat());
    const meanOf = (label) => mean(byEngine.get(label).times.flat());
    for (const engine of ENGINES) {
      const { times, first } = byEngine.get(engine.label);
      const all = times.flat(), repMeans = times.map(mean), m = mean(all);
      const pen = first.penetrations, asleep = first.asleep;
      let from = asleep.length;
      while (from > 0 && asleep[from - 1] === -1) --from;
      const movable = asleep.at(-1) === -1 ? 'all' : String(asleep.at(-1));
      table.push(`| ${spec.label} | ${engine.label} | **${ms(m)}** | ${ms(median(all))} | ` +
                 `${ms(Math.min(...repMeans))}–${ms(Math.max(...repMeans))} | ` +
                 `${engine.label === BOXSIM ? '' : (m / base).toFixed(2)} | ` +
                 `${(1000 * mean(pen)).toFixed(1)} / ${(1000 * pen.at(-1)).toFixed(1)} / ` +
                 `${(1000 * Math.max(...pen)).toFixed(1)} | ${movable} | ` +
                 `${from < asleep.length ? (from * DT).toFixed(2) : 'never'} |`);
      if (engine.method !== 'damped')
        for (const [row, lists] of summary) {
          const own = meanOf(row);
          (own < m ? lists.win : lists.loss).push(
            `- ${spec.label}: ${row} ${ms(own)} ms/step, ${engine.label} ${ms(m)} ` +
            `(boxsim's mean ${(own / m).toFixed(2)}× ${engine.label}'s)`);
        }
    }
  }
  lines.push('## Summary', '');
  for (const [row, { win, loss }] of summary) {
    lines.push(`**${row} is faster than:**`, '', ...(win.length ? win : ['- none']), '',
               `**${row} is slower than:**`, '', ...(loss.length ? loss : ['- none']), '');
  }
  lines.push('The frictionless rows are not like for like: Jolt and Rapier run with μ = 0.5 there ' +
             'too, and a frictionless box slides and tumbles further.', '',
             '## Table', '', ...table, '');
  const temporary = `${out}.tmp`;
  writeFileSync(temporary, lines.join('\n'));
  renameSync(temporary, out);
  console.log(`browser_bench: wrote ${out}`);
} finally {
  await browser.close();
  server.close();
}
