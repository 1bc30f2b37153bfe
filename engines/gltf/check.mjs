// The glTF Sample Viewer engine check: bakes the bundled HDRIs with `splitsum bake --target
// gltf` and renders them with the viewer's own renderer (npm @khronosgroup/gltf-viewer
// 1.1.0) in headless Chromium (SwiftShader), the files loaded through its KTX2 decoder into
// its environment, against the viewer's own path from the same HDRI (its run-time
// filtering, ResourceLoader.loadEnvironment).
//
//   cd engines/gltf && npm ci && node check.mjs
//
// Environment: SPLITSUM (the binary; default ../../target/release/splitsum), CHROMIUM
// (default /usr/bin/chromium). Writes renders and results.json to
// ../../target/engines/gltf/. Exits 1 when a bar is missed or the console shows an error
// or warning.
import { execFileSync } from 'node:child_process';
import { mkdirSync } from 'node:fs';
import { join, resolve, dirname } from 'node:path';
import { fileURLToPath } from 'node:url';
import puppeteer from 'puppeteer-core';
import { requireTools, runEngineCheck } from '../chromium.mjs';

const here = dirname(fileURLToPath(import.meta.url));
const root = resolve(here, '../..');
const out = join(root, 'target/engines/gltf');
const splitsum = process.env.SPLITSUM ?? join(root, 'target/release/splitsum');
const chromium = process.env.CHROMIUM ?? '/usr/bin/chromium';

// The bars (docs/engines.md, "glTF Sample Viewer"): the sun within 1° of the viewer's own
// path, spheres at r = 0.25, 0.5, 1 within 5 % of it in mean brightness with correlation
// ≥ 0.98.
const BARS = { sunDegrees: 1, brightness: 0.05, correlation: 0.98, controlDegrees: 10, cubeCorrelation: 0.99 };
const ROUGHNESS = [0.25, 0.5, 1];
const HDRIS = ['venice_sunset_1k', 'quarry_01_1k'];
// The target's chain: 256² to 16².
const LEVELS = 5;

requireTools([['splitsum', splitsum], ['chromium', chromium]]);

mkdirSync(out, { recursive: true });
const run = (...args) => execFileSync(splitsum, args, { cwd: root, stdio: 'inherit' });
run('bake', ...HDRIS.map((h) => `tests/data/${h}.hdr`), '--target', 'gltf', '-q', '-o', 'target/engines/gltf/splitsum');
// The negative control: the same bake turned a quarter about +Y.
run('bake', ...HDRIS.map((h) => `tests/data/${h}.hdr`), '--target', 'gltf', '--rotate', '90', '-q', '-o', 'target/engines/gltf/control');
// The sun as a light: quarry_01 with its sun split out, sun.gltf read by the viewer's
// glTF loader; its light within 1° of where the viewer shows the sun (the bar of every sun
// here), its colour × intensity within 1e-5 of sun.json's E.
const SUN_HDRI = 'quarry_01_1k';
run('bake', `tests/data/${SUN_HDRI}.hdr`, '--target', 'gltf', '--sun', 'split', '-q', '-o', 'target/engines/gltf/split');

