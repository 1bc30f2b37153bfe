// The Babylon.js engine check: bakes the bundled HDRIs with `splitsum bake --target
// babylon`, loads the .env into Babylon.js 9.35 (npm babylonjs) in headless Chromium
// (SwiftShader) as a Babylon app does, renders the skybox and PBRMaterial spheres into float
// targets, and compares them with Babylon's own path from the same HDRI (HDRCubeTexture,
// prefiltered on load) and with that path from splitsum's exact cube of the HDRI
// (engines/panorama.mjs).
//
//   cd engines/babylon && npm ci && node check.mjs
//
// A studio case (studio_small_03_1k) renders a `--sun split` bake's lamps as Babylon
// RectAreaLights (js/splitsum-babylon.js) for tests/engine_renders.rs, as Babylon shades
// them and with its specular compensated, with a unit check of the area light.
//
// Environment: SPLITSUM (the binary; default ../../target/release/splitsum), CHROMIUM
// (default /usr/bin/chromium). Writes renders and results.json to
// ../../target/engines/babylon/. Exits 1 when a bar is missed or the console shows an error
// or warning.
import { execFileSync } from 'node:child_process';
import { mkdirSync, readFileSync, writeFileSync } from 'node:fs';
import { join, resolve, dirname } from 'node:path';
import { fileURLToPath } from 'node:url';
import puppeteer from 'puppeteer-core';
import { requireTools, runEngineCheck } from '../chromium.mjs';
import { judgeRecipe } from '../recipe.mjs';
import { exactPanorama } from '../panorama.mjs';

const here = dirname(fileURLToPath(import.meta.url));
const root = resolve(here, '../..');
const out = join(root, 'target/engines/babylon');
const splitsum = process.env.SPLITSUM ?? join(root, 'target/release/splitsum');
const chromium = process.env.CHROMIUM ?? '/usr/bin/chromium';

// The bars (docs/engines.md, "Babylon.js"): the sun within 1° of Babylon's own path, spheres
// at r = 0.25, 0.5, 1 within 5 % of it in mean brightness with correlation ≥ 0.98.
const BARS = { sunDegrees: 1, brightness: 0.05, correlation: 0.98, controlDegrees: 10, cubeCorrelation: 0.99 };
const ROUGHNESS = [0.25, 0.5, 1];
const HDRIS = ['venice_sunset_1k', 'quarry_01_1k'];
// The sun bars (docs/engines.md, "The sun as a light"): a diffuse sphere under the full IBL
// and under the residual IBL plus the DirectionalLight, each within 3 % of the truth on its
// lit and its shaded side (see the judge); the shadow's centre
// within 2° of the azimuth the sun's direction puts it at. The split bake's skybox
// (_background.env) looking at the sun: its brightest pixel within 10 % of the kept bake's
// skybox (both hold the disc clipped at RGBD's 255; the kept .env's level 0 is a prefilter
// at alpha 1/256, the background's the plain cube: measured 0.00 %), where the residual's
// is 83 % under.
const SUN_HDRI = 'quarry_01_1k';
const SUN_BARS = { sides: 0.03, shadowDegrees: 2, skyboxPeak: 0.1 };
// A studio's lamps as area lights: studio_small_03 (a 6° round lamp with ~2/3 of the light)
// baked with --sun split (its lamps as RectAreaLights beside the residual IBL) and with
// --sun keep; its spheres, shaded as Babylon ships its shader (plain_sphere_*) and with
// js/splitsum-babylon.js's compensateRectAreaLights (sphere_*: the LTC as a control
// variate), are held against the truth by tests/engine_renders.rs
// (studio_area_lights_against_truth). Here: the renders exist and are finite, the
// rectangles Babylon draws are sun.json's, the patched renders ran on the patched shader
// (and the plain ones did not), and the unit check of Babylon's RectAreaLight (check.js,
// areaLightUnit), which pins its units: where a unit sphere faces a light of radiance L, a
// white Lambertian one within 2 % of albedo · L · F (F the rectangle's form factor),
// Babylon's diffuse being the closed-form polygon integral in float32 with its edge term a
// rational fit of θ / sin θ (measured: −0.03 % under a 6° × 6° and a 40° × 20° light); a
// white metal at r = 1 within 2 % of L ∫ f (n·l) dω over the rectangle (GGX, F = 1), the
// patched specular being Babylon's GGX at the rectangle's centre × its solid angle plus
// the LTC's variation over it (measured: +0.04 % and +0.81 %; as Babylon ships it, Heitz's
// fitted LTC lobe alone, which at r = 1 and normal incidence holds 3.4 % less than GGX over
// a small light: −3.4 % and −2.6 %, reported); and the light turned away lights nothing
// (one-sided).
const STUDIO_HDRI = 'studio_small_03_1k';
const AREA_BARS = { diffuse: 0.02, specular: 0.02 };
// Babylon's RectAreaLight fetches its LTC tables (areaLightsLTC.bin: per texel LTC1's then
// LTC2's RGBA as half floats, 64², Lights/LTC/ltcTextureTool.ts) from assets.babylonjs.com,
// which the page cannot reach, through Tools.GetAssetUrl, which maps that host under
// Tools.AssetBaseUrl. The page gets them from here: the tables three.js r187 ships
// (Heitz's GGX fit, which Babylon's LTC shader code, ported from three's, reads:
// LTC_MAT_1 then LTC_MAT_2 as f32), in Babylon's layout.
const LTC_TABLE = 'tests/data/ltc_ggx_heitz_three_r187.f32';
const LTC_ASSETS = 'target/engines/babylon/assets';

