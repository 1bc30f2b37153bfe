// Runs in the page: loads a splitsum `--target filament` bake and cmgen's deploy of the
// same HDRI into Filament (npm filament, its WebGL2 build) exactly as a Filament web app
// does (`engine.createIblFromKtx1`, `engine.createSkyFromKtx1`), renders the skybox and
// spheres with gltfio's own materials, and returns the measurements for check.mjs to judge.
//
// Filament's web build has no float read-back: the view renders with LINEAR tone mapping
// (so the output is exposure × radiance, sRGB-encoded into the 8-bit canvas), and each
// render's exposure is lowered until no pixel clips; the pixels are decoded back to linear
// radiance. A self-check renders the same view at two exposures and requires the decoded
// radiance to agree, so a non-linear output would fail the check rather than skew it.
import * as measure from '/engines/measure.js';
import { shadowSceneGlb, sphereGlb } from '/engines/sphere.js';
import { drawFrames } from '/engines/filament/frames.js';

const { SIZE, MIRROR_SIZE, SPHERE_DISTANCE, SPHERE_FOV, SKY_FOV, add, scale, degrees, pinhole, pixelRay } = measure;
// Filament's default intensity of a Skybox and an IndirectLight (FIndirectLight::
// DEFAULT_INTENSITY, lux); the web build's createSkyFromKtx1 keeps it, and the IBL is set to
// it, so both show radiance × INTENSITY × the camera's exposure.
const INTENSITY = 30000;

const canvas = measure.pageCanvas(MIRROR_SIZE);
await new Promise((ok) => Filament.init([], ok));
const engine = Filament.Engine.create(canvas, { preserveDrawingBuffer: true });
const gl = engine.context;
const renderer = engine.createRenderer();
const swapChain = engine.createSwapChain();
const camera = engine.createCamera(Filament.EntityManager.get().create());
const scene = engine.createScene();
const view = engine.createView();
view.setCamera(camera);
view.setScene(scene);
view.setAntiAliasing(Filament.View$AntiAliasing.NONE);
view.setColorGrading(
  Filament.ColorGrading.Builder().toneMapping(Filament.ColorGrading$ToneMapping.LINEAR).build(engine),
);
renderer.setClearOptions({ clearColor: [0, 0, 0, 1], clear: true });
const assetLoader = engine.createAssetLoader();

const srgbToLinear = (c) => (c <= 0.04045 ? c / 12.92 : ((c + 0.055) / 1.055) ** 2.4);
const SRGB = Float32Array.from({ length: 256 }, (_, i) => srgbToLinear(i / 255));

// Sets the camera's exposure (1 / (1.2 · 2^EV100)) to `exposure` through aperture N,
// shutter time t and sensitivity S, where exposure = t S / (120 N²) (Filament's
// Exposure::exposure). Not setExposureDirect: the web build's binding of it ends at
// 204800 ISO for any input. Filament clamps t to [1/25000, 60] s, N to [0.5, 64] and S to
// [10, 204800], so the exposure cannot go below MIN_EXPOSURE.
const MIN_EXPOSURE = ((1 / 25000) * 10) / (120 * 64 * 64);
function setExposure(exposure) {
  let aperture = 1, shutter = 1.2 * exposure, iso = 100;
  while (shutter < 1 / 25000 && aperture < 64) {
    aperture *= 2;
    shutter *= 4;
  }
  if (shutter < 1 / 25000) {
    iso = Math.max(10, (iso * shutter) * 25000);
    shutter = 1 / 25000;
  }
  camera.setExposure(aperture, shutter, iso);
}

// Renders the scene `size`² through `cam` with radiance scaled by `e` and returns linear radiance
// (RGBA float; alpha 0 where a channel saturates), reading Filament's 8-bit sRGB output
// after two frames (frames.js).
async function renderAt(cam, size, e) {
  view.setViewport([0, 0, size, size]);
  camera.setProjectionFov(cam.fov, 1, 0.05, 50, Filament.Camera$Fov.VERTICAL);
  camera.lookAt(cam.eye, add(cam.eye, cam.forward), cam.up);
  setExposure(e / INTENSITY);
  await drawFrames(engine, renderer, swapChain, view);
  const bytes = new Uint8Array(size * size * 4);
  const previous = gl.getParameter(gl.READ_FRAMEBUFFER_BINDING);
  gl.bindFramebuffer(gl.READ_FRAMEBUFFER, null);
  gl.readPixels(0, 0, size, size, gl.RGBA, gl.UNSIGNED_BYTE, bytes);
  gl.bindFramebuffer(gl.READ_FRAMEBUFFER, previous);
  return measure.decode8(bytes, SRGB, e);
}

