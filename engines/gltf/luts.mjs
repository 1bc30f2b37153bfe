// The glTF Sample Viewer's LUTs, computed by the viewer's own shader: npm
// @khronosgroup/gltf-viewer 1.1.0 generates lut_ggx and lut_charlie at run time with
// `ibl_filtering.frag` (its port of glTF-IBL-Sampler's filter shader, `LUT()`), drawn with
// its `fullscreen.vert` into a float texture, 512 Hammersley samples a texel as its
// `iblSampler.sampleLut` sets. This lifts both shaders out of the package as they are,
// draws them the same way in headless Chromium (SwiftShader WebGL2) at 128² (the viewer
// draws 1024²; a texel's value depends only on its uv, here (i + ½)/128), and writes the
// RGBA float32 texels, row 0 at uv.y = roughness ≈ 0, for `cargo test --release --test
// lut_accuracy gltf_viewer -- --ignored` to compare.
//
//   cd engines/gltf && npm ci && node luts.mjs
//
// Environment: CHROMIUM (default /usr/bin/chromium). Writes ../../target/engines/gltf/
// lut_ggx.f32, lut_charlie.f32 and luts.json. Exits 1 on a WebGL or console error.
import { mkdirSync, readFileSync, writeFileSync, existsSync } from 'node:fs';
import { join, resolve, dirname } from 'node:path';
import { fileURLToPath } from 'node:url';
import puppeteer from 'puppeteer-core';
import { launchChromium, watchConsole } from '../chromium.mjs';

const here = dirname(fileURLToPath(import.meta.url));
const out = resolve(here, '../../target/engines/gltf');
const chromium = process.env.CHROMIUM ?? '/usr/bin/chromium';
const SIZE = 128;
const SAMPLES = 512; // iblSampler.sampleLut: shader.updateUniform("u_sampleCount", 512)
const DISTRIBUTIONS = { lut_ggx: 1, lut_charlie: 2 }; // cGGX, cCharlie in ibl_filtering.frag

if (!existsSync(chromium)) {
  console.error(`error: chromium not found at ${chromium}`);
  process.exit(2);
}
// The bundle holds each shader as a string literal: `var iblFiltering = "...";`.
const bundle = readFileSync(join(here, 'node_modules/@khronosgroup/gltf-viewer/dist/gltf-viewer.module.js'), 'utf8');
const shader = (name) => {
  const m = bundle.match(new RegExp(`var ${name} = ("(?:[^"\\\\]|\\\\.)*");`));
  if (!m) throw new Error(`${name} not found in the gltf-viewer bundle`);
  return JSON.parse(m[1]);
};
const fragment = shader('iblFiltering');
const vertex = shader('fullscreenShader');

mkdirSync(out, { recursive: true });
const { browser, close } = await launchChromium(puppeteer, chromium);
let problems = [];
try {
  const page = await browser.newPage();
  problems = watchConsole(page);
  await page.goto('about:blank');
  const meta = {};
  for (const [name, distribution] of Object.entries(DISTRIBUTIONS)) {
    const texels = await page.evaluate(({ vertex, fragment, size, samples, distribution }) => {
      const canvas = document.createElement('canvas');
      const gl = canvas.getContext('webgl2');
      if (!gl.getExtension('EXT_color_buffer_float')) throw new Error('no EXT_color_buffer_float');
      // The viewer's ShaderCache prepends the version line to every shader.
      const compile = (type, src) => {
        const s = gl.createShader(type);
        gl.shaderSource(s, '#version 300 es\n' + src);
        gl.compileShader(s);
        if (!gl.getShaderParameter(s, gl.COMPILE_STATUS)) throw new Error(gl.getShaderInfoLog(s));
        return s;
      };
      const program = gl.createProgram();
      gl.attachShader(program, compile(gl.VERTEX_SHADER, vertex));
      gl.attachShader(program, compile(gl.FRAGMENT_SHADER, fragment));
      gl.linkProgram(program);
      if (!gl.getProgramParameter(program, gl.LINK_STATUS)) throw new Error(gl.getProgramInfoLog(program));
      const texture = gl.createTexture();
      gl.bindTexture(gl.TEXTURE_2D, texture);
      gl.texImage2D(gl.TEXTURE_2D, 0, gl.RGBA32F, size, size, 0, gl.RGBA, gl.FLOAT, null);
      const fb = gl.createFramebuffer();
      gl.bindFramebuffer(gl.FRAMEBUFFER, fb);
      gl.framebufferTexture2D(gl.FRAMEBUFFER, gl.COLOR_ATTACHMENT0, gl.TEXTURE_2D, texture, 0);
      gl.viewport(0, 0, size, size);
      gl.useProgram(program);
      const set = (n, v, f = 'uniform1i') => gl[f](gl.getUniformLocation(program, n), v);
      // As iblSampler.sampleLut sets them.
      set('u_roughness', 0.0, 'uniform1f');
      set('u_sampleCount', samples);
      set('u_width', 0);
      set('u_lodBias', 0.0, 'uniform1f');
      set('u_distribution', distribution);
      set('u_currentFace', 0);
      set('u_isGeneratingLUT', 1);
      gl.drawArrays(gl.TRIANGLES, 0, 3);
      const px = new Float32Array(size * size * 4);
      gl.readPixels(0, 0, size, size, gl.RGBA, gl.FLOAT, px);
      const err = gl.getError();
      if (err !== gl.NO_ERROR) throw new Error(`WebGL error ${err}`);
      return Array.from(px);
    }, { vertex, fragment, size: SIZE, samples: SAMPLES, distribution });
    writeFileSync(join(out, `${name}.f32`), Buffer.from(new Float32Array(texels).buffer));
    meta[name] = { size: SIZE, samples: SAMPLES, distribution, layout: 'RGBA float32, row 0 at uv.y = roughness (i + 0.5)/size, uv.x = n·v' };
    console.log(`ok   ${name}: ${SIZE}² texels, ${SAMPLES} samples a texel`);
  }
  writeFileSync(join(out, 'luts.json'), JSON.stringify({ viewer: '@khronosgroup/gltf-viewer 1.1.0', ...meta }, null, 2));
} finally {
  await close();
}
if (problems.length > 0) {
  console.log('FAIL console:\n  ' + problems.join('\n  '));
  process.exit(1);
}
console.log(`LUTs in ${out}`);
