// Records the GIF of the README (docs/images/web_demo.gif): the pyramid of Fig. 6.6 at rest,
// then shot from the eye point, drawn by the page of build-web/ in Debian's Chromium, frames
// joined by ImageMagick (apt-get install -y imagemagick).
//
//   node web/test/record_gif.mjs [--site build-web] [--out docs/images/web_demo.gif]
import { spawnSync } from 'node:child_process';
import { mkdtemp, rm } from 'node:fs/promises';
import { tmpdir } from 'node:os';
import { join, resolve } from 'node:path';
import { launchChromium, option, serve } from './harness.mjs';

const site = resolve(option('site', 'build-web'));
const out = resolve(option('out', 'docs/images/web_demo.gif'));
const server = await serve(site);
const browser = await launchChromium();
const frames = await mkdtemp(join(tmpdir(), 'boxsim-gif-'));
try {
  const page = await browser.newPage({ viewport: { width: 640, height: 400 } });
  await page.goto(server.url);
  await page.waitForFunction(() => window.boxsimPage && window.boxsimPage.time() >= 0);
  // Without the panel; 1 s at rest, then the shot, 4 s more: one frame drawn every 3 steps.
  await page.evaluate(() => {
    document.getElementById('panel').style.display = 'none';
    window.boxsimPage.paused = true;
    return window.boxsimPage.restart();
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
