// Records the GIF of the README (docs/images/web_demo.gif): the pyramid of Fig. 6.6 at rest,
// then shot from the eye point, drawn by the page of build-web/ in Debian's Chromium, frames
// joined by ImageMagick (apt-get install -y imagemagick).
//
//   node web/test/record_gif.mjs [--site build-web] [--out docs/images/web_demo.gif]
import { spawnSync } from 'node:child_process';
import { createServer } from 'node:http';
import { mkdtemp, readFile, rm } from 'node:fs/promises';
import { tmpdir } from 'node:os';
import { extname, join, resolve } from 'node:path';
import { chromium } from 'playwright-core';

const option = (name, fallback) => {
  const i = process.argv.indexOf(`--${name}`);
  return i > 0 ? process.argv[i + 1] : fallback;
};
const site = resolve(option('site', 'build-web'));
const out = resolve(option('out', 'docs/images/web_demo.gif'));
const types = { '.html': 'text/html', '.js': 'text/javascript', '.mjs': 'text/javascript',
                '.wasm': 'application/wasm' };
const server = createServer(async (request, response) => {
  let path = join(site, decodeURIComponent(new URL(request.url, 'http://x').pathname));
  if (path.endsWith('/')) path = join(path, 'index.html');
  try {
    const body = await readFile(path);
    response.writeHead(200, { 'Content-Type': types[extname(path)] ?? 'application/octet-stream' });
    response.end(body);
  } catch {
    response.writeHead(404);
    response.end();
  }
});
await new Promise((done) => server.listen(0, '127.0.0.1', done));
const browser = await chromium.launch({
  executablePath: option('chromium', '/usr/bin/chromium'),
  args: ['--no-sandbox', '--use-angle=swiftshader', '--enable-unsafe-swiftshader'],
});
const frames = await mkdtemp(join(tmpdir(), 'boxsim-gif-'));
try {
  const page = await browser.newPage({ viewport: { width: 640, height: 400 } });
  await page.goto(`http://127.0.0.1:${server.address().port}/`);
  await page.waitForFunction(() => window.boxsimPage && window.boxsimPage.time() >= 0);
  // Without the panel; 1 s at rest, then the shot, 4 s more: one frame drawn every 3 steps.
  await page.evaluate(() => {
    document.getElementById('panel').style.display = 'none';
    window.boxsimPage.paused = true;
    window.boxsimPage.restart();
  });
  let index = 0;
  const capture = () => page.screenshot({ path: join(frames, `${String(index++).padStart(4, '0')}.png`) });
  for (let k = 0; k < 20; ++k) { await page.evaluate(() => window.boxsimPage.advance(3)); await capture(); }
  await page.evaluate(() => window.boxsimPage.shootAtTarget());
  for (let k = 0; k < 80; ++k) { await page.evaluate(() => window.boxsimPage.advance(3)); await capture(); }
  const convert = spawnSync('convert', ['-delay', '5', '-loop', '0', join(frames, '*.png'),
                                        '-layers', 'Optimize', out], { encoding: 'utf8' });
  if (convert.status !== 0) throw new Error(`convert failed: ${convert.stderr}`);
  console.log(`wrote ${out}`);
} finally {
  await browser.close();
  server.close();
  await rm(frames, { recursive: true, force: true });
}