// Renders with the exposure lowered until nothing clips or the exposure reaches Filament's
// least (a sun brighter than 1 / (INTENSITY · MIN_EXPOSURE) ≈ 41000 stays clipped).
const render = (cam, size, e0) => measure.renderUnclipped((e) => renderAt(cam, size, e), e0, MIN_EXPOSURE * INTENSITY);

async function loadSphere(metallic, roughness) {
  const asset = assetLoader.createAsset(sphereGlb(metallic, roughness));
  await new Promise((ok) => asset.loadResources(ok, null, null, 1));
  return asset;
}

// An unsigned float of R11F_G11F_B10F (5-bit exponent, `mantissaBits` mantissa).
function unpackUfloat(bits, mantissaBits) {
  const e = bits >> mantissaBits, m = bits & ((1 << mantissaBits) - 1);
  if (e === 0) return (m / (1 << mantissaBits)) * 2 ** -14;
  if (e === 31) return m ? NaN : Infinity;
  return (1 + m / (1 << mantissaBits)) * 2 ** (e - 15);
}

// Level 0 of a KTX 1 skybox (R11F_G11F_B10F, as cmgen and splitsum write it) as six RGBA
// float faces, and its measure.cubeStats.
function skyStats(bytes) {
  const dv = new DataView(bytes.buffer, bytes.byteOffset);
  const n = dv.getUint32(36, true);
  let p = 64 + dv.getUint32(60, true) + 4;
  const faces = [];
  for (let f = 0; f < 6; f++) {
    const face = new Float32Array(4 * n * n);
    for (let k = 0; k < n * n; k++, p += 4) {
      const w = dv.getUint32(p, true);
      face.set([unpackUfloat(w & 0x7ff, 6), unpackUfloat((w >> 11) & 0x7ff, 6), unpackUfloat(w >>> 22, 5), 1], 4 * k);
    }
    faces.push(face);
  }
  return measure.cubeStats(faces, n);
}

async function fetchBytes(url) {
  const r = await fetch(url);
  if (!r.ok) throw new Error(`${url}: HTTP ${r.status}`);
  return new Uint8Array(await r.arrayBuffer());
}

// One path's environment: the IBL as createIblFromKtx1 builds it (diffuse from the last
// level), the same reflections with the file's SH as irradiance, and the skybox.
async function loadPath({ ibl, sky }) {
  const iblBytes = await fetchBytes(ibl);
  const skyBytes = await fetchBytes(sky);
  const light = engine.createIblFromKtx1(iblBytes);
  light.setIntensity(INTENSITY);
  const withSh = Filament.IndirectLight.Builder()
    .reflections(light.getReflectionsTexture())
    .irradianceSh(3, light.shfloats)
    .intensity(INTENSITY)
    .build(engine);
  return { light, withSh, skybox: engine.createSkyFromKtx1(skyBytes), stats: skyStats(skyBytes), sh: light.shfloats };
}

