// What the browser test and the GIF recorder share: their command-line options, a static
// server for the built page, and Debian's Chromium, headless.
import { createServer } from 'node:http';
import { readFile } from 'node:fs/promises';
import { extname, join } from 'node:path';
import { chromium } from 'playwright-core';

/// The value after `--name` on the command line, or `fallback`.
export const option = (name, fallback) => {
  const i = process.argv.indexOf(`--${name}`);
  return i > 0 ? process.argv[i + 1] : fallback;
};

const types = { '.html': 'text/html', '.js': 'text/javascript', '.mjs': 'text/javascript',
                '.wasm': 'application/wasm', '.png': 'image/png' };

/// Serves the folder `site` on a free port of the loopback; resolves to { url, close }.
export async function serve(site) {
  const server = createServer(async (request, response) => {
    let path = join(site, decodeURIComponent(new URL(request.url, 'http://x').pathname));
    if (path.endsWith('/')) path = join(path, 'index.html');
    try {
      const body = await readFile(path);
      // Cross-origin isolated, as a page that times in a worker should be: Chromium then gives
      // performance.now() to 5 µs instead of 100 µs.
      response.writeHead(200, { 'Content-Type': types[extname(path)] ?? 'application/octet-stream',
                                'Cross-Origin-Opener-Policy': 'same-origin',
                                'Cross-Origin-Embedder-Policy': 'require-corp' });
      response.end(body);
    } catch {
      response.writeHead(404);
      response.end();
    }
  });
  await new Promise((done) => server.listen(0, '127.0.0.1', done));
  return { url: `http://127.0.0.1:${server.address().port}/`, close: () => server.close() };
}

/// Chromium (--chromium, default Debian's /usr/bin/chromium), headless, drawing WebGL with its
/// software rasteriser, as on a machine without a GPU.
export function launchChromium() {
  return chromium.launch({
    executablePath: option('chromium', '/usr/bin/chromium'),
    args: ['--no-sandbox', '--use-angle=swiftshader', '--enable-unsafe-swiftshader'],
  });
}
