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
//   if (bake.sunLight) {        // a `--sun split` bake: the sun, taken out of the IBL
//     renderer.shadowMap.enabled = true;
//     scene.add(bake.sunLight, bake.sunLight.target);
//     scene.background = bake.background; // the sky as seen, the sun in it
//   }
//
// Why a loader of its own: KTX2Loader (r187) returns a cube KTX2 in an uncompressed format
// as a 2D DataTexture whose levels hold the six faces one after another, with Nearest
// filtering; used as it is, the background is one flat face and every sphere is black.
// This module splits each level into faces and builds a cube with trilinear filtering.
//
// Formats: rgba16f and rgba32f are uploaded as they are (rgba32f needs
// OES_texture_float_linear to be filtered); rgb9e5 and rg11b10f are decoded to rgba16f,
// since three.js uploads uncompressed cube mips through the CompressedCubeTexture path
// only for RGBA data. BC6H (`--pixel-format bc6h`), which KTX2Loader r187 has no entry
// for, is read here (three's ktx-parse and zstddec) and uploaded compressed as
// RGB_BPTC_UNSIGNED_Format: 1 byte a texel in video memory. It needs the WebGL extension
// EXT_texture_compression_bptc (desktop GPUs; not most phones): without it the loader
// throws an Error that says so, and a page can load an rgba16f or rgb9e5 bake instead.

import {
  CompressedCubeTexture,
  DataUtils,
  DirectionalLight,
  RGB_BPTC_UNSIGNED_Format,
  UnsignedByteType,
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
import {
  read as readKtx2,
  KHR_SUPERCOMPRESSION_NONE,
  KHR_SUPERCOMPRESSION_ZSTD,
  VK_FORMAT_BC6H_UFLOAT_BLOCK,
} from 'three/addons/libs/ktx-parse.module.js';
import { ZSTDDecoder } from 'three/addons/libs/zstddec.module.js';

/**
 * Whether `renderer` can sample BC6H textures (EXT_texture_compression_bptc).
 * @param {THREE.WebGLRenderer} renderer
 * @returns {boolean}
 */
export function supportsBc6h(renderer) {
  return renderer.extensions.has('EXT_texture_compression_bptc');
}

// A BC6H KTX2 cube (ktx-parse's container) as a CompressedCubeTexture of its blocks.
async function bc6hCube(url, container, renderer) {
  if (!supportsBc6h(renderer)) {
    throw new Error(
      `${url}: BC6H needs the WebGL extension EXT_texture_compression_bptc, which this GPU or browser does not have; ` +
        'bake with --pixel-format rgba16f or rgb9e5 for it, or fall back to such a bake when this throws',
    );
  }
  let zstd = null;
  if (container.supercompressionScheme === KHR_SUPERCOMPRESSION_ZSTD) {
    zstd = new ZSTDDecoder();
    await zstd.init();
  } else if (container.supercompressionScheme !== KHR_SUPERCOMPRESSION_NONE) {
    throw new Error(`${url}: supercompression ${container.supercompressionScheme} is not one splitsum writes`);
  }
  const faces = [[], [], [], [], [], []];
  container.levels.forEach((level, m) => {
    const data = zstd ? zstd.decode(level.levelData, level.uncompressedByteLength) : level.levelData;
    const n = Math.max(1, container.pixelWidth >> m);
    const faceBytes = data.byteLength / 6;
    for (let f = 0; f < 6; f++) {
      faces[f].push({ data: data.subarray(f * faceBytes, (f + 1) * faceBytes), width: n, height: n });
    }
  });
  return new CompressedCubeTexture(
    faces.map((mipmaps) => ({ mipmaps, width: mipmaps[0].width, height: mipmaps[0].height })),
    RGB_BPTC_UNSIGNED_Format,
    UnsignedByteType,
  );
}

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
  const bytes = new Uint8Array(await (await fetch(url)).arrayBuffer());
  const container = readKtx2(bytes);
  const cube =
    container.vkFormat === VK_FORMAT_BC6H_UFLOAT_BLOCK
      ? await bc6hCube(url, container, renderer)
      : await uncompressedCube(url, bytes, renderer);
  cube.minFilter = cube.image[0].mipmaps.length > 1 ? LinearMipmapLinearFilter : LinearFilter;
  cube.magFilter = LinearFilter;
  cube.generateMipmaps = false;
  cube.colorSpace = LinearSRGBColorSpace;
  cube.isPMREMTexture = pmrem;
  cube.name = pmrem ? 'splitsum PMREM' : 'splitsum cube';
  cube.needsUpdate = true;
  return cube;
}

