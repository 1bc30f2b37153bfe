// Headless Chromium for the engine checks (engines/three, filament, babylon, gltf):
// SwiftShader WebGL2, no network, a throw-away profile. Each check passes its own
// puppeteer-core (its package's node_modules) and the browser path to runEngineCheck, which
// serves the repository to the page (serveFiles) and collects the page's console problems
// (watchConsole); the glTF LUT run uses the pieces directly.
import { mkdtempSync, rmSync, existsSync, readFileSync, writeFileSync } from 'node:fs';
import { createServer } from 'node:http';
import { extname, join, normalize } from 'node:path';
import { tmpdir } from 'node:os';
import { runRecipe } from './recipe.mjs';

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

// Exits with 2 when a tool a check needs is missing: `tools` is [[name, path], …].
export function requireTools(tools) {
  for (const [what, path] of tools) {
    if (!existsSync(path)) {
      console.error(`error: ${what} not found at ${path}`);
      process.exit(2);
    }
  }
}

// Runs an engine check page: serves `root`, opens `page` (a path under it) in headless
// Chromium with `puppeteer`, waits for window.checkReady, and for each of `cases` calls
// window.runCheck(config(case)), saves the images it returns as <case>_<name>.png in `out`
// (and its `raw` files, base64 strings, as <case>_<name>, for checks run after this one)
// and hands the result to judge(result, { bad, note }): bad(ok, text) prints an ok or FAIL
// line that fails the check, note(ok, text) an ok or info line that does not. Then the
// console must be clean; writes results.json with `bars` and exits (1 on a failure).
// `recipe` (optional): the README's recipe for the engine, run first as written
// (recipe.mjs: { heading, head, prelude, epilogue, files, splitsum } and judge(result,
// { bad, note }) as above), its page's console held to the same rule.
export async function runEngineCheck({ puppeteer, chromium, root, page: pagePath, out, cases, config, judge, bars, recipe }) {
  const server = await serveFiles(root);
  const { browser, close } = await launchChromium(puppeteer, chromium);
  let recipeProblems = [];
  let pageProblems = [];
  let failed = false;
  const results = {};
  const lineFor = (name) => ({
    bad: (ok, text) => {
      console.log(`${ok ? 'ok  ' : 'FAIL'} ${name}: ${text}`);
      if (!ok) failed = true;
    },
    note: (ok, text) => console.log(`${ok ? 'ok  ' : 'info'} ${name}: ${text}`),
    name,
  });
  try {
    if (recipe) {
      const { result, problems } = await runRecipe({
        browser, watchConsole, root, port: server.port, dir: join(out, 'recipe'), ...recipe,
      });
      results.readmeRecipe = result;
      recipeProblems = problems.map((p) => `README recipe: ${p}`);
      recipe.judge(result, lineFor('README recipe'));
    }
    const page = await browser.newPage();
    pageProblems = watchConsole(page);
    await page.goto(`http://127.0.0.1:${server.port}${pagePath}`);
    await page.waitForFunction('window.checkReady === true', { timeout: 120000 });
    for (const c of cases) {
      const { out: r, images, raw = {} } = await page.evaluate((cfg) => window.runCheck(cfg), config(c));
      results[c] = r;
      for (const [name, url] of Object.entries(images)) {
        writeFileSync(join(out, `${c}_${name}.png`), Buffer.from(url.split(',')[1], 'base64'));
      }
      for (const [name, base64] of Object.entries(raw)) {
        writeFileSync(join(out, `${c}_${name}`), Buffer.from(base64, 'base64'));
      }
      judge(r, lineFor(c));
    }
  } finally {
    await close();
    server.close();
  }
  const consoleProblems = [...recipeProblems, ...pageProblems];
  if (consoleProblems.length > 0) {
    failed = true;
    console.log('FAIL console:\n  ' + consoleProblems.join('\n  '));
  } else {
    console.log('ok   no console errors or warnings');
  }
  writeFileSync(join(out, 'results.json'), JSON.stringify({ bars, results, consoleProblems }, null, 2));
  console.log(`renders and results.json in ${out}`);
  process.exit(failed ? 1 : 0);
}
