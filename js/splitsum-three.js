// Loads splitsum's `--target three` outputs into three.js (r187) as three uses its own
// PMREM: a cube texture with `isPMREMTexture = true`, which MeshStandardMaterial and
// MeshPhysicalMaterial sample as it is (no run-time PMREM), and which `scene.background`
// shows (level 0, or blurred along the chain with `scene.backgroundBlurriness`).
//
//   import { loadSplitsumBake } from './splitsum-three.js';
//   const bake = await loadSplitsumBake('out/sky', renderer);
//   scene.environment = bake.envMap;
//   scene.background = bake.envMap;
//   scene.add(bake.lightProbe); // optional: the SH as a THREE.LightProbe
//
// Why a loader of its own: KTX2Loader (r187) returns a cube KTX2 in an uncompressed format
// as a 2D DataTexture whose levels hold the six faces one after another, with Nearest
// filtering; used as it is, the background is one flat face and every sphere is black.
// This module splits each level into faces and builds a cube with trilinear filtering.
//
// Formats: rgba16f and rgba32f are uploaded as they are (rgba32f needs
// OES_texture_float_linear to be filtered); rgb9e5 and rg11b10f are decoded to rgba16f,
// since three.js uploads uncompressed cube mips through the CompressedCubeTexture path
// only for RGBA data.

import {
  CompressedCubeTexture,
  DataUtils,
  FloatType,
  HalfFloatType,
  LightProbe,
  LinearFilter,
  LinearMipmapLinearFilter,
  LinearSRGBColorSpace,
  RGBAFormat,
  SphericalHarmonics3,
  UnsignedInt101111Type,
  UnsignedInt5999Type,
} from 'three';
import { KTX2Loader } from 'three/addons/loaders/KTX2Loader.js';

// E5B9G9R9_UFLOAT_PACK32: 9-bit mantissas, shared exponent with bias 15.
function unpackRgb9e5(p) {
  const scale = 2 ** (((p >>> 27) & 31) - 15 - 9);
  return [(p & 511) * scale, ((p >>> 9) & 511) * scale, ((p >>> 18) & 511) * scale];
}

// An unsigned float with `m` mantissa bits and a 5-bit exponent (bias 15).
function ufloat(u, m) {
  const e = u >>> m;
  const f = u & ((1 << m) - 1);
  if (e === 0) return f * 2 ** (-14 - m);
  if (e === 31) return f === 0 ? Infinity : NaN;
  return (1 + f / (1 << m)) * 2 ** (e - 15);
}

// B10G11R11_UFLOAT_PACK32: R in bits 0–10, G 11–21, B 22–31.
function unpackRg11b10f(p) {
  return [ufloat(p & 2047, 6), ufloat((p >>> 11) & 2047, 6), ufloat(p >>> 22, 5)];
}

// One face's texels as RGBA half floats (a Uint16Array of 4 per texel).
function toRgbaHalf(packed, unpack) {
  const out = new Uint16Array(packed.length * 4);
  const one = DataUtils.toHalfFloat(1);
  for (let i = 0; i < packed.length; i++) {
    const [r, g, b] = unpack(packed[i]);
    out[4 * i] = DataUtils.toHalfFloat(r);
    out[4 * i + 1] = DataUtils.toHalfFloat(g);
    out[4 * i + 2] = DataUtils.toHalfFloat(b);
    out[4 * i + 3] = one;
  }
  return out;
}

/**
 * Loads a splitsum KTX2 cube (every mip) as a three.js cube texture.
 * @param {string} url - the .ktx2 file.
 * @param {THREE.WebGLRenderer} renderer - the renderer it is for (KTX2Loader checks
 *   its formats).
 * @param {{pmrem?: boolean}} options - `pmrem: true` (the default) marks it as a PMREM,
 *   for a `--target three` specular.ktx2; `false` for a plain cube (a `cubemap --target
 *   three` skybox), which three re-filters if a material uses it.
 * @returns {Promise<CompressedCubeTexture>}
 */
export async function loadSplitsumCube(url, renderer, { pmrem = true } = {}) {
  const loader = new KTX2Loader().detectSupport(renderer);
  const flat = await loader.loadAsync(url);
  loader.dispose();
  if (!flat.mipmaps || flat.mipmaps.length === 0 || flat.mipmaps[0].data.length % 6 !== 0) {
    throw new Error(`${url}: not a splitsum KTX2 cube (six faces per level expected)`);
  }
  let type = flat.type;
  let decode = null;
  if (type === UnsignedInt5999Type) decode = unpackRgb9e5;
  else if (type === UnsignedInt101111Type) decode = unpackRg11b10f;
  else if (type !== HalfFloatType && type !== FloatType) {
    throw new Error(`${url}: unsupported pixel format (three type ${type})`);
  }
  if (decode) type = HalfFloatType;
  const faces = [];
  for (let f = 0; f < 6; f++) {
    const mipmaps = flat.mipmaps.map((m) => {
      const n = m.data.length / 6;
      const data = m.data.subarray(f * n, (f + 1) * n);
      return { data: decode ? toRgbaHalf(data, decode) : data, width: m.width, height: m.height };
    });
    faces.push({ mipmaps, width: mipmaps[0].width, height: mipmaps[0].height });
  }
  flat.dispose();
  const cube = new CompressedCubeTexture(faces, RGBAFormat, type);
  cube.minFilter = faces[0].mipmaps.length > 1 ? LinearMipmapLinearFilter : LinearFilter;
  cube.magFilter = LinearFilter;
  cube.generateMipmaps = false;
  cube.colorSpace = LinearSRGBColorSpace;
  cube.isPMREMTexture = pmrem;
  cube.name = pmrem ? 'splitsum PMREM' : 'splitsum cube';
  cube.needsUpdate = true;
  return cube;
}

/**
 * The SH of a splitsum sh.json as a THREE.LightProbe (radiance_sh9 is three's
 * SphericalHarmonics3 as it is: same basis, order and world axes).
 * @param {object} sh - parsed sh.json.
 * @returns {LightProbe}
 */
export function lightProbeFromSh(sh) {
  const harmonics = new SphericalHarmonics3().fromArray(sh.radiance_sh9.flat());
  return new LightProbe(harmonics, 1);
}

/**
 * Loads a `--target three` bake folder: specular.ktx2 as the PMREM environment,
 * sh.json (when written) as a LightProbe, and the manifest.
 * @param {string} dir - the bake's folder (URL), e.g. 'out/sky'.
 * @param {THREE.WebGLRenderer} renderer
 * @returns {Promise<{envMap: CompressedCubeTexture, lightProbe: LightProbe|null, manifest: object}>}
 */
export async function loadSplitsumBake(dir, renderer) {
  const manifest = await (await fetch(`${dir}/manifest.json`)).json();
  if (manifest.target?.name !== 'three') {
    throw new Error(`${dir}: baked for target '${manifest.target?.name}', not 'three' (bake with --target three)`);
  }
  const envMap = await loadSplitsumCube(`${dir}/specular.ktx2`, renderer);
  const hasSh = manifest.outputs.some((o) => o.file === 'sh.json');
  const lightProbe = hasSh
    ? lightProbeFromSh(await (await fetch(`${dir}/sh.json`)).json())
    : null;
  return { envMap, lightProbe, manifest };
}
