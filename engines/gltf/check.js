// Runs in the page: renders with the glTF Sample Viewer's own renderer (npm
// @khronosgroup/gltf-viewer 1.1.0: GltfView, GltfState, ResourceLoader) a generated sphere
// glTF under two environments: the viewer's own, which it filters at run time from the HDRI
// (ResourceLoader.loadEnvironment: its iblSampler, 256² to 16², r = m/4), and splitsum's
// `--target gltf` files, loaded through the viewer's own KTX2 path (its libktx decoder, the
// one it uses for KTX2 glTF textures) into the environment the viewer built, in place of
// its run-time textures.
//
// The viewer renders to an 8-bit canvas: tone mapping "None" (exposure × radiance, then
// pow(1/2.2)), each render's exposure lowered until nothing clips, decoded back with
// pow(2.2) (a self-check compares two exposures).
import { GltfView, GltfState, ResourceLoader } from '/engines/gltf/node_modules/@khronosgroup/gltf-viewer/dist/gltf-viewer.module.js';
import * as measure from '/engines/measure.js';
import { sphereGlb } from '/engines/sphere.js';

const LIBS = '/engines/gltf/node_modules/@khronosgroup/gltf-viewer/dist/libs/';
const { SIZE, MIRROR_SIZE, SPHERE_DISTANCE, SPHERE_FOV, SKY_FOV, scale, degrees, pinhole, pixelRay } = measure;
// The brute-force Lambertian cube's size: E/π is smooth enough that a 16² cube read
// bilinearly holds it (a point sun's cosine lobe bends by (5.6°)²/8 ≈ 0.1 % between texels).
const TRUTH_SIZE = 16;
// The viewer's linearTosRGB: pow(color, 1/2.2).
const DECODE = Float32Array.from({ length: 256 }, (_, i) => (i / 255) ** 2.2);

const canvas = measure.pageCanvas(MIRROR_SIZE);
const gl = canvas.getContext('webgl2', { preserveDrawingBuffer: true, antialias: false, alpha: false });
const view = new GltfView(gl);
const state = view.createState();
// The resource loader with the viewer's KTX2 decoder (libktx) and no Draco, which a
// generated sphere does not need.
const loader = new ResourceLoader(view, LIBS);
loader.initKtxLib(window.LIBKTX);
state.renderingParameters.toneMap = GltfState.ToneMaps.NONE;
state.renderingParameters.blurEnvironmentMap = false;
state.renderingParameters.clearColor = [0, 0, 0, 255];
state.renderingParameters.internalMSAA = 1;

// A camera for the viewer: its UserCamera's transform is the camera-to-world matrix
// (column-major, looking along −z), set directly: UserCamera.lookAt stores gl-matrix's
// lookAt, a world-to-camera matrix, which the renderer inverts once more.
function aim(cam) {
  state.userCamera.setVerticalFoV((cam.fov * Math.PI) / 180);
  const [r, u, f, e] = [cam.right, cam.up, cam.forward, cam.eye];
  state.userCamera.transform = new Float32Array([
    r[0], r[1], r[2], 0, u[0], u[1], u[2], 0, -f[0], -f[1], -f[2], 0, e[0], e[1], e[2], 1,
  ]);
}

async function renderAt(cam, size, e) {
  aim(cam);
  state.renderingParameters.exposure = e;
  canvas.width = canvas.height = size;
  view.renderFrame(state, size, size);
  const bytes = new Uint8Array(size * size * 4);
  gl.bindFramebuffer(gl.READ_FRAMEBUFFER, null);
  gl.readPixels(0, 0, size, size, gl.RGBA, gl.UNSIGNED_BYTE, bytes);
  return measure.decode8(bytes, DECODE, e);
}

// Renders with the exposure lowered until nothing clips, at most 14 times 8× (the sun may
// stay clipped: then its centroid is the saturated disc's).
const render = (cam, size, e0) => measure.renderUnclipped((e) => renderAt(cam, size, e), e0, e0 / 8 ** 14);

// The level-0 texels of a cube texture the viewer holds (RGBA float).
function readCube(texture, size) {
  const fb = gl.createFramebuffer();
  gl.bindFramebuffer(gl.FRAMEBUFFER, fb);
  const faces = [];
  for (let f = 0; f < 6; f++) {
    gl.framebufferTexture2D(gl.FRAMEBUFFER, gl.COLOR_ATTACHMENT0, gl.TEXTURE_CUBE_MAP_POSITIVE_X + f, texture, 0);
    const px = new Float32Array(size * size * 4);
    gl.readPixels(0, 0, size, size, gl.RGBA, gl.FLOAT, px);
    faces.push(px);
  }
  gl.bindFramebuffer(gl.FRAMEBUFFER, null);
  gl.deleteFramebuffer(fb);
  return faces;
}

