// Runs in the page: loads a splitsum `--target babylon` .env into Babylon.js (npm babylonjs,
// its UMD build) as a Babylon app does (`new CubeTexture(url)` as scene.environmentTexture,
// `scene.createDefaultSkybox`), renders the skybox and PBRMaterial spheres into float
// targets, and compares them with Babylon's own path from the same HDRI (HDRCubeTexture with
// its prefiltering) and with Babylon's prefiltering of splitsum's exact cube.
//
// Renders are linear: the scene's image processing runs as a post-process (not attached
// here), so materials write linear radiance, clamped by Babylon to 30; each render lowers
// scene.environmentIntensity until nothing reaches the clamp and divides it back out.
import * as measure from '/engines/measure.js';

const B = window.BABYLON;
const { SIZE, MIRROR_SIZE, SPHERE_DISTANCE, SPHERE_FOV, SKY_FOV, add, scale, normalize, degrees } = measure;
// Babylon's PBR output clamp with the image processing as a post-process (pbr.fragment).
const CLAMP = 30;

const canvas = measure.pageCanvas(64);
const engine = new B.Engine(canvas, false, { preserveDrawingBuffer: true });
const scene = new B.Scene(engine);
scene.imageProcessingConfiguration.applyByPostProcess = true;
scene.clearColor = new B.Color4(0, 0, 0, 0);
const camera = new B.FreeCamera('camera', new B.Vector3(0, 0, 0), scene);
camera.fovMode = B.Camera.FOVMODE_VERTICAL_FIXED;
camera.minZ = 0.05;
camera.maxZ = 1000;

function aim(eye, target, fov) {
  camera.position = new B.Vector3(...eye);
  camera.upVector = Math.abs(normalize(add(target, scale(eye, -1)))[1]) > 0.999 ? new B.Vector3(0, 0, 1) : new B.Vector3(0, 1, 0);
  camera.setTarget(new B.Vector3(...target));
  camera.fov = (fov * Math.PI) / 180;
  camera.getViewMatrix(true);
}

// The world ray through pixel (x, y) of a read-back image (row 0 at the bottom).
function pixelRay([x, y], size) {
  const view = camera.getViewMatrix(), proj = camera.getProjectionMatrix(true);
  const p = B.Vector3.Unproject(new B.Vector3(x, size - y, 0.5), size, size, B.Matrix.Identity(), view, proj);
  return normalize([p.x - camera.position.x, p.y - camera.position.y, p.z - camera.position.z]);
}

// Renders `meshes` size² into a float target with the environment (and scaledLights)
// scaled by `e`; returns
// linear radiance (alpha: coverage) and the largest value written.
// Lights scaled with the environment: [light, its intensity at e = 1].
const scaledLights = [];

async function renderAt(meshes, size, e) {
  scene.environmentIntensity = e;
  for (const [light, intensity] of scaledLights) light.intensity = intensity * e;
  // Shaders compile asynchronously: wait until every mesh and its material can draw.
  for (let tries = 0; !meshes.every((m) => m.isReady(true)); tries++) {
    if (tries > 3000) throw new Error('a material never compiled');
    await new Promise((ok) => setTimeout(ok, 10));
  }
  const rtt = new B.RenderTargetTexture('rtt', size, scene, false, true, B.Constants.TEXTURETYPE_FLOAT);
  rtt.renderList = meshes;
  rtt.activeCamera = camera;
  camera.getProjectionMatrix(true);
  scene.render(false);
  rtt.render(false);
  const raw = await rtt.readPixels();
  rtt.dispose();
  const px = new Float32Array(raw.length);
  let max = 0;
  for (let i = 0; i < raw.length; i += 4) {
    for (let c = 0; c < 3; c++) {
      px[i + c] = raw[i + c] / e;
      max = Math.max(max, raw[i + c]);
    }
    px[i + 3] = raw[i + 3] > 0.5 ? 1 : 0;
  }
  return { px, max };
}

// Lowers the intensity until nothing reaches Babylon's output clamp.
async function render(meshes, size, e0) {
  let e = e0;
  for (let k = 0; k < 16; k++, e /= 8) {
    const { px, max } = await renderAt(meshes, size, e);
    if (max < 0.98 * CLAMP) return px;
  }
  throw new Error('every intensity reaches the clamp');
}

// Level 0 of a cube texture as Babylon holds it: per face, RGBA floats, rows as read back.
async function faces(texture) {
  const out = [];
  for (let f = 0; f < 6; f++) out.push(await texture.readPixels(f, 0));
  return out;
}