// An uncompressed KTX2 cube through KTX2Loader, its flat levels split into faces.
async function uncompressedCube(url, bytes, renderer) {
  const loader = new KTX2Loader().detectSupport(renderer);
  const flat = await new Promise((resolve, reject) => loader.parse(bytes.buffer, resolve, reject));
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
  return new CompressedCubeTexture(faces, RGBAFormat, type);
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
 * A light of a splitsum sun.json (the sun, or one of its `additional_lights`) as a
 * THREE.DirectionalLight with the same irradiance: three shades a directional light of
 * colour c and intensity I with the irradiance c·I on a surface facing it, in the units
 * its environment's radiance is in, so the light is `illuminance` (E's luminance) in
 * intensity and E / illuminance (linear, components above 1 allowed) in colour. It shines
 * from `direction` toward the origin, from `distance` away; with `shadows` it casts them
 * through a `shadowMapSize`² map whose orthographic camera spans ±`shadowExtent` about
 * the origin (fit `light.shadow.camera` to a scene of another size).
 * @param {object} light - sun.json, or an entry of its additional_lights.
 * @param {{distance?: number, shadows?: boolean, shadowMapSize?: number, shadowExtent?: number}} options
 * @returns {DirectionalLight}
 */
export function directionalLightFromSun(light, { distance = 50, shadows = true, shadowMapSize = 2048, shadowExtent = 10 } = {}) {
  const e = light.irradiance;
  const illuminance = light.illuminance;
  const sun = new DirectionalLight(0xffffff, illuminance);
  if (illuminance > 0) {
    sun.color.setRGB(e[0] / illuminance, e[1] / illuminance, e[2] / illuminance, LinearSRGBColorSpace);
  }
  const [x, y, z] = light.direction;
  sun.position.set(x * distance, y * distance, z * distance);
  sun.target.position.set(0, 0, 0);
  sun.name = 'splitsum sun';
  if (shadows) {
    sun.castShadow = true;
    sun.shadow.mapSize.set(shadowMapSize, shadowMapSize);
    const cam = sun.shadow.camera;
    cam.left = -shadowExtent;
    cam.right = shadowExtent;
    cam.top = shadowExtent;
    cam.bottom = -shadowExtent;
    cam.near = Math.max(distance - 2 * shadowExtent, 0.1);
    cam.far = distance + 2 * shadowExtent;
    cam.updateProjectionMatrix();
    // One shadow-map texel of depth (the map spans 2·shadowExtent) keeps a lit floor
    // free of acne at a grazing sun.
    sun.shadow.normalBias = (2 * shadowExtent) / shadowMapSize;
  }
  return sun;
}

/**
 * Loads a `--target three` bake folder: specular.ktx2 as the PMREM environment,
 * sh.json (when written) as a LightProbe, and the manifest. A `--sun split` bake that
 * found a sun also gives `sunLight` (a shadow-casting DirectionalLight, see
 * directionalLightFromSun), `lights` (the further compact lights taken out, without
 * shadows) and `background` (background.ktx2: the environment as seen, the sun in it, for
 * `scene.background`); they are null (lights empty) otherwise.
 * @param {string} dir - the bake's folder (URL), e.g. 'out/sky'.
 * @param {THREE.WebGLRenderer} renderer
 * @returns {Promise<{envMap: CompressedCubeTexture, lightProbe: LightProbe|null, sunLight: DirectionalLight|null, lights: DirectionalLight[], background: CompressedCubeTexture|null, manifest: object}>}
 */
export async function loadSplitsumBake(dir, renderer) {
  const manifest = await (await fetch(`${dir}/manifest.json`)).json();
  if (manifest.target?.name !== 'three') {
    throw new Error(`${dir}: baked for target '${manifest.target?.name}', not 'three' (bake with --target three)`);
  }
  const has = (file) => manifest.outputs.some((o) => o.file === file);
  const envMap = await loadSplitsumCube(`${dir}/specular.ktx2`, renderer);
  const lightProbe = has('sh.json')
    ? lightProbeFromSh(await (await fetch(`${dir}/sh.json`)).json())
    : null;
  let sunLight = null;
  let lights = [];
  if (has('sun.json')) {
    const sun = await (await fetch(`${dir}/sun.json`)).json();
    sunLight = directionalLightFromSun(sun);
    lights = (sun.additional_lights ?? []).map((l) => directionalLightFromSun(l, { shadows: false }));
  }
  const background = has('background.ktx2')
    ? await loadSplitsumCube(`${dir}/background.ktx2`, renderer, { pmrem: false })
    : null;
  return { envMap, lightProbe, sunLight, lights, background, manifest };
}