// The README's recipe for this file set as written, given what it takes as given (a WebGL2
// context `gl`); then each cube it returns is read back level by level, face by face (one
// texel each, as float through EXT_color_buffer_float): the chains hold the five levels the
// viewer's u_MipCount names, the diffuse cube at least one, every texel finite and not
// negative, some bright, and no GL error.
const recipe = {
  splitsum,
  heading: 'glTF Sample Viewer',
  head: '<script src="/engines/gltf/node_modules/@khronosgroup/gltf-viewer/dist/libs/libktx.js"></script>',
  prelude: `const canvas = document.createElement('canvas');
document.body.appendChild(canvas);
const gl = canvas.getContext('webgl2');`,
  epilogue: `{
  gl.getExtension('EXT_color_buffer_float');
  const framebuffer = gl.createFramebuffer();
  const report = { glError: 0 };
  for (const [name, texture] of Object.entries({ ggx, lambertian, charlie })) {
    gl.bindTexture(gl.TEXTURE_CUBE_MAP, texture);
    // libktx uploads level by level (a mutable texture): a level is there when each face
    // of it makes a complete framebuffer.
    const texels = [];
    let levels = 0;
    gl.bindFramebuffer(gl.FRAMEBUFFER, framebuffer);
    for (let m = 0; m < 16; m++) {
      const faces = [];
      for (let f = 0; f < 6; f++) {
        gl.framebufferTexture2D(gl.FRAMEBUFFER, gl.COLOR_ATTACHMENT0, gl.TEXTURE_CUBE_MAP_POSITIVE_X + f, texture, m);
        if (gl.checkFramebufferStatus(gl.FRAMEBUFFER) !== gl.FRAMEBUFFER_COMPLETE) break;
        const px = new Float32Array(4);
        gl.readPixels(0, 0, 1, 1, gl.RGBA, gl.FLOAT, px);
        faces.push(...px.slice(0, 3));
      }
      if (faces.length < 18) break;
      texels.push(...faces);
      levels += 1;
    }
    gl.bindFramebuffer(gl.FRAMEBUFFER, null);
    report[name] = { levels, texels: texels.length, finite: texels.every((v) => Number.isFinite(v) && v >= 0), max: Math.max(...texels) };
  }
  report.glError = gl.getError();
  window.recipeResult = report;
}`,
  judge: (r, { bad }) => {
    for (const [name, least] of [['ggx', 5], ['charlie', 5], ['lambertian', 1]]) {
      const c = r[name];
      bad((name === 'lambertian' ? c.levels >= least : c.levels === least) && c.finite && c.max > 1e-3,
        `the README's code, as written, uploads ${name} as a cube, levels: ${c.levels} (${least === 5 ? 'u_MipCount 5' : 'at least 1'}), ${c.texels} texels read back, ${c.finite ? 'all finite and ≥ 0' : 'NOT all finite and ≥ 0'}, largest ${c.max.toFixed(3)}`);
    }
    bad(r.glError === 0, `GL errors after the upload and reads: ${r.glError === 0 ? "none" : r.glError}`);
  },
};

