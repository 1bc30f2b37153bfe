// A README engine recipe, run as written: the shell lines and the js block under the
// README heading `### <heading>`. The shell lines run in a fresh folder holding the bundled
// venice_sunset HDRI as `sky.hdr` (`splitsum` is the binary under test); the js block is
// written, unchanged, between the check's `prelude` (what the README takes as given: the
// engine's renderer or engine and its scene) and `epilogue` (which renders with what the
// recipe set up and sets `window.recipeResult`) into recipe.js, next to an index.html
// holding `head` (the engine's scripts), in the folder the bake command's `-o` names, so
// that the recipe's relative URLs (`sky/…`) resolve as they would on the user's site.
import { execFileSync } from 'node:child_process';
import { copyFileSync, mkdirSync, readFileSync, rmSync, writeFileSync } from 'node:fs';
import { join, relative } from 'node:path';

// The sh and js blocks under `### heading`, up to the next heading.
export function readmeRecipe(root, heading) {
  const readme = readFileSync(join(root, 'README.md'), 'utf8');
  const start = readme.indexOf(`\n### ${heading}`);
  if (start < 0) throw new Error(`README.md has no heading '### ${heading}'`);
  const rest = readme.slice(start + 1);
  const next = rest.slice(4).search(/\n##/);
  const section = next < 0 ? rest : rest.slice(0, next + 4);
  const blocks = { sh: [], js: [] };
  let lang = null;
  for (const line of section.split('\n')) {
    if (line.startsWith('```')) {
      lang = lang === null ? line.slice(3).trim() : null;
      if (lang !== null) blocks[lang]?.push([]);
      continue;
    }
    if (lang !== null) blocks[lang]?.at(-1).push(line);
  }
  if (blocks.js.length !== 1) throw new Error(`'### ${heading}': ${blocks.js.length} js blocks, not one`);
  const commands = blocks.sh.flat().map((l) => l.replace(/#.*$/, '').trim()).filter((l) => l.length > 0);
  return { commands, code: blocks.js[0].join('\n') };
}

// Runs the recipe under `heading` in `browser` (a launched Chromium) against the
// repository served at `port`, writing under `dir`; `files` are copied next to recipe.js
// ([repository path, name]). Returns { result, problems }: window.recipeResult and the
// page's console problems; throws when the page fails or sets no result.
export async function runRecipe({ browser, watchConsole, root, port, splitsum, dir, heading, head, prelude, epilogue, files = [] }) {
  const { commands, code } = readmeRecipe(root, heading);
  rmSync(dir, { recursive: true, force: true });
  mkdirSync(dir, { recursive: true });
  copyFileSync(join(root, 'tests/data/venice_sunset_1k.hdr'), join(dir, 'sky.hdr'));
  let site = null;
  for (const command of commands) {
    const [program, ...args] = command.split(/\s+/);
    if (program !== 'splitsum') throw new Error(`'### ${heading}': '${command}' does not run splitsum`);
    execFileSync(splitsum, args, { cwd: dir, stdio: ['ignore', 'ignore', 'inherit'] });
    const o = args.indexOf('-o');
    if (args[0] === 'bake' && o >= 0) site = join(dir, args[o + 1]);
  }
  if (site === null) throw new Error(`'### ${heading}': no 'splitsum bake … -o DIR' line`);
  for (const [from, name] of files) copyFileSync(join(root, from), join(site, name));
  writeFileSync(join(site, 'recipe.js'), `${prelude}\n// --- README.md, "### ${heading}", as written ---\n${code}\n// --- end of the README's code ---\n${epilogue}\n`);
  writeFileSync(join(site, 'index.html'), `<!doctype html>
<html>
<head>
<meta charset="utf-8">
<title>README recipe: ${heading}</title>
<link rel="icon" href="data:,">
${head}
<script type="module" src="recipe.js"></script>
</head>
<body style="margin:0;background:#000"></body>
</html>
`);
  const page = await browser.newPage();
  const problems = watchConsole(page);
  await page.goto(`http://127.0.0.1:${port}/${relative(root, site)}/index.html`);
  const started = Date.now();
  while (!(await page.evaluate(() => window.recipeResult !== undefined))) {
    const failure = problems.find((p) => p.startsWith('page error'));
    if (failure) throw new Error(`the '${heading}' recipe failed: ${failure}`);
    if (Date.now() - started > 300000) throw new Error(`the '${heading}' recipe set no result in 300 s: ${problems.join('; ')}`);
    await new Promise((ok) => setTimeout(ok, 200));
  }
  const result = await page.evaluate(() => window.recipeResult);
  await page.close();
  return { result, problems };
}

// The verdict on a page's measure.recipeReport: the recipe's environment lights the sphere
// (which is black without it) and the sky shows.
export function judgeRecipe(r, { bad }) {
  const lit = Number.isFinite(r.sphere) && r.sphere > 1e-3 && r.sphereUnlit < 1e-4;
  const sky = Number.isFinite(r.sky) && r.sky > 1e-3;
  bad(lit && sky,
    `the README's code, as written, lights a white sphere (mean luminance ${r.sphere.toFixed(4)}, ${r.sphereUnlit.toFixed(4)} without its environment) and shows the sky (${r.sky.toFixed(4)} in the corners)`);
}
