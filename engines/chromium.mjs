// Headless Chromium for the engine checks (engines/three, engines/gltf): SwiftShader
// WebGL2, no network, a throw-away profile. Each check passes its own puppeteer-core (its
// package's node_modules) and the browser path, serves the repository to the page with
// serveFiles and collects the page's console problems with watchConsole.
import { mkdtempSync, rmSync, existsSync, readFileSync } from 'node:fs';
import { createServer } from 'node:http';
import { extname, join, normalize } from 'node:path';
import { tmpdir } from 'node:os';

export async function launchChromium(puppeteer, executablePath) {
  const profile = mkdtempSync(join(tmpdir(), 'splitsum-chromium-'));
  const browser = await puppeteer.launch({
    executablePath,
    headless: true,
    // SwiftShader is slow: a page's filtering (the glTF viewer's run-time IBL) can take
    // minutes within one call.
    protocolTimeout: 900000,
    args: [
      '--headless=new', '--use-angle=swiftshader', '--enable-unsafe-swiftshader', '--no-sandbox',
      '--no-first-run', '--disable-background-networking', '--disable-component-update',
      '--disable-sync', '--disable-quic', `--user-data-dir=${profile}`,
    ],
  });
  const close = async () => {
    await browser.close();
    rmSync(profile, { recursive: true, force: true });
  };
  return { browser, close };
}

// ANGLE forwards the GL driver's debug messages to the page console as warnings. Those the
// driver files under "Performance" (for example "GPU stall due to ReadPixels", which comes
// or not with timing on the same page) are advice about speed, not errors; every other
// warning or error, and every uncaught page error, is a problem that fails a check.
const PERFORMANCE_NOTICE = /^\[[^\]]*\]GL Driver Message \([^,]*, Performance,/;

export function isPerformanceNotice(text) {
  return PERFORMANCE_NOTICE.test(text);
}

export function watchConsole(page) {
  const problems = [];
  page.on('console', (m) => {
    const type = m.type();
    if ((type === 'error' || type === 'warn' || type === 'warning') && !isPerformanceNotice(m.text())) {
      problems.push(`${type}: ${m.text()}`);
    }
  });
  page.on('pageerror', (e) => problems.push(`page error: ${e.message}`));
  return problems;
}

const TYPES = {
  '.html': 'text/html', '.js': 'text/javascript', '.mjs': 'text/javascript',
  '.json': 'application/json', '.wasm': 'application/wasm',
};

// Serves the files under `root` on 127.0.0.1 (an ephemeral port) until close().
export async function serveFiles(root) {
  const server = createServer((req, res) => {
    const path = normalize(decodeURIComponent(new URL(req.url, 'http://x').pathname));
    const file = join(root, path);
    if (!file.startsWith(root) || !existsSync(file)) {
      res.writeHead(404).end();
      return;
    }
    res.writeHead(200, { 'content-type': TYPES[extname(file)] ?? 'application/octet-stream' });
    res.end(readFileSync(file));
  });
  await new Promise((ok) => server.listen(0, '127.0.0.1', ok));
  return { port: server.address().port, close: () => server.close() };
}