window.runCheck = async function ({ splitsum, cmgen, fromCmgenCube, cmgenOfExact, control, roughness, split }) {
  const ours = await loadPath(splitsum);
  const ref = await loadPath(cmgen);
  const sun = ref.stats.sun; // the sun as Filament's own path (cmgen) places it
  const out = { sun };
  const images = {};

  // Linearity: the same view at exposures 1 and 1/4 decodes to the same radiance.
  scene.setSkybox(ref.skybox);
  scene.setIndirectLight(ref.light);
  const skyCam = pinhole([0, 0, 0], sun, SKY_FOV);
  const eSky = 0.6 / ref.stats.mean;
  out.linearity = await measure.readbackLinearity((e) => renderAt(skyCam, SIZE, e), eSky, SIZE);

  // Where Filament shows a path's sun: the brightest of six 90° views, then the bright
  // centroid of a 50° view centred there.
  const findSun = async (path) => {
    scene.setSkybox(path.skybox);
    scene.setIndirectLight(path.light);
    const e = 0.5 / path.stats.max;
    return measure.locateSun(async (d, fov, size) => {
      const cam = pinhole([0, 0, 0], d, fov);
      const { px } = await render(cam, size, e);
      return { px, ray: (p) => pixelRay(cam, p, size) };
    }, SKY_FOV, SIZE);
  };
  const refSun = await findSun(ref);
  const eView = (path) => 0.6 / path.stats.mean;
  // The view at the sun, exposed for the sky (the sun saturates and is left out).
  scene.setSkybox(ref.skybox);
  const refView = (await renderAt(skyCam, SIZE, eView(ref))).px;
  scene.setSkybox(ours.skybox);
  const gotView = (await renderAt(skyCam, SIZE, eView(ours))).px;
  out.background = {
    sunError: degrees(await findSun(ours), refSun),
    cmgenVsFile: degrees(refSun, sun),
    logDiff: measure.logDiff(gotView, refView, SIZE),
  };
  images.sky_cmgen = measure.toPng(refView, SIZE);
  images.sky_splitsum = measure.toPng(gotView, SIZE);
  // The negative control: the same environment in the generic orientation.
  const controlPath = { skybox: engine.createSkyFromKtx1(await fetchBytes(control)), light: ref.light, stats: ours.stats };
  out.control = { sunError: degrees(await findSun(controlPath), refSun) };
  scene.setSkybox(null);

  // Spheres: the camera 40° from the sun.
  const viewDir = measure.turnedFrom(sun, 40);
  const sphereCam = pinhole(scale(viewDir, SPHERE_DISTANCE), [0, 0, 0], SPHERE_FOV);
  const sphereAt = async (metallic, r, light, size, e) => {
    const asset = await loadSphere(metallic, r);
    scene.addEntities(asset.getEntities());
    scene.setIndirectLight(light);
    const { px, clipped } = await render(sphereCam, size, e);
    scene.removeEntities(asset.getEntities());
    assetLoader.destroyAsset(asset);
    if (clipped && r > 0) throw new Error(`sphere r = ${r} saturates at Filament's least exposure`);
    return measure.maskSphere(px, sphereCam.eye, (p) => pixelRay(sphereCam, p, size), size);
  };

  // The mirror sphere: the sun's reflection.
  const reflected = (px) => measure.mirrorSun(px, sphereCam.eye, (p) => pixelRay(sphereCam, p, MIRROR_SIZE), MIRROR_SIZE);
  const refMirror = await sphereAt(1, 0, ref.light, MIRROR_SIZE, 0.5 / ref.stats.max);
  const gotMirror = await sphereAt(1, 0, ours.light, MIRROR_SIZE, 0.5 / ours.stats.max);
  out.mirror = { sunError: degrees(reflected(gotMirror), reflected(refMirror)), cmgenVsSkybox: degrees(reflected(refMirror), sun) };

  // Each path's spheres (metal and white dielectric at each roughness), a white r = 1
  // sphere lit by its file's SH (IndirectLight::Builder::irradiance(3, sh): light almost
  // all diffuse) and the same lit by its last level, rendered once and saved as `tag`.
  const renderPath = async (path, tag) => {
    const spheres = [];
    for (const metallic of [1, 0]) {
      for (const r of roughness) {
        const px = await sphereAt(metallic, r, path.light, SIZE, eView(path));
        spheres.push({ metallic, roughness: r, px });
        images[`sphere_m${metallic}_r${r}_${tag}`] = measure.toPng(px, SIZE);
      }
    }
    const sh = await sphereAt(0, 1, path.withSh, SIZE, eView(path));
    images[`sh_${tag}`] = measure.toPng(sh, SIZE);
    const level = await sphereAt(0, 1, path.light, SIZE, eView(path));
    return { path, spheres, sh, level };
  };
  // A path's renders against a cmgen bake's: spheres, SH-lit diffuse, and the path's SH
  // against its own last level (the two diffuse sources agree).
  const compare = (got, want) => ({
    spheres: got.spheres.map(({ metallic, roughness: r, px }, k) => ({ metallic, roughness: r, ...measure.compareSpheres(px, want.spheres[k].px, SIZE) })),
    sh: measure.compareSpheres(got.sh, want.sh, SIZE),
    shVsLastLevel: measure.compareSpheres(got.sh, got.level, SIZE),
    fluxVsCmgen: got.path.stats.mean / want.path.stats.mean,
  });
  const cmgenRenders = await renderPath(ref, 'cmgen');
  const ourRenders = await renderPath(ours, 'splitsum');
  // splitsum's bake of the HDRI and its bake of cmgen's own level-0 cube (the same cube on
  // both sides: only the prefiltering and the SH differ) against cmgen's bake of the HDRI.
  out.fromHdri = compare(ourRenders, cmgenRenders);
  out.fromCmgenCube = compare(await renderPath(await loadPath(fromCmgenCube), 'splitsum_from_cmgen_cube'), cmgenRenders);
  // splitsum's bake of the HDRI against cmgen's bake of splitsum's exact cube of it
  // (engines/panorama.mjs): cmgen's prefiltering and SH of the cube splitsum bakes from.
  out.vsCmgenOfExact = compare(ourRenders, await renderPath(await loadPath(cmgenOfExact), 'cmgen_of_exact'));
  if (split) out.sunLight = await sunLight(ours, split, images);
  out.renderer = gl.getParameter(gl.VERSION);
  return { out, images };
};