async function image(url) {
  const img = new Image();
  img.src = url;
  await img.decode();
  return img;
}

// The viewer's environment with splitsum's files in place of its run-time textures: the
// images the viewer made (0 Lambertian, 1 GGX, 2 Charlie, 3 lut_ggx, 4 lut_charlie,
// 5 lut_sheen_E) become splitsum's, the cubes through the viewer's KTX2 decoder with the
// filtering the viewer gives its own cubes (iblSampler.createCubemapTexture: trilinear for
// the chains, bilinear for the Lambertian cube; the viewer's texture setup would force
// environment cubes to one level), the LUTs as PNG images it uploads itself.
// A copy of the viewer's environment object (a glTF), with its own image and texture
// objects, so that cubes can be swapped in it; the viewer's filtering runs once, for its own
// path.
function copyEnvironment(own) {
  const copy = (o) => Object.assign(Object.create(Object.getPrototypeOf(o)), o);
  const env = copy(own);
  env.images = own.images.map(copy);
  env.textures = own.textures.map(copy);
  return env;
}

// Makes cube texture `texture` image k of `env`, with the filtering the viewer gives its own.
function setCube(env, k, texture, minFilter) {
  gl.bindTexture(gl.TEXTURE_CUBE_MAP, texture);
  gl.texParameteri(gl.TEXTURE_CUBE_MAP, gl.TEXTURE_MIN_FILTER, minFilter);
  gl.texParameteri(gl.TEXTURE_CUBE_MAP, gl.TEXTURE_MAG_FILTER, gl.LINEAR);
  gl.texParameteri(gl.TEXTURE_CUBE_MAP, gl.TEXTURE_WRAP_S, gl.CLAMP_TO_EDGE);
  gl.texParameteri(gl.TEXTURE_CUBE_MAP, gl.TEXTURE_WRAP_T, gl.CLAMP_TO_EDGE);
  env.images[k].image = texture;
  env.textures[k].glTexture = undefined;
  env.textures[k].initialized = true;
}

async function withSplitsumFiles(own, dir, levels) {
  const env = copyEnvironment(own);
  const cube = async (k, file, minFilter) => setCube(env, k, await view.ktxDecoder.loadKtxFromUri(`${dir}/${file}`), minFilter);
  const swap = (k, mimeType, content) => {
    env.images[k].image = content;
    env.images[k].mimeType = mimeType;
    env.textures[k].glTexture = undefined;
    env.textures[k].initialized = false;
  };
  await cube(0, 'lambertian/diffuse.ktx2', gl.LINEAR);
  await cube(1, 'ggx/specular.ktx2', gl.LINEAR_MIPMAP_LINEAR);
  await cube(2, 'charlie/sheen.ktx2', gl.LINEAR_MIPMAP_LINEAR);
  swap(3, 'image/png', await image(`${dir}/lut_ggx.png`));
  swap(4, 'image/png', await image(`${dir}/lut_charlie.png`));
  env.mipCount = levels;
  env.iblIntensityScale = 1;
  return env;
}