requireTools([['splitsum', splitsum], ['chromium', chromium], ['the LTC table', join(root, LTC_TABLE)]]);

mkdirSync(out, { recursive: true });
const run = (...args) => execFileSync(splitsum, args, { cwd: root, stdio: 'inherit' });
run('bake', ...HDRIS.map((h) => `tests/data/${h}.hdr`), '--target', 'babylon', '-q', '-o', 'target/engines/babylon/splitsum');
// The sun as a light: quarry_01 with its sun split out.
run('bake', `tests/data/${SUN_HDRI}.hdr`, '--target', 'babylon', '--sun', 'split', '-q', '-o', 'target/engines/babylon/split');
// The studio: its lamps split out as area lights, and kept in the IBL.
run('bake', `tests/data/${STUDIO_HDRI}.hdr`, '--target', 'babylon', '--sun', 'split', '-q', '-o', 'target/engines/babylon/studio_split');
run('bake', `tests/data/${STUDIO_HDRI}.hdr`, '--target', 'babylon', '--sun', 'keep', '-q', '-o', 'target/engines/babylon/studio_kept');
writeLtcAssets();
// The negative control: the same bake turned a quarter about +Y.
run('bake', ...HDRIS.map((h) => `tests/data/${h}.hdr`), '--target', 'babylon', '--rotate', '90', '-q', '-o', 'target/engines/babylon/control');

// LTC_TABLE as Babylon's areaLightsLTC.bin under LTC_ASSETS (Tools.AssetBaseUrl's layout).
function writeLtcAssets() {
  const bytes = readFileSync(join(root, LTC_TABLE));
  const table = new Float32Array(bytes.buffer, bytes.byteOffset, bytes.byteLength / 4);
  const texels = 64 * 64;
  if (table.length !== 8 * texels) throw new Error(`${LTC_TABLE}: ${table.length} floats, not two 64² RGBA tables`);
  const half = new Uint16Array(8 * texels);
  for (let t = 0; t < texels; t++) {
    for (let c = 0; c < 4; c++) {
      half[8 * t + c] = toHalf(table[4 * t + c]);
      half[8 * t + 4 + c] = toHalf(table[4 * texels + 4 * t + c]);
    }
  }
  mkdirSync(join(root, LTC_ASSETS, 'areaLights'), { recursive: true });
  writeFileSync(join(root, LTC_ASSETS, 'areaLights/areaLightsLTC.bin'), Buffer.from(half.buffer));
}

// IEEE half-float bits of a number, rounded to nearest even.
function toHalf(x) {
  const bits = new Uint32Array(new Float32Array([x]).buffer)[0];
  const sign = (bits >>> 16) & 0x8000;
  const exp = (bits >>> 23) & 0xff;
  let mant = bits & 0x7fffff;
  if (exp === 0xff) return sign | 0x7c00 | (mant ? 0x200 : 0);
  const e = exp - 112;
  if (e >= 0x1f) return sign | 0x7c00;
  if (e <= 0) {
    // A subnormal half (or zero): the mantissa with its leading 1, shifted into 2^-24 units.
    if (e < -10) return sign;
    mant |= 0x800000;
    const shift = 14 - e;
    const round = (mant >>> (shift - 1)) & 1, sticky = mant & ((1 << (shift - 1)) - 1);
    let h = mant >>> shift;
    if (round && (sticky || h & 1)) h++;
    return sign | h;
  }
  let h = sign | (e << 10) | (mant >>> 13);
  if (mant & 0x1000 && mant & 0x2fff) h++;
  return h;
}

