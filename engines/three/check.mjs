// The three.js engine check: bakes the bundled HDRIs with `splitsum bake --target three`
// (rgba16f, BC6H: the `_bc6h` cases, ASTC HDR 4×4: the `_astc` cases), renders them in three.js r187 (npm three 0.187.0) in headless Chromium (SwiftShader
// WebGL2) with js/splitsum-three.js and built-in materials, and compares against three's
// own path for the same HDRI (HDRLoader as float, equirect background, run-time PMREM).
//
//   cd engines/three && npm ci && node check.mjs
//
// Environment: SPLITSUM (the binary; default ../../target/release/splitsum), CHROMIUM
// (default /usr/bin/chromium). A BC6H case renders where the WebGL context exposes
// EXT_texture_compression_bptc and is reported as not run otherwise; an ASTC case renders
// where WEBGL_compressed_texture_astc lists the "hdr" profile, and otherwise checks what a
// page gets there: the loader's error naming the extension, and pickSplitsumBake choosing
// the rgba16f bake. Writes renders and
// results.json to
// ../../target/engines/three/. Exits 1 when a bar is missed or the console shows a WebGL
// error or warning.
import { execFileSync } from 'node:child_process';
import { mkdirSync } from 'node:fs';
import { join, resolve, dirname } from 'node:path';
import { fileURLToPath } from 'node:url';
import puppeteer from 'puppeteer-core';
import { requireTools, runEngineCheck } from '../chromium.mjs';
import { judgeRecipe } from '../recipe.mjs';

const here = dirname(fileURLToPath(import.meta.url));
const root = resolve(here, '../..');
const out = join(root, 'target/engines/three');
const splitsum = process.env.SPLITSUM ?? join(root, 'target/release/splitsum');
const chromium = process.env.CHROMIUM ?? '/usr/bin/chromium';

// The bars (docs/engines.md, "three.js"): the sun within 1° of three's own path, spheres
// within 5 % of three's PMREM in mean brightness with correlation ≥ 0.98.
const BARS = { sunDegrees: 1, brightness: 0.05, correlation: 0.98 };
const ROUGHNESS = [0.25, 0.5, 1];
const HDRIS = ['quarry_01_1k', 'venice_sunset_1k'];
// The sun bars (docs/engines.md, "The sun as a light"): a diffuse sphere under the residual
// IBL plus the sun light within 3 % of the full IBL on its lit and shaded sides; the
// shadow's centre within 2° of the azimuth the sun's direction puts it at.
const SUN_HDRI = 'quarry_01_1k';
const SUN_BARS = { sides: 0.03, shadowDegrees: 2 };

requireTools([['splitsum', splitsum], ['chromium', chromium]]);

mkdirSync(out, { recursive: true });
execFileSync(
  splitsum,
  ['bake', ...HDRIS.map((h) => `tests/data/${h}.hdr`), '--target', 'three', '-q', '-o', 'target/engines/three/bakes'],
  { cwd: root, stdio: 'inherit' },
);
// The block formats, each into bakes_<suffix>.
const BLOCK_CASES = { bc6h: 'bc6h', astc: 'astc-4x4-hdr' };
for (const [suffix, format] of Object.entries(BLOCK_CASES)) {
  execFileSync(
    splitsum,
    ['bake', ...HDRIS.map((h) => `tests/data/${h}.hdr`), '--target', 'three', '--pixel-format', format, '-q', '-o', `target/engines/three/bakes_${suffix}`],
    { cwd: root, stdio: 'inherit' },
  );
}
// A studio's lamps as area lights: studio_small_03 split (its lamps as RectAreaLights) and
// kept, for tests/engine_renders.rs to hold against the truth.
const STUDIO_HDRI = 'studio_small_03_1k';
for (const mode of ['split', 'keep']) {
  execFileSync(
    splitsum,
    ['bake', `tests/data/${STUDIO_HDRI}.hdr`, '--target', 'three', '--sun', mode, '-q', '-o', `target/engines/three/studio_${mode}`],
    { cwd: root, stdio: 'inherit' },
  );
}
// The sun as a light: quarry_01 with its sun split out.
execFileSync(
  splitsum,
  ['bake', `tests/data/${SUN_HDRI}.hdr`, '--target', 'three', '--sun', 'split', '-q', '-o', 'target/engines/three/bakes_split'],
  { cwd: root, stdio: 'inherit' },
);
for (const h of HDRIS) {
  execFileSync(
    splitsum,
    ['cubemap', `tests/data/${h}.hdr`, '--target', 'three', '--size', '256', '-o', `target/engines/three/bakes/${h}_cube.ktx2`],
    { cwd: root, stdio: 'inherit' },
  );
}

// The README's three.js recipe as written, given what it takes as given (a renderer and a
// scene), then a white sphere rendered with and without the environment it set.
const recipe = {
  splitsum,
  heading: 'three.js',
  head: `<script type="importmap">
{ "imports": {
    "three": "/engines/three/node_modules/three/build/three.module.js",
    "three/addons/": "/engines/three/node_modules/three/examples/jsm/"
} }
</script>`,
  files: [['js/splitsum-three.js', 'splitsum-three.js']],
  prelude: `import * as THREE from 'three';
import * as measure from '/engines/measure.js';
const renderer = new THREE.WebGLRenderer({ antialias: false });
renderer.toneMapping = THREE.NoToneMapping;
const scene = new THREE.Scene();`,
  epilogue: `{
  const size = 64;
  scene.add(new THREE.Mesh(new THREE.SphereGeometry(1, 64, 32), new THREE.MeshStandardMaterial({ color: 0xffffff, roughness: 0.5 })));
  const camera = new THREE.PerspectiveCamera(measure.SPHERE_FOV, 1, 0.1, 100);
  camera.position.set(0, 0, measure.SPHERE_DISTANCE);
  camera.lookAt(0, 0, 0);
  const target = new THREE.WebGLRenderTarget(size, size, { type: THREE.FloatType });
  const render = () => {
    renderer.setRenderTarget(target);
    renderer.render(scene, camera);
    const px = new Float32Array(size * size * 4);
    renderer.readRenderTargetPixels(target, 0, 0, size, size, px);
    renderer.setRenderTarget(null);
    return px;
  };
  const lit = render();
  const environment = scene.environment;
  scene.environment = null;
  const unlit = render();
  scene.environment = environment;
  window.recipeResult = measure.recipeReport(lit, unlit, size);
}`,
  judge: judgeRecipe,
};