// The sun of a split bake's sun.json as Filament's SUN light, as the README recipe builds
// it: towards −direction, colour E / illuminance, intensity illuminance × the IBL's
// intensity in lux (Filament shades a directional light with colour × intensity, the IBL
// with radiance × intensity), the sun's disc radius, casting shadows.
function sunEntity(sun) {
  const entity = Filament.EntityManager.get().create();
  const lum = sun.illuminance;
  Filament.LightManager.Builder(Filament.LightManager$Type.SUN)
    .color(sun.irradiance.map((c) => c / lum))
    .intensity(lum * INTENSITY)
    .direction(scale(sun.direction, -1))
    .sunAngularRadius(sun.angular_radius_deg)
    .castShadows(true)
    .build(engine, entity);
  return entity;
}

// The sun as a light (`split`: a `--sun split` bake's files, beside `full`, the kept
// bake): a white diffuse sphere (gltfio, metallic 0, roughness 1) lit by the full IBL
// against the residual IBL plus the SUN light, seen 90° from the sun (half lit, half
// shaded); then a box floating above a floor, lit by the sun alone with its shadow, seen
// from above.
async function sunLight(full, split, images) {
  const path = await loadPath(split);
  const sun = await (await fetch(split.sun)).json();
  const light = sunEntity(sun);
  const toSun = sun.direction;
  const eye = scale(measure.turnedFrom(toSun, 90), SPHERE_DISTANCE);
  const cam = pinhole(eye, [0, 0, 0], SPHERE_FOV);
  const sides = async (ibl, withSun, tag) => {
    const asset = await loadSphere(0, 1);
    scene.addEntities(asset.getEntities());
    scene.setIndirectLight(ibl);
    if (withSun) scene.addEntity(light);
    const { px } = await render(cam, SIZE, 0.5);
    if (withSun) scene.remove(light);
    scene.removeEntities(asset.getEntities());
    assetLoader.destroyAsset(asset);
    images[`sun_sphere_${tag}`] = measure.toPng(px, SIZE);
    return measure.sideMeans(px, eye, (p) => pixelRay(cam, p, SIZE), SIZE, toSun);
  };
  const want = await sides(full.light, false, 'full_ibl');
  const got = await sides(path.light, true, 'split');

  // The shadow: the sun alone (no IBL), the floor and box casting and receiving shadows.
  const HEIGHT = 1, EXTENT = 10, TOP = 40;
  const asset = assetLoader.createAsset(shadowSceneGlb(2 * EXTENT, HEIGHT));
  await new Promise((ok) => asset.loadResources(ok, null, null, 1));
  const rm = engine.getRenderableManager();
  for (const e of asset.getRenderableEntities()) {
    const instance = rm.getInstance(e);
    rm.setCastShadows(instance, true);
    rm.setReceiveShadows(instance, true);
  }
  scene.addEntities(asset.getEntities());
  scene.addEntity(light);
  scene.setIndirectLight(null);
  const top = pinhole([0, TOP, 0], [0, 0, 0], (2 * Math.atan(EXTENT / TOP) * 180) / Math.PI);
  const { px } = await render(top, SIZE, 1);
  scene.remove(light);
  scene.removeEntities(asset.getEntities());
  assetLoader.destroyAsset(asset);
  engine.destroyEntity(light);
  images.sun_shadow = measure.toPng(px, SIZE);
  return {
    direction: toSun,
    ...measure.sideRatios(got, want),
    shadow: measure.shadowAzimuth(px, SIZE, (p) => measure.floorPoint(top.eye, pixelRay(top, p, SIZE)), toSun, HEIGHT),
  };
}

window.checkReady = true;