// Babylon's own path converts the HDRI to a 256² cube (HDRCubeTexture's size here).
const exact = Object.fromEntries(HDRIS.map((h) => [h, exactPanorama({
  splitsum, root, input: `tests/data/${h}.hdr`, name: h, dir: 'target/engines/babylon/exact', size: 256,
})]));

// The README's Babylon.js recipe as written, given what it takes as given (an engine and a
// scene with a camera), then a white PBR sphere rendered with and without the environment
// it set (8-bit canvas values, decoded).
const recipe = {
  splitsum,
  heading: 'Babylon.js',
  head: '<script src="/engines/babylon/node_modules/babylonjs/babylon.js"></script>',
  files: [['js/splitsum-babylon.js', 'splitsum-babylon.js']],
  prelude: `import * as measure from '/engines/measure.js';
const size = 64;
const canvas = measure.pageCanvas(size);
const engine = new BABYLON.Engine(canvas, false, { preserveDrawingBuffer: true });
const scene = new BABYLON.Scene(engine);
const camera = new BABYLON.FreeCamera('camera', new BABYLON.Vector3(0, 0, -measure.SPHERE_DISTANCE), scene);
camera.setTarget(BABYLON.Vector3.Zero());
camera.fov = (measure.SPHERE_FOV * Math.PI) / 180;`,
  epilogue: `{
  const sphere = BABYLON.MeshBuilder.CreateSphere('sphere', { diameter: 2, segments: 64 }, scene);
  const material = new BABYLON.PBRMaterial('white', scene);
  material.albedoColor = new BABYLON.Color3(1, 1, 1);
  material.metallic = 0;
  material.roughness = 0.5;
  sphere.material = material;
  const render = async () => {
    await scene.whenReadyAsync();
    scene.render();
    const bytes = await engine.readPixels(0, 0, size, size);
    return Float32Array.from(bytes, (b, i) => (i % 4 === 3 ? 1 : (b / 255) ** 2.2));
  };
  const lit = await render();
  const environment = scene.environmentTexture;
  scene.environmentTexture = null;
  const unlit = await render();
  scene.environmentTexture = environment;
  window.recipeResult = measure.recipeReport(lit, unlit, size);
}`,
  judge: judgeRecipe,
};

