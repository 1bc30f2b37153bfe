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
//   bake.areaLights.forEach((l) => scene.add(l)); // a studio's lamps as RectAreaLights
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
// only for RGBA data. The block formats are read here (three's ktx-parse and zstddec) and
// uploaded compressed: BC6H (`--pixel-format bc6h`, which KTX2Loader r187 has no entry
// for) as RGB_BPTC_UNSIGNED_Format, 1 byte a texel in video memory, where the WebGL
// extension EXT_texture_compression_bptc is (desktop GPUs; not most phones); ASTC HDR
// (`--pixel-format astc-4x4-hdr` or `astc-6x6-hdr`) as RGBA_ASTC_4x4_Format or
// RGBA_ASTC_6x6_Format with half-float results, where WEBGL_compressed_texture_astc lists
// the "hdr" profile (phones, Apple GPUs). Without its extension the loader throws an Error
// that says so; `pickSplitsumBake` chooses, among bakes of one HDRI in several formats,
// the first this renderer samples.

import {
  CompressedCubeTexture,
  DataUtils,
  DirectionalLight,
  RGB_BPTC_UNSIGNED_Format,
  RGBA_ASTC_4x4_Format,
  RGBA_ASTC_6x6_Format,
  UnsignedByteType,
  FloatType,
  HalfFloatType,
  LightProbe,
  LinearFilter,
  LinearMipmapLinearFilter,
  LinearSRGBColorSpace,
  Matrix4,
  RectAreaLight,
  RGBAFormat,
  ShaderChunk,
  SphericalHarmonics3,
  UnsignedInt101111Type,
  UnsignedInt5999Type,
  Vector3,
} from 'three';
import { KTX2Loader } from 'three/addons/loaders/KTX2Loader.js';
import { RectAreaLightUniformsLib } from 'three/addons/lights/RectAreaLightUniformsLib.js';
import {
  read as readKtx2,
  KHR_SUPERCOMPRESSION_NONE,
  KHR_SUPERCOMPRESSION_ZSTD,
  VK_FORMAT_ASTC_4x4_SFLOAT_BLOCK_EXT,
  VK_FORMAT_ASTC_6x6_SFLOAT_BLOCK_EXT,
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

/**
 * Whether `renderer` can sample ASTC HDR textures (WEBGL_compressed_texture_astc with the
 * "hdr" profile, as three's KTX2Loader tests it).
 * @param {THREE.WebGLRenderer} renderer
 * @returns {boolean}
 */
export function supportsAstcHdr(renderer) {
  return (
    renderer.extensions.has('WEBGL_compressed_texture_astc') &&
    renderer.extensions.get('WEBGL_compressed_texture_astc').getSupportedProfiles().includes('hdr')
  );
}

// The block formats splitsum writes: by KTX2 vkFormat, by its `--pixel-format` name, three's
// format and type for them, what a renderer needs to sample them, and whether it has it.
const BLOCK_FORMATS = [
  {
    vkFormat: VK_FORMAT_BC6H_UFLOAT_BLOCK,
    name: 'bc6h',
    format: RGB_BPTC_UNSIGNED_Format,
    type: UnsignedByteType,
    needs: 'the WebGL extension EXT_texture_compression_bptc',
    supported: supportsBc6h,
  },
  ...[
    [VK_FORMAT_ASTC_4x4_SFLOAT_BLOCK_EXT, 'astc-4x4-hdr', RGBA_ASTC_4x4_Format],
    [VK_FORMAT_ASTC_6x6_SFLOAT_BLOCK_EXT, 'astc-6x6-hdr', RGBA_ASTC_6x6_Format],
  ].map(([vkFormat, name, format]) => ({
    vkFormat,
    name,
    format,
    type: HalfFloatType,
    needs: 'the WebGL extension WEBGL_compressed_texture_astc with its "hdr" profile',
    supported: supportsAstcHdr,
  })),
];

/**
 * Among bakes of one HDRI in several pixel formats, the first `renderer` can sample: list
 * the smallest first (for example an astc-6x6-hdr bake, a bc6h one, then an rgb9e5 one
 * that every WebGL 2 context samples) and each GPU gets the best it can use.
 * @param {THREE.WebGLRenderer} renderer
 * @param {Array<{url: string, pixelFormat: string}>} bakes - each bake's folder (or
 *   file) and its `--pixel-format` (the manifest's `parameters.pixel_format`).
 * @returns {string} the chosen bake's url.
 */
export function pickSplitsumBake(renderer, bakes) {
  const usable = bakes.find(({ pixelFormat }) => {
    const block = BLOCK_FORMATS.find((b) => b.name === pixelFormat);
    return !block || block.supported(renderer);
  });
  if (!usable) {
    throw new Error(
      `none of the bakes (${bakes.map((b) => b.pixelFormat).join(', ')}) is in a format this GPU or browser samples; add an rgba16f or rgb9e5 bake`,
    );
  }
  return usable.url;
}

// A block-format KTX2 cube (ktx-parse's container) as a CompressedCubeTexture of its blocks.
async function blockCube(url, container, renderer, block) {
  if (!block.supported(renderer)) {
    throw new Error(
      `${url}: ${block.name} needs ${block.needs}, which this GPU or browser does not have; ` +
        'bake with --pixel-format rgba16f or rgb9e5 for it, or choose among bakes with pickSplitsumBake',
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
    block.format,
    block.type,
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
  const block = BLOCK_FORMATS.find((b) => b.vkFormat === container.vkFormat);
  const cube = block
    ? await blockCube(url, container, renderer, block)
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

// three r187's RE_Direct_RectArea_Physical (lights_physical_pars_fragment) as it ships, and
// what compensateRectAreaLights puts in its place.
const RECT_SPECULAR = 'reflectedLight.directSpecular += lightColor * fresnel * LTC_Evaluate( normal, viewDir, position, mInv, rectCoords );';
const RECT_DIFFUSE = 'reflectedLight.directDiffuse += lightColor * material.diffuseContribution * LTC_Evaluate( normal, viewDir, position, mat3( 1.0 ), rectCoords );';
const RECT_COMPENSATED = `// splitsum (js/splitsum-three.js, compensateRectAreaLights): the LTC as a control
		// variate, the multiple-scattering compensation and the Fresnel-weighted diffuse of
		// RE_Direct_Physical, as splitsum's preview shades an area light (plan::ltc::shade_polygon).
		{
			// The rectangle's centre and its solid angle (two spherical triangles, Van Oosterom
			// and Strackee 1983).
			vec3 splitsumC = normalize( lightPos - position );
			vec3 splitsumP[ 4 ];
			for ( int i = 0; i < 4; i ++ ) splitsumP[ i ] = normalize( rectCoords[ i ] - position );
			float splitsumOmega = 0.0;
			for ( int i = 1; i < 3; i ++ ) {
				vec3 a = splitsumP[ 0 ], b = splitsumP[ i ], c = splitsumP[ i + 1 ];
				splitsumOmega += 2.0 * atan( abs( dot( a, cross( b, c ) ) ), 1.0 + dot( a, b ) + dot( b, c ) + dot( c, a ) );
			}
			// The LTC's density at the centre: D_o(M^-1 c / |M^-1 c|) |det M^-1| / |M^-1 c|^3.
			vec3 splitsumT1 = normalize( viewDir - normal * dot( viewDir, normal ) );
			vec3 splitsumT2 = - cross( normal, splitsumT1 );
			vec3 splitsumLo = mInv * ( transpose( mat3( splitsumT1, splitsumT2, normal ) ) * splitsumC );
			float splitsumLen = length( splitsumLo );
			float splitsumDensity = max( splitsumLo.z / splitsumLen, 0.0 ) * RECIPROCAL_PI * abs( determinant( mInv ) ) / ( splitsumLen * splitsumLen * splitsumLen );
			// The exact BRDF at the centre, weighted by how small the light is against the lobe.
			float splitsumAlpha = pow2( max( roughness, 0.045 ) );
			float splitsumLobe = 4.0 * PI * splitsumAlpha * splitsumAlpha;
			float splitsumBeta = splitsumLobe / ( splitsumLobe + splitsumOmega );
			vec3 splitsumPoint = BRDF_GGX( splitsumC, viewDir, normal, material ) * saturate( dot( normal, splitsumC ) ) * splitsumOmega;
			vec3 splitsumLtc = fresnel * LTC_Evaluate( normal, viewDir, position, mInv, rectCoords );
			vec3 splitsumSpecular = max( splitsumLtc + splitsumBeta * ( splitsumPoint - fresnel * splitsumDensity * splitsumOmega ), 0.0 );
			float splitsumEss = material.dfg.x + material.dfg.y;
			vec3 splitsumCompensation = 1.0 + material.specularColorBlended * ( 1.0 / splitsumEss - 1.0 );
			reflectedLight.directSpecular += lightColor * splitsumSpecular * splitsumCompensation;
			float splitsumVH = saturate( dot( viewDir, normalize( splitsumC + viewDir ) ) );
			vec3 splitsumF = F_Schlick( material.specularColor, material.specularF90, splitsumVH );
			reflectedLight.directDiffuse += lightColor * material.diffuseContribution * LTC_Evaluate( normal, viewDir, position, mat3( 1.0 ), rectCoords ) * ( 1.0 - splitsumF );
		}`;

/**
 * Shades three's RectAreaLight as splitsum's preview shades an area light, with the BRDF
 * three's punctual lights have. three r187's RE_Direct_RectArea_Physical shades the
 * specular from its LTC table alone, whose fit is 8–10 % off the GGX lobe at r ≥ 0.35
 * (tests/ltc.rs), and leaves out two terms that RE_Direct_Physical (a DirectionalLight)
 * applies: the specular's multiple-scattering compensation 1 + F0 (1 / (A + B) − 1) and the
 * diffuse's weight 1 − F(v·h). Without them a white metal sphere at r = 1 under a studio
 * lamp gets 45 % of the lamp's light and a dielectric 5 % too much (docs/targets.md, "Area
 * lights"). This replaces those two lines of THREE.ShaderChunk.lights_physical_pars_fragment:
 * the specular is the LTC plus β (the exact BRDF at the rectangle's centre − the LTC there)
 * times its solid angle, β = 4πα² / (4πα² + Ω), compensated; the diffuse weighted at the
 * centre. Call it before the first render that compiles a material lit by a RectAreaLight.
 * It is idempotent, and throws where the chunk is not r187's.
 */
export function compensateRectAreaLights() {
  const chunk = ShaderChunk.lights_physical_pars_fragment;
  if (chunk.includes(RECT_COMPENSATED)) return;
  if (!chunk.includes(RECT_SPECULAR) || !chunk.includes(RECT_DIFFUSE)) {
    throw new Error(
      "compensateRectAreaLights: this three.js's lights_physical_pars_fragment is not r187's; " +
        'load the bake with { compensateAreaLights: false } (its RectAreaLights then lack the compensation)',
    );
  }
  ShaderChunk.lights_physical_pars_fragment = chunk.replace(RECT_DIFFUSE, '').replace(RECT_SPECULAR, RECT_COMPENSATED);
}

/**
 * An area light of a splitsum sun.json (a light with `rect_light`: a studio's lamp or soft
 * box) as a THREE.RectAreaLight: the rectangle facing the origin from `distance` away along
 * `direction`, 2·distance·tan(half_width_deg) wide along `width_axis` and
 * 2·distance·tan(half_height_deg) high, of the radiance `rect_light.radiance` (three's
 * RectAreaLight shines its colour × intensity as radiance from its local −z side), which
 * gives the origin the light's irradiance. A point p away from the origin sees it off by
 * about 2·(p·direction)/distance in irradiance, so keep `distance` well beyond the scene.
 * Calls RectAreaLightUniformsLib.init() (three's LTC tables), which RectAreaLight needs.
 * RectAreaLight casts no shadows.
 * @param {object} light - sun.json, or an entry of its additional_lights, with rect_light.
 * @param {{distance?: number}} options
 * @returns {RectAreaLight}
 */
export function rectAreaLightFromSun(light, { distance = 100 } = {}) {
  const rect = light.rect_light;
  if (!rect) throw new Error('rectAreaLightFromSun: this light has no rect_light (a directional light: directionalLightFromSun)');
  RectAreaLightUniformsLib.init();
  const tan = (deg) => Math.tan((deg * Math.PI) / 180);
  const area = new RectAreaLight(0xffffff, rect.luminance, 2 * distance * tan(rect.half_width_deg), 2 * distance * tan(rect.half_height_deg));
  if (rect.luminance > 0) {
    const [r, g, b] = rect.radiance;
    area.color.setRGB(r / rect.luminance, g / rect.luminance, b / rect.luminance, LinearSRGBColorSpace);
  }
  // Local x along the width, local z toward the light (it shines along −z), y = z × x.
  const z = new Vector3(...light.direction).normalize();
  const x = new Vector3(...rect.width_axis).normalize();
  const y = new Vector3().crossVectors(z, x);
  area.quaternion.setFromRotationMatrix(new Matrix4().makeBasis(x, y, z));
  area.position.copy(z).multiplyScalar(distance);
  area.name = 'splitsum area light';
  return area;
}

/**
 * Loads a `--target three` bake folder: specular.ktx2 as the PMREM environment,
 * sh.json (when written) as a LightProbe, and the manifest. A `--sun split` bake that
 * took lights out also gives them: each area light (a studio's lamp, a soft box: a light
 * with `rect_light`) in `areaLights` as a RectAreaLight (rectAreaLightFromSun, at
 * `areaDistance`), the first directional light in `sunLight` (shadow-casting, see
 * directionalLightFromSun) and the further ones in `lights` (without shadows), and
 * `background` (background.ktx2: the environment as seen, the lights in it, for
 * `scene.background`); they are null or empty otherwise. With area lights it calls
 * compensateRectAreaLights (`compensateAreaLights: false` leaves three's shader as it is).
 * With `areaLights: false` every light is a directional light of the same irradiance
 * (shadows, but a lamp's highlight the size of a point).
 * @param {string} dir - the bake's folder (URL), e.g. 'out/sky'.
 * @param {THREE.WebGLRenderer} renderer
 * @param {{areaLights?: boolean, areaDistance?: number, compensateAreaLights?: boolean}} options
 * @returns {Promise<{envMap: CompressedCubeTexture, lightProbe: LightProbe|null, sunLight: DirectionalLight|null, lights: DirectionalLight[], areaLights: RectAreaLight[], background: CompressedCubeTexture|null, manifest: object}>}
 */
export async function loadSplitsumBake(dir, renderer, { areaLights = true, areaDistance = 100, compensateAreaLights = true } = {}) {
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
  const areas = [];
  if (has('sun.json')) {
    const sun = await (await fetch(`${dir}/sun.json`)).json();
    const all = [sun, ...(sun.additional_lights ?? [])];
    const directional = [];
    for (const light of all) {
      if (areaLights && light.rect_light) areas.push(rectAreaLightFromSun(light, { distance: areaDistance }));
      else directional.push(light);
    }
    if (areas.length > 0 && compensateAreaLights) compensateRectAreaLights();
    if (directional.length > 0) {
      sunLight = directionalLightFromSun(directional[0]);
      lights = directional.slice(1).map((l) => directionalLightFromSun(l, { shadows: false }));
    }
  }
  const background = has('background.ktx2')
    ? await loadSplitsumCube(`${dir}/background.ktx2`, renderer, { pmrem: false })
    : null;
  return { envMap, lightProbe, sunLight, lights, areaLights: areas, background, manifest };
}