const ready = (texture) => new Promise((ok, fail) => {
  if (texture.isReady()) ok(texture);
  else texture.onLoadObservable.addOnce(() => ok(texture));
  setTimeout(() => fail(new Error(`${texture.name} did not load`)), 120000);
});

window.runCheck = async function ({ hdrUrl, exactUrl, envUrl, irradianceUrl, controlUrl, roughness, split }) {
  const own = await ready(new B.HDRCubeTexture(hdrUrl, scene, 256, false, true, false, true));
  // Babylon's own path from splitsum's exact cube (engines/panorama.mjs): its SH and its
  // prefiltering of the cube splitsum bakes from, with the clamp its SH projection puts on
  // every texel lifted (MAX_HDRI_VALUE, 4096, a public setting): quarry_01's exact cube
  // peaks at 40 852, and with the clamp Babylon's irradiance holds 38 % less than the exact
  // E/π, which its PBR shader also uses for rough reflections (measured: giving splitsum's
  // .env Babylon's clamped polynomial dims a metal r = 1 sphere by 38 %).
  const clamp = B.CubeMapToSphericalPolynomialTools.MAX_HDRI_VALUE;
  B.CubeMapToSphericalPolynomialTools.MAX_HDRI_VALUE = Infinity;
  const ownExact = await ready(new B.HDRCubeTexture(exactUrl, scene, 256, false, true, false, true));
  B.CubeMapToSphericalPolynomialTools.MAX_HDRI_VALUE = clamp;
  const ours = await ready(new B.CubeTexture(envUrl, scene));
  const control = await ready(new B.CubeTexture(controlUrl, scene));
  const ownFaces = await faces(own);
  const ownStats = measure.cubeStats(ownFaces, 256);
  const ownExactStats = measure.cubeStats(await faces(ownExact), 256);
  const ourFaces = await faces(ours);
  const ourStats = measure.cubeStats(ourFaces, 256);
  const sun = ownStats.sun;
  const out = {
    sun,
    levels: Math.round(Math.log2(ours.getSize().width)) + 1,
    lodGenerationScale: ours.lodGenerationScale,
    cube: { correlation: measure.cubeCorrelation(ourFaces, ownFaces, 256), sunError: degrees(ourStats.sun, ownStats.sun), fluxRatio: ourStats.mean / ownStats.mean },
  };
  const images = {};

  // The skybox looking at the sun.
  const skyAt = async (texture, e) => {
    const box = scene.createDefaultSkybox(texture, true, 100, 0);
    aim([0, 0, 0], sun, SKY_FOV);
    const px = await render([box], SIZE, e);
    box.material.dispose();
    box.dispose();
    return px;
  };
  // Where Babylon shows a texture's sun: the brightest of six 90° views, then the bright
  // centroid of a 50° view centred there.
  const findSun = async (texture, e) => {
    const box = scene.createDefaultSkybox(texture, true, 100, 0);
    const sunDir = await measure.locateSun(async (d, fov, size) => {
      aim([0, 0, 0], d, fov);
      const px = await render([box], size, e);
      return { px, ray: (p) => pixelRay(p, size) };
    }, SKY_FOV, SIZE);
    box.material.dispose();
    box.dispose();
    return sunDir;
  };
  const refSun = await findSun(own, 0.5 / ownStats.max);
  const refView = await skyAt(own, 0.6 / ownStats.mean), gotView = await skyAt(ours, 0.6 / ourStats.mean);
  out.background = { sunError: degrees(await findSun(ours, 0.5 / ourStats.max), refSun), logDiff: measure.logDiff(gotView, refView, SIZE) };
  images.sky_babylon = measure.toPng(refView, SIZE);
  images.sky_splitsum = measure.toPng(gotView, SIZE);
  out.control = { sunError: degrees(await findSun(control, 0.5 / ourStats.max), refSun) };
  // The irradiance each texture carries: its polynomial's mean over the sphere (band 0).
  const band0 = (t) => (t.sphericalPolynomial.xx.y + t.sphericalPolynomial.yy.y + t.sphericalPolynomial.zz.y) / 3;
  out.irradianceRatio = band0(ours) / band0(own);
  out.exact = { irradianceRatio: band0(ours) / band0(ownExact) };

  // Spheres, the camera 40° from the sun.
  const viewDir = measure.turnedFrom(sun, 40);
  const eye = scale(viewDir, SPHERE_DISTANCE);
  const sphere = B.MeshBuilder.CreateSphere('sphere', { diameter: 2, segments: 96 }, scene);
  const material = new B.PBRMaterial('material', scene);
  material.albedoColor = new B.Color3(1, 1, 1);
  sphere.material = material;
  sphere.setEnabled(false);
  const sphereAt = async (texture, metallic, r, size, e) => {
    scene.environmentTexture = texture;
    material.metallic = metallic;
    material.roughness = r;
    sphere.setEnabled(true);
    aim(eye, [0, 0, 0], SPHERE_FOV);
    const px = await render([sphere], size, e);
    sphere.setEnabled(false);
    return measure.maskSphere(px, eye, (p) => pixelRay(p, size), size);
  };
  // pixelRay reads Babylon's camera, which sphereAt leaves on the sphere.
  const reflected = (px) => measure.mirrorSun(px, eye, (p) => pixelRay(p, MIRROR_SIZE), MIRROR_SIZE);
  const refMirror = await sphereAt(own, 1, 0, MIRROR_SIZE, 0.5 / ownStats.max);
  const gotMirror = await sphereAt(ours, 1, 0, MIRROR_SIZE, 0.5 / ourStats.max);
  out.mirror = { sunError: degrees(reflected(gotMirror), reflected(refMirror)), ownVsCube: degrees(reflected(refMirror), sun) };

  // Each texture's spheres, rendered once and saved as `tag`; then compared.
  const renderSpheres = async (texture, tag, mean) => {
    const spheres = [];
    for (const metallic of [1, 0]) {
      for (const r of roughness) {
        const px = await sphereAt(texture, metallic, r, SIZE, 0.6 / mean);
        spheres.push({ metallic, roughness: r, px });
        images[`sphere_m${metallic}_r${r}_${tag}`] = measure.toPng(px, SIZE);
      }
    }
    return spheres;
  };
  const ourSpheres = await renderSpheres(ours, 'splitsum', ourStats.mean);
  const compareWith = async (reference, tag, refMean) => (await renderSpheres(reference, tag, refMean))
    .map(({ metallic, roughness: r, px }, k) => ({ metallic, roughness: r, ...measure.compareSpheres(ourSpheres[k].px, px, SIZE) }));
  out.vsOwn = await compareWith(own, 'babylon', ownStats.mean);
  out.vsOwnExact = await compareWith(ownExact, 'babylon_exact', ownExactStats.mean);
  // The README recipe's environment: the .env with its irradiance cube as the
  // irradianceTexture (the comparisons above read the .env's SH, as Babylon's own path
  // does). Its spheres, linear RGBA float rows from the bottom, for the preview's
  // Babylon.js mode to be held against (tests/engine_renders.rs): the camera as
  // measure.pinhole takes it, in Babylon's (left-handed) world.
  ours.irradianceTexture = await ready(new B.CubeTexture(irradianceUrl, scene));
  const raw = {};
  out.sphereCamera = { eye, fov: SPHERE_FOV, size: SIZE };
  for (const metallic of [1, 0]) {
    for (const r of roughness) {
      const px = await sphereAt(ours, metallic, r, SIZE, 0.6 / ourStats.mean);
      raw[`sphere_m${metallic}_r${r}.rgba32f`] = measure.base64(px);
      images[`sphere_m${metallic}_r${r}_splitsum_recipe`] = measure.toPng(px, SIZE);
    }
  }
  if (split) {
    out.sunLight = await sunLight(ours, split, images);
    // The split bake's skybox: its _background.env keeps the sun; its .env does not.
    const background = await ready(new B.CubeTexture(split.background, scene));
    const residual = await ready(new B.CubeTexture(split.env, scene));
    // The residual's brightest spot lies where the sun was too (the fill copies the bright
    // sky around it), so where the sun shows is not enough: its disc must also be as bright
    // as the kept bake's skybox shows it, looking at the sun (radiance, the brightest pixel).
    const e = 0.5 / ourStats.max;
    const peak = async (texture) => {
      const px = await skyAt(texture, e);
      return measure.luminance(px, 4 * measure.brightestPixel(px, SIZE)) / e;
    };
    const kept = await peak(ours);
    out.sunLight.background = {
      sunError: degrees(await findSun(background, e), refSun),
      peak: (await peak(background)) / kept,
      residualPeak: (await peak(residual)) / kept,
    };
    images.sky_split_background = measure.toPng(await skyAt(background, 0.6 / ourStats.mean), SIZE);
    background.dispose();
    residual.dispose();
  }
  out.renderer = engine.description;
  return { out, images, raw };
};