await runEngineCheck({
  puppeteer,
  chromium,
  root,
  recipe,
  page: '/engines/babylon/check.html',
  out,
  cases: [...HDRIS, STUDIO_HDRI],
  bars: { ...BARS, area: AREA_BARS },
  config: (hdri) => (hdri === STUDIO_HDRI ? {
    roughness: ROUGHNESS,
    studio: {
      env: `/target/engines/babylon/studio_split/${hdri}/${hdri}.env`,
      irradiance: `/target/engines/babylon/studio_split/${hdri}/${hdri}_irradiance.env`,
      sun: `/target/engines/babylon/studio_split/${hdri}/sun.json`,
      keptEnv: `/target/engines/babylon/studio_kept/${hdri}/${hdri}.env`,
      keptIrradiance: `/target/engines/babylon/studio_kept/${hdri}/${hdri}_irradiance.env`,
      assetBaseUrl: `/${LTC_ASSETS}`,
    },
  } : {
    hdrUrl: `/tests/data/${hdri}.hdr`,
    exactUrl: `/${exact[hdri]}`,
    envUrl: `/target/engines/babylon/splitsum/${hdri}/${hdri}.env`,
    irradianceUrl: `/target/engines/babylon/splitsum/${hdri}/${hdri}_irradiance.env`,
    controlUrl: `/target/engines/babylon/control/${hdri}/${hdri}.env`,
    roughness: ROUGHNESS,
    split: hdri === SUN_HDRI
      ? {
          env: `/target/engines/babylon/split/${hdri}/${hdri}.env`,
          irradiance: `/target/engines/babylon/split/${hdri}/${hdri}_irradiance.env`,
          background: `/target/engines/babylon/split/${hdri}/${hdri}_background.env`,
          sun: `/target/engines/babylon/split/${hdri}/sun.json`,
        }
      : undefined,
  }),
  judge: (r, { bad, note, name: hdri }) => {
    if (hdri === STUDIO_HDRI) {
      judgeStudio(r, { bad, note });
      return;
    }
    bad(r.levels === 9 && Math.abs(r.lodGenerationScale - 0.8) < 1e-6, `the .env loads as a ${r.levels}-level cube with lodGenerationScale ${r.lodGenerationScale}`);
    bad(r.cube.correlation >= BARS.cubeCorrelation && r.cube.sunError <= 0.5,
      `level 0 as Babylon holds it against its own HDRCubeTexture: correlation ${r.cube.correlation.toFixed(4)} of ln(1+L) over 8×8 blocks (bar ${BARS.cubeCorrelation}), bright texels ${r.cube.sunError.toFixed(2)}° apart (bar 0.5°); flux ratio ${r.cube.fluxRatio.toFixed(4)}`);
    bad(r.background.sunError <= BARS.sunDegrees,
      `skybox sun ${r.background.sunError.toFixed(2)}° from Babylon's own (bar ${BARS.sunDegrees}°); mean |Δ ln(1+L)| ${r.background.logDiff.toFixed(4)} looking at the sun`);
    bad(r.control.sunError > BARS.controlDegrees,
      `negative control: the bake turned 90° about +Y puts the sun ${r.control.sunError.toFixed(1)}° off (must exceed ${BARS.controlDegrees}°)`);
    bad(r.mirror.sunError <= BARS.sunDegrees,
      `mirror sphere sun ${r.mirror.sunError.toFixed(2)}° from Babylon's own (bar ${BARS.sunDegrees}°; Babylon's reflection is ${r.mirror.ownVsCube.toFixed(2)}° from its cube's sun)`);
    // Against Babylon's own path (HDRCubeTexture prefiltered on load), held to the bars where
    // that path keeps the HDRI's light: its cube's flux and its irradiance within 2 % of
    // splitsum's. On a small hard sun it does not (it samples the equirect at texel centres,
    // and its SH projection clamps texels at 4096, CubeMapToSphericalPolynomialTools.
    // MAX_HDRI_VALUE), and the comparison is reported.
    const kept = Math.abs(r.cube.fluxRatio - 1) <= 0.02 && Math.abs(r.irradianceRatio - 1) <= 0.02;
    console.log(`     ${hdri}: splitsum's irradiance (polynomial band 0) is ${(100 * (r.irradianceRatio - 1)).toFixed(1)} % off Babylon's own`);
    for (const s of r.vsOwn) {
      const ok = Math.abs(s.ratio - 1) <= BARS.brightness && s.correlation >= BARS.correlation;
      (kept ? bad : note)(ok, `${s.metallic ? 'metal' : 'dielectric'} r = ${s.roughness}: brightness ${(100 * (s.ratio - 1)).toFixed(2)} % against Babylon's own path, correlation ${s.correlation.toFixed(4)} (${s.pixels} pixels)`);
    }
    // Against Babylon's own path from splitsum's exact cube of the HDRI (its SH clamp
    // lifted): Babylon's SH projection and prefiltering of the cube splitsum bakes from,
    // held to the bars on every HDRI. The irradiance within 2 %: both project the same cube;
    // the panorama that carries it to Babylon keeps its flux to 0.2 % (venice_sunset) and
    // 1.4 % (quarry_01's sun), measured on Babylon's level 0 against splitsum's rough mips.
    bad(Math.abs(r.exact.irradianceRatio - 1) <= 0.02,
      `irradiance (polynomial band 0) ${(100 * (r.exact.irradianceRatio - 1)).toFixed(2)} % off Babylon's SH of splitsum's exact cube (bar 2 %)`);
    for (const s of r.vsOwnExact) {
      bad(Math.abs(s.ratio - 1) <= BARS.brightness && s.correlation >= BARS.correlation,
        `${s.metallic ? 'metal' : 'dielectric'} r = ${s.roughness}: brightness ${(100 * (s.ratio - 1)).toFixed(2)} % against Babylon's own path from splitsum's exact cube, correlation ${s.correlation.toFixed(4)} (${s.pixels} pixels)`);
    }
    if (r.sunLight) {
      const s = r.sunLight;
      // Both environments as the README recipe sets them, their diffuse light from the
      // irradiance cube (the .env's SH9 cannot hold a sun: the full IBL's shaded side was
      // 19 % under the truth through it): both renders within 3 % of the brute-force truth
      // on the lit and the shaded side.
      const pc = (x) => `${(100 * (x - 1)).toFixed(2)} %`;
      const within = (t) => Math.abs(t.lit - 1) <= SUN_BARS.sides && Math.abs(t.shaded - 1) <= SUN_BARS.sides;
      bad(within(s.truth.split) && within(s.truth.full),
        `sun split: diffuse sphere against the brute-force truth, lit / shaded side (${s.litPixels} / ${s.shadedPixels} pixels, bar ${100 * SUN_BARS.sides} %): the residual IBL + DirectionalLight ${pc(s.truth.split.lit)} / ${pc(s.truth.split.shaded)}, the full IBL ${pc(s.truth.full.lit)} / ${pc(s.truth.full.shaded)}; split against full ${pc(s.litRatio)}, ${pc(s.shadedRatio)}`);
      bad(s.background.sunError <= BARS.sunDegrees && Math.abs(s.background.peak - 1) <= SUN_BARS.skyboxPeak,
        `sun split: the skybox of ${hdri}_background.env shows the sun ${s.background.sunError.toFixed(2)}° from Babylon's own (bar ${BARS.sunDegrees}°), its brightest pixel ${pc(s.background.peak)} off the kept bake's skybox (bar ${100 * SUN_BARS.skyboxPeak} %); the residual .env's is ${pc(s.background.residualPeak)} off`);
      bad(s.shadow.pixels > 100 && s.shadow.error <= SUN_BARS.shadowDegrees,
        `sun split: the box's shadow at azimuth ${s.shadow.azimuth.toFixed(2)}°, where the sun puts it ${s.shadow.expectedAzimuth.toFixed(2)}° (${s.shadow.error.toFixed(2)}°, bar ${SUN_BARS.shadowDegrees}°; ${s.shadow.pixels} pixels)`);
    }
  },
});