await runEngineCheck({
  puppeteer,
  chromium,
  root,
  recipe,
  page: '/engines/three/check.html',
  out,
  cases: [...HDRIS, ...Object.keys(BLOCK_CASES).flatMap((suffix) => HDRIS.map((h) => `${h}_${suffix}`)), STUDIO_HDRI],
  bars: BARS,
  config: (name) => {
    if (name === STUDIO_HDRI) {
      return {
        roughness: ROUGHNESS,
        studio: { splitDir: `/target/engines/three/studio_split/${name}`, keptDir: `/target/engines/three/studio_keep/${name}` },
      };
    }
    const suffix = Object.keys(BLOCK_CASES).find((k) => name.endsWith(`_${k}`));
    const hdri = suffix ? name.slice(0, -suffix.length - 1) : name;
    const bakes = suffix ? `bakes_${suffix}` : 'bakes';
    return {
      hdrUrl: `/tests/data/${hdri}.hdr`,
      bakeDir: `/target/engines/three/${bakes}/${hdri}`,
      fallbackDir: `/target/engines/three/bakes/${hdri}`,
      cubeUrl: `/target/engines/three/bakes/${hdri}_cube.ktx2`,
      roughness: ROUGHNESS,
      splitDir: name === SUN_HDRI ? `/target/engines/three/bakes_split/${hdri}` : undefined,
    };
  },
  judge: (r, { bad, note }) => {
    note(true, `path: ${r.path}`);
    if (r.unsupported) {
      // A block format this context cannot sample: the loader says which extension it needs,
      // and pickSplitsumBake falls back to the rgba16f bake.
      const u = r.unsupported;
      bad(u.refused !== null && u.refused.includes(u.needs), `loadSplitsumBake refuses it: ${u.refused}`);
      bad(u.picked === u.fallbackDir, `pickSplitsumBake chooses ${u.picked} (the rgba16f bake is ${u.fallbackDir})`);
    }
    if (r.skipped) return;
    if (r.areaLights !== undefined) {
      // Held against the truth by tests/engine_renders.rs (studio_area_lights_against_truth).
      bad(r.areaLights > 0, `studio: ${r.areaLights} area light(s), ${r.directionalLights} directional`);
      return;
    }
    bad(r.background.sunError <= BARS.sunDegrees,
      `background sun ${r.background.sunError.toFixed(2)}° from three's equirect path (bar ${BARS.sunDegrees}°; three's own path is ${r.background.threeSunVsEquirect.toFixed(2)}° from the HDRI's sun); mean |Δ ln(1+L)| ${r.background.logDiff.toFixed(4)} at the sun, ${r.background.logDiffAllViews.toFixed(4)} over six views`);
    bad(r.mirror.sunError <= BARS.sunDegrees,
      `mirror sphere sun ${r.mirror.sunError.toFixed(2)}° from three's PMREM (bar ${BARS.sunDegrees}°)`);
    for (const s of r.spheres) {
      bad(Math.abs(s.ratio - 1) <= BARS.brightness && s.correlation >= BARS.correlation,
        `${s.metalness ? 'metal' : 'dielectric'} r = ${s.roughness}: brightness ${(100 * (s.ratio - 1)).toFixed(2)} % against three's PMREM, correlation ${s.correlation.toFixed(4)} (${s.pixels} pixels); ${(100 * (s.ratioToThreePmremOfExactCube - 1)).toFixed(2)} % against three's PMREM of splitsum's exact cube`);
    }
    if (r.sunLight) {
      const s = r.sunLight;
      bad(Math.abs(s.litRatio - 1) <= SUN_BARS.sides && Math.abs(s.shadedRatio - 1) <= SUN_BARS.sides,
        `sun split: diffuse sphere under the residual IBL + sunLight against the full IBL: lit side ${(100 * (s.litRatio - 1)).toFixed(2)} % (${s.litPixels} pixels), shaded side ${(100 * (s.shadedRatio - 1)).toFixed(2)} % (${s.shadedPixels} pixels) (bar ${100 * SUN_BARS.sides} %)`);
      bad(s.shadow.pixels > 100 && s.shadow.error <= SUN_BARS.shadowDegrees,
        `sun split: the box's shadow at azimuth ${s.shadow.azimuth.toFixed(2)}°, where the sun puts it ${s.shadow.expectedAzimuth.toFixed(2)}° (${s.shadow.error.toFixed(2)}°, bar ${SUN_BARS.shadowDegrees}°; ${s.shadow.pixels} pixels)`);
    }
    if (r.lightProbe) {
      bad(Math.abs(r.lightProbe.ratio - 1) <= BARS.brightness && r.lightProbe.correlation >= BARS.correlation,
        `LightProbe from sh.json: brightness ${(100 * (r.lightProbe.ratio - 1)).toFixed(2)} % against three's PMREM diffuse, correlation ${r.lightProbe.correlation.toFixed(4)}`);
    }
  },
});