window.runCheck = async function ({ hdrUrl, dir, controlDir, levels, roughness, splitDir }) {
  const luts = { lut_sheen_E_file: `${dir}/lut_sheen_E.png` };
  const own = await loader.loadEnvironment(hdrUrl, luts);
  const ours = await withSplitsumFiles(own, dir, levels);
  const control = await withSplitsumFiles(own, controlDir, levels);
  // One sphere glTF per material, loaded by the viewer (it bakes the factors into the
  // material's uniforms at load).
  const spheres = new Map();
  const setSphere = async (metallic, r) => {
    const key = `${metallic}/${r}`;
    if (!spheres.has(key)) spheres.set(key, await loader.loadGltf(sphereGlb(metallic, r).buffer));
    state.gltf = spheres.get(key);
  };
  await setSphere(1, 0);
  const ownFaces = readCube(own.images[1].image, 256);
  const ourFaces = readCube(ours.textures[1].glTexture ?? ours.images[1].image, 256);
  const ownStats = measure.cubeStats(ownFaces, 256), ourStats = measure.cubeStats(ourFaces, 256);
  // The viewer samples its cubes at u_EnvRotation · d, a turn of environmentRotation
  // (default 90°) about +Y (gl-matrix rotateY): the cube's sun seen from the world.
  const turn = (state.renderingParameters.environmentRotation * Math.PI) / 180;
  const [cx, cy, cz] = ownStats.sun;
  const sun = [Math.cos(turn) * cx - Math.sin(turn) * cz, cy, Math.sin(turn) * cx + Math.cos(turn) * cz];
  // The Lambertian cubes (E/π): the viewer's 256² and splitsum's 32², mean over the sphere.
  const ownLambertian = readCube(own.images[0].image, 256), ourLambertian = readCube(ours.images[0].image, 32);
  // Each Lambertian cube against a brute-force E/π of the radiance cube it stands for (the
  // level-0 GGX cube as the viewer holds it: the viewer filters its own from that cube), at
  // texel centres: the viewer's 256² cube at those of a 16² cube (1536 directions),
  // splitsum's 32² one at every other texel centre of its own (1536).
  const dirs = measure.cubeDirections(TRUTH_SIZE);
  const ownTruth = measure.bruteIrradiance(ownFaces, 256, dirs);
  const ourDirs = measure.cubeDirections(32).filter((_, k) => k % 2 === 1 && Math.floor(k / 32) % 2 === 1);
  const lambertian = {
    viewer: measure.lambertianError(ownLambertian, 256, ownTruth, dirs),
    splitsum: measure.lambertianError(ourLambertian, 32, measure.bruteIrradiance(ourFaces, 256, ourDirs), ourDirs),
  };
  // The viewer's own path with its Lambertian filter replaced by that brute force: the
  // 16² cube of E/π of its own cube (bilinear, as the viewer filters its Lambertian cube).
  const ownExactDiffuse = copyEnvironment(own);
  const truthCube = gl.createTexture();
  gl.bindTexture(gl.TEXTURE_CUBE_MAP, truthCube);
  for (let f = 0; f < 6; f++) {
    const texels = ownTruth.slice(f * TRUTH_SIZE * TRUTH_SIZE, (f + 1) * TRUTH_SIZE * TRUTH_SIZE);
    const data = Float32Array.from(texels.flatMap(([r, g, b]) => [r, g, b, 1]));
    gl.texImage2D(gl.TEXTURE_CUBE_MAP_POSITIVE_X + f, 0, gl.RGBA16F, TRUTH_SIZE, TRUTH_SIZE, 0, gl.RGBA, gl.FLOAT, data);
  }
  gl.texParameteri(gl.TEXTURE_CUBE_MAP, gl.TEXTURE_MAX_LEVEL, 0);
  setCube(ownExactDiffuse, 0, truthCube, gl.LINEAR);
  const out = {
    sun,
    lambertian,
    irradianceRatio: measure.cubeStats(ourLambertian, 32).mean / measure.cubeStats(ownLambertian, 256).mean,
    cube: { correlation: measure.cubeCorrelation(ourFaces, ownFaces, 256), sunError: degrees(ourStats.sun, ownStats.sun), fluxRatio: ourStats.mean / ownStats.mean },
  };
  const images = {};

  // Linearity of the read-back.
  state.environment = own;
  const skyCam = pinhole([0, 0, 0], sun, SKY_FOV);
  const eSky = 0.6 / ownStats.mean;
  out.linearity = await measure.readbackLinearity((e) => renderAt(skyCam, SIZE, e), eSky, SIZE);

  // Where the viewer shows each environment's sun (the camera sits inside the sphere,
  // whose back faces are culled): the brightest of six 90° views, then the bright centroid
  // of a 50° view centred there.
  const findSun = (env, e) => {
    state.environment = env;
    return measure.locateSun(async (d, fov, size) => {
      const cam = pinhole([0, 0, 0], d, fov);
      const { px } = await render(cam, size, e);
      return { px, ray: (p) => pixelRay(cam, p, size) };
    }, SKY_FOV, SIZE);
  };
  const refSun = await findSun(own, 0.5 / ownStats.max);
  out.background = { sunError: degrees(await findSun(ours, 0.5 / ourStats.max), refSun) };
  out.control = { sunError: degrees(await findSun(control, 0.5 / ourStats.max), refSun) };
  state.environment = own;
  const refView = (await renderAt(skyCam, SIZE, eSky)).px;
  state.environment = ours;
  const gotView = (await renderAt(skyCam, SIZE, 0.6 / ourStats.mean)).px;
  out.background.logDiff = measure.logDiff(gotView, refView, SIZE);
  images.sky_viewer = measure.toPng(refView, SIZE);
  images.sky_splitsum = measure.toPng(gotView, SIZE);

  // Spheres, the camera 40° from the sun.
  const eye = scale(measure.turnedFrom(sun, 40), SPHERE_DISTANCE);
  const sphereCam = pinhole(eye, [0, 0, 0], SPHERE_FOV);
  let exposure = 0;
  const sphereAt = async (env, metallic, r, size, e) => {
    state.environment = env;
    await setSphere(metallic, r);
    const { px, clipped, exposure: used } = await render(sphereCam, size, e);
    if (clipped && r > 0) throw new Error(`sphere r = ${r} saturates`);
    exposure = used;
    return measure.maskSphere(px, eye, (p) => pixelRay(sphereCam, p, size), size);
  };
  const reflected = (px) => measure.mirrorSun(px, eye, (p) => pixelRay(sphereCam, p, MIRROR_SIZE), MIRROR_SIZE);
  const refMirror = await sphereAt(own, 1, 0, MIRROR_SIZE, 0.5 / ownStats.max);
  const gotMirror = await sphereAt(ours, 1, 0, MIRROR_SIZE, 0.5 / ourStats.max);
  out.mirror = { sunError: degrees(reflected(gotMirror), reflected(refMirror)), viewerVsCube: degrees(reflected(refMirror), sun) };
  out.background.viewerVsCube = degrees(refSun, sun);
  out.spheres = [];
  // The spheres as rendered from the bake (decoded to linear, RGBA float rows from the
  // bottom), for the preview's glTF mode to be held against (tests/engine_renders.rs): the
  // camera as measure.pinhole takes it, the viewer's environment rotation, and each
  // sphere's exposure (its 8-bit read-back decodes as (v/255)^2.2 / exposure).
  const raw = {};
  out.sphereCamera = { eye, fov: SPHERE_FOV, size: SIZE, environmentRotationDegrees: state.renderingParameters.environmentRotation, exposures: {} };
  for (const metallic of [1, 0]) {
    for (const r of roughness) {
      const want = await sphereAt(own, metallic, r, SIZE, 0.6 / ownStats.mean);
      const got = await sphereAt(ours, metallic, r, SIZE, 0.6 / ourStats.mean);
      raw[`sphere_m${metallic}_r${r}.rgba32f`] = measure.base64(got);
      out.sphereCamera.exposures[`sphere_m${metallic}_r${r}`] = exposure;
      const sphere = { metallic, roughness: r, ...measure.compareSpheres(got, want, SIZE) };
      if (!metallic) {
        const wantExact = await sphereAt(ownExactDiffuse, metallic, r, SIZE, 0.6 / ownStats.mean);
        sphere.exactDiffuse = measure.compareSpheres(got, wantExact, SIZE);
        images[`sphere_m${metallic}_r${r}_viewer_exact_diffuse`] = measure.toPng(wantExact, SIZE);
      }
      out.spheres.push(sphere);
      images[`sphere_m${metallic}_r${r}_viewer`] = measure.toPng(want, SIZE);
      images[`sphere_m${metallic}_r${r}_splitsum`] = measure.toPng(got, SIZE);
    }
  }
  if (splitDir) {
    // sun.gltf as the viewer loads a glTF, its light as the viewer's renderer builds the
    // light's uniform (gltfLight.toUniform: the node's world rotation of −Z).
    const lights = await loader.loadGltf(`${splitDir}/sun.gltf`);
    const scene = lights.scenes[lights.scene ?? 0];
    scene.applyTransformHierarchy(lights);
    const node = lights.nodes[scene.nodes[0]];
    const light = lights.lights[node.extensions.KHR_lights_punctual.light];
    const uniform = light.toUniform(node);
    const json = await (await fetch(`${splitDir}/sun.json`)).json();
    const [jx, jy, jz] = json.direction;
    const jsonWorld = [Math.cos(turn) * jx - Math.sin(turn) * jz, jy, Math.sin(turn) * jx + Math.cos(turn) * jz];
    const from = scale(Array.from(uniform.direction), -1);
    const e = Array.from(uniform.color).map((c) => c * uniform.intensity);
    out.sunLight = {
      lights: lights.lights.length,
      type: light.type,
      sunError: degrees(from, sun),
      jsonError: degrees(from, jsonWorld),
      irradianceError: Math.max(...e.map((c, i) => Math.abs(c / json.irradiance[i] - 1))),
    };
  }
  out.renderer = gl.getParameter(gl.VERSION);
  return { out, images, raw };
};

window.checkReady = true;