// The studio case: its renders (held against the truth by tests/engine_renders.rs,
// studio_area_lights_against_truth) and the unit check of Babylon's RectAreaLight.
function judgeStudio(r, { bad, note }) {
  note(true, `path: ${r.path}`);
  bad(r.rectError < 0.01, `studio: the rectangles Babylon draws (their parent's world matrix on position, width and height) ${r.rectError.toExponential(1)}° from sun.json's rect_light (bar 0.01°)`);
  bad(r.areaLights > 0 && r.spheres.every((s) => s.finite && s.mean > 0),
    `studio: ${r.areaLights} area light(s), ${r.directionalLights} directional; ${r.spheres.length} sphere renders, every pixel finite (mean luminance ${r.spheres.map((s) => s.mean.toPrecision(3)).join(', ')})`);
  bad(r.shaderPatch.before === 0 && r.shaderPatch.patchedNow && r.shaderPatch.after > 0,
    `studio: js/splitsum-babylon.js's compensateRectAreaLights patched Babylon's GLSL (${r.shaderPatch.patchedNow ? 'now' : 'already before'}); compiled effects holding it: ${r.shaderPatch.before} for the plain renders, ${r.shaderPatch.after} for the patched ones`);
  const pc = (x) => `${(100 * (x - 1)).toFixed(2)} %`;
  for (const u of r.areaUnitPlain) {
    if (u.term !== 'back') note(true, `RectAreaLight unit check as Babylon ships it, ${u.what}: ${u.got.toPrecision(5)} against ${u.want.toPrecision(5)}, ${pc(u.ratio)}`);
  }
  for (const u of r.areaUnit) {
    if (u.term === 'back') {
      bad(u.got === 0, `RectAreaLight unit check, ${u.what}: ${u.got} (one-sided: must be 0)`);
      continue;
    }
    const bar = AREA_BARS[u.term];
    bad(Math.abs(u.ratio - 1) <= bar,
      `RectAreaLight unit check, ${u.what}: ${u.got.toPrecision(5)} against ${u.want.toPrecision(5)}, ${pc(u.ratio)} (bar ${100 * bar} %; ${u.pixels} pixels)`);
  }
}