// The sun of a split bake's sun.json as a Babylon DirectionalLight, as the README recipe
// builds it: shining along −direction, diffuse and specular colour E / illuminance,
// intensity illuminance (Babylon shades it with colour × intensity, the environment with
// its radiance, both × 1/π for a Lambertian surface), from 50 units away for its shadows.
function sunLightFrom(sun) {
  const light = new B.DirectionalLight('sun', new B.Vector3(...scale(sun.direction, -1)), scene);
  const color = new B.Color3(...sun.irradiance.map((c) => c / sun.illuminance));
  light.diffuse = color;
  light.specular = color;
  light.intensity = sun.illuminance;
  light.position = new B.Vector3(...scale(sun.direction, 50));
  return light;
}

// The sun as a light (`split`: a `--sun split` bake's .env, irradiance .env and sun.json,
// beside `full`, the kept bake, both with their irradiance cubes as the README recipe sets
// them): a white Lambertian PBR sphere lit by the full IBL against the residual IBL plus
// the DirectionalLight, seen 90° from the sun (half lit, half shaded); then a box
// floating above a floor, lit by the sun alone with a ShadowGenerator, seen from above.
async function sunLight(full, split, images) {
  const residual = await ready(new B.CubeTexture(split.env, scene));
  residual.irradianceTexture = await ready(new B.CubeTexture(split.irradiance, scene));
  const sun = await (await fetch(split.sun)).json();
  const toSun = sun.direction;
  const light = sunLightFrom(sun);
  light.setEnabled(false);
  scaledLights.push([light, light.intensity]);
  const eye = scale(measure.turnedFrom(toSun, 90), SPHERE_DISTANCE);
  const sphere = B.MeshBuilder.CreateSphere('sun sphere', { diameter: 2, segments: 96 }, scene);
  const material = new B.PBRMaterial('diffuse', scene);
  material.albedoColor = new B.Color3(1, 1, 1);
  material.metallic = 0;
  material.roughness = 1;
  // Lambertian and no specular (F0 = 0, and with it F90, fresnelGrazingReflectance): what
  // the truth computes.
  material.baseDiffuseModel = B.Constants.MATERIAL_DIFFUSE_MODEL_LAMBERT;
  material.metallicF0Factor = 0;
  sphere.material = material;
  const sides = async (texture, withSun, tag) => {
    scene.environmentTexture = texture;
    light.setEnabled(withSun);
    aim(eye, [0, 0, 0], SPHERE_FOV);
    const px = await render([sphere], SIZE, 0.5);
    images[`sun_sphere_${tag}`] = measure.toPng(px, SIZE);
    return measure.sideMeans(px, eye, (p) => pixelRay(p, SIZE), SIZE, toSun);
  };
  const want = await sides(full, false, 'full_ibl');
  const got = await sides(residual, true, 'split');
  sphere.dispose();
  // The truth: the residual's level 0 as Babylon holds it, brute force, plus the lights
  // shaded exactly (Babylon holds the full environment's sun, ~64 000, past half floats;
  // residual + lights = the environment's irradiance within 0.2 %, tests/irradiance.rs).
  const lights = [sun, ...(sun.additional_lights ?? [])];
  const truth = measure.sideTruth(await faces(residual), residual.getSize().width, lights, eye, (p) => pixelRay(p, SIZE), SIZE, toSun);

  // The shadow: the sun alone (no environment).
  const HEIGHT = 1, EXTENT = 10, TOP = 40;
  scene.environmentTexture = null;
  const white = new B.PBRMaterial('white', scene);
  white.albedoColor = new B.Color3(1, 1, 1);
  white.metallic = 0;
  white.roughness = 1;
  const floor = B.MeshBuilder.CreateGround('floor', { width: 4 * EXTENT, height: 4 * EXTENT }, scene);
  floor.material = white;
  floor.receiveShadows = true;
  const box = B.MeshBuilder.CreateBox('box', { size: 1 }, scene);
  box.position = new B.Vector3(0, HEIGHT, 0);
  box.material = white;
  const shadows = new B.ShadowGenerator(2048, light);
  shadows.addShadowCaster(box);
  light.setEnabled(true);
  aim([0, TOP, 0], [0, 0, 0], (2 * Math.atan(EXTENT / TOP) * 180) / Math.PI);
  const px = await render([floor, box], SIZE, 1);
  images.sun_shadow = measure.toPng(px, SIZE);
  const shadow = measure.shadowAzimuth(px, SIZE, (p) => measure.floorPoint([0, TOP, 0], pixelRay(p, SIZE)), toSun, HEIGHT);
  shadows.dispose();
  for (const m of [floor, box, white, material]) m.dispose();
  light.dispose();
  scaledLights.length = 0;
  return {
    direction: toSun,
    ...measure.sideRatios(got, want),
    truth: {
      split: { lit: got.lit / truth.lit, shaded: got.shaded / truth.shaded },
      full: { lit: want.lit / truth.lit, shaded: want.shaded / truth.shaded },
    },
    shadow,
  };
}

window.checkReady = true;