await runEngineCheck({
  puppeteer,
  chromium,
  root,
  recipe,
  page: '/engines/gltf/check.html',
  out,
  cases: HDRIS,
  bars: BARS,
  config: (hdri) => ({
    hdrUrl: `/tests/data/${hdri}.hdr`,
    dir: `/target/engines/gltf/splitsum/${hdri}`,
    controlDir: `/target/engines/gltf/control/${hdri}`,
    levels: LEVELS,
    roughness: ROUGHNESS,
    splitDir: hdri === SUN_HDRI ? `/target/engines/gltf/split/${hdri}` : undefined,
  }),
  judge: (r, { bad, note, name: hdri }) => {
    bad(Math.abs(r.linearity - 1) < 0.02, `read-back linearity: radiance at 1/4 the exposure ${(100 * (r.linearity - 1)).toFixed(2)} % off (bar 2 %)`);
    bad(r.cube.correlation >= BARS.cubeCorrelation && r.cube.sunError <= 0.5,
      `level 0 of the GGX cube as the viewer holds it against its own: correlation ${r.cube.correlation.toFixed(4)} of ln(1+L) over 8×8 blocks (bar ${BARS.cubeCorrelation}), bright texels ${r.cube.sunError.toFixed(2)}° apart (bar 0.5°); flux ratio ${r.cube.fluxRatio.toFixed(4)}`);
    bad(r.background.sunError <= BARS.sunDegrees,
      `background sun ${r.background.sunError.toFixed(2)}° from the viewer's own (bar ${BARS.sunDegrees}°); mean |Δ ln(1+L)| ${r.background.logDiff.toFixed(4)} looking at the sun`);
    bad(r.control.sunError > BARS.controlDegrees,
      `negative control: the bake turned 90° about +Y puts the sun ${r.control.sunError.toFixed(1)}° off (must exceed ${BARS.controlDegrees}°)`);
    bad(r.mirror.sunError <= BARS.sunDegrees,
      `mirror sphere sun ${r.mirror.sunError.toFixed(2)}° from the viewer's own (bar ${BARS.sunDegrees}°; the viewer's reflection is ${r.mirror.viewerVsCube.toFixed(2)}° from its cube's sun)`);
    // The Lambertian cubes against a brute-force E/π of the radiance cube each stands for,
    // summed in the page over every texel the viewer holds: splitsum's within 1 % at every
    // direction (its E/π is exact to 0.03 % against the HDRI, tests/irradiance.rs; here
    // rgba16f texels and the 256² cube as the integrand).
    const lam = r.lambertian;
    bad(lam.splitsum.worst <= 0.01,
      `splitsum's Lambertian cube against a brute-force E/π of its level-0 cube: ${(100 * (lam.splitsum.ratio - 1)).toFixed(2)} % over 1536 directions, worst ${(100 * lam.splitsum.worst).toFixed(2)} % (bar 1 %); the viewer's own against its cube: ${(100 * (lam.viewer.ratio - 1)).toFixed(2)} %, worst ${(100 * lam.viewer.worst).toFixed(2)} %`);
    // As for Filament and Babylon: held to the bars where the viewer's own path keeps the
    // HDRI's light, reported otherwise: the metal spheres where its cube keeps the flux
    // within 2 % (it samples the equirect at texel centres), the dielectric ones, lit
    // mostly by the Lambertian cube, where the viewer's Lambertian cube is within 2 % of the
    // brute-force E/π of its own cube (its filter samples box-filtered mips of the cube,
    // which misplace a small sun's light).
    const fluxKept = Math.abs(r.cube.fluxRatio - 1) <= 0.02;
    const irradianceKept = Math.abs(lam.viewer.ratio - 1) <= 0.02;
    console.log(`     ${hdri}: splitsum's E/π is ${(100 * (r.irradianceRatio - 1)).toFixed(1)} % off the viewer's Lambertian cube (means over the sphere)`);
    for (const s of r.spheres) {
      const ok = Math.abs(s.ratio - 1) <= BARS.brightness && s.correlation >= BARS.correlation;
      const kept = s.metallic ? fluxKept : irradianceKept;
      (kept ? bad : note)(ok, `${s.metallic ? 'metal' : 'dielectric'} r = ${s.roughness}: brightness ${(100 * (s.ratio - 1)).toFixed(2)} % against the viewer's own path, correlation ${s.correlation.toFixed(4)} (${s.pixels} pixels)`);
      // The dielectric spheres against the viewer's own path with its Lambertian cube
      // replaced by the brute-force E/π of its own cube, held to the bars on every HDRI.
      if (s.exactDiffuse) {
        const e = s.exactDiffuse;
        bad(Math.abs(e.ratio - 1) <= BARS.brightness && e.correlation >= BARS.correlation,
          `dielectric r = ${s.roughness}: brightness ${(100 * (e.ratio - 1)).toFixed(2)} % against the viewer's own path with a brute-force Lambertian cube, correlation ${e.correlation.toFixed(4)}`);
      }
    }
    if (r.sunLight) {
      const l = r.sunLight;
      bad(l.type === 'directional' && l.sunError <= BARS.sunDegrees && l.irradianceError <= 1e-5,
        `sun.gltf through the viewer's glTF loader: ${l.lights} KHR_lights_punctual light(s), the first '${l.type}' shining from ${l.sunError.toFixed(2)}° off where the viewer shows the sun (bar ${BARS.sunDegrees}°; ${l.jsonError.toFixed(3)}° off sun.json's direction turned by the viewer's environment rotation), colour × intensity ${l.irradianceError.toExponential(1)} off sun.json's E`);
    }
  },
});
