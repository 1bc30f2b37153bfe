// Headless Chromium for the engine checks (engines/three, engines/gltf): SwiftShader
// WebGL2, no network, a throw-away profile. Each check passes its own puppeteer-core (its
// package's node_modules) and the browser path.
import { mkdtempSync, rmSync } from 'node:fs';
import { join } from 'node:path';
import { tmpdir } from 'node:os';

export async function launchChromium(puppeteer, executablePath) {
  const profile = mkdtempSync(join(tmpdir(), 'splitsum-chromium-'));
  const browser = await puppeteer.launch({
    executablePath,
    headless: true,
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
