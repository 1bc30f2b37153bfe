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
import { compensateRectAreaLights, directionalLightFromSun, rectAreaLightFromSun } from '/js/splitsum-babylon.js';

const B = window.BABYLON;
const { SIZE, MIRROR_SIZE, SPHERE_DISTANCE, SPHERE_FOV, SKY_FOV, add, scale, normalize, degrees } = measure;
// Babylon's PBR output clamp with the image processing as a post-process (pbr.fragment).
const CLAMP = 30;
// The distance of a studio's area lights from the origin (sun.json's rect_light gives the
// origin the light's irradiance from any distance along its direction; a point p off the
// origin sees it off by about 2·(p·direction)/distance, 2 % on the unit sphere).
const AREA_DISTANCE = 100;
// Edge of the studio case's sphere renders, which tests/engine_renders.rs integrates the
// truth of per pixel (its cost grows with the square of this): engines/three's.
const STUDIO_SIZE = 96;
// The unit check of the area light (areaLightUnit): its direction, radiance and angular
// half-sizes (°: a studio lamp's and a soft box's), the cap of normals about its axis whose
// pixels are averaged (their radiance within 0.1 % of the axis's), and the cells per side
// of the specular's sum over the rectangle.
const UNIT_DIRECTION = [0.3, 0.5, -0.8];
const UNIT_RADIANCE = 1000;
const UNIT_LIGHTS = [[3, 3], [20, 10]];
const UNIT_CAP = 2;
const UNIT_CELLS = 128;

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

// Renders `meshes` size² into a float target with the environment (and lightScales)
// scaled by `e`; returns
// linear radiance (alpha: coverage) and the largest value written.
// Lights scaled with the environment: functions of e that set a light's output to e times
// its own.
const lightScales = [];

async function renderAt(meshes, size, e) {
  scene.environmentIntensity = e;
  for (const scaleTo of lightScales) scaleTo(e);
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

window.runCheck = async function ({ hdrUrl, exactUrl, envUrl, irradianceUrl, controlUrl, roughness, split, studio }) {
  if (studio) return studioCase(studio, roughness);
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
  return directionalLightFromSun(B, scene, sun);
}

// A light's scaling with the environment (lightScales): its intensity, e times its own.
function intensityScale(light) {
  const intensity = light.intensity;
  return (e) => {
    light.intensity = intensity * e;
  };
}

// An area light of a split bake's sun.json as js/splitsum-babylon.js's rectAreaLightFromSun
// makes it (a RectAreaLight under a TransformNode, its radiance a 1×1 float
// emissionTexture; units and orientation there), `distance` away. Returns the light, its
// frame, and its scaling with the environment (lightScales: the emission texture's radiance
// × e).
function rectAreaLightFrom(light, distance = AREA_DISTANCE) {
  const area = rectAreaLightFromSun(B, scene, light, { distance });
  const emission = area.emissionTexture, frame = area.parent;
  const radiance = light.rect_light.radiance;
  return {
    light: area,
    frame,
    scale: (e) => emission.update(new Float32Array([...radiance.map((c) => c * e), 1])),
    dispose: () => {
      area.dispose();
      emission.dispose();
      frame.dispose();
    },
  };
}

// Waits until Babylon holds its LTC tables (fetched once per scene by the first area light,
// Lights/areaLight.pure.ts, CreateSceneLTCTextures). PBRMaterial.isReadyForSubMesh asks
// the lights' _isReady only when its defines already say AREALIGHTUSED, which it sets
// later in the same call (_prepareEffect), and not at all once its effect is ready
// (pbrBaseMaterial.pure.ts): a shader that compiles before the fetch ends draws from empty
// tables (measured: the studio's first sphere black when the case ran after the others).
async function ltcReady(lights) {
  for (let tries = 0; !lights.every((l) => l._isReady()); tries++) {
    if (tries > 3000) throw new Error("Babylon's LTC tables never loaded");
    await new Promise((ok) => setTimeout(ok, 10));
  }
}

// How far (degrees) the rectangle Babylon draws for `area` (rectAreaLightFrom) is from
// sun.json's: its centre against direction · distance, its width against ±width_axis, its
// height against height_axis (its parent's world matrix on x, y and the position, as
// RectAreaLight.transferToEffect does).
function rectError(light, { light: area, frame }) {
  const world = frame.getWorldMatrix();
  const at = B.Vector3.TransformCoordinates(area.position, world);
  const across = B.Vector3.TransformNormal(new B.Vector3(1, 0, 0), world);
  const up = B.Vector3.TransformNormal(new B.Vector3(0, 1, 0), world);
  const { width_axis: w, height_axis: h } = light.rect_light;
  return Math.max(
    degrees(at.asArray(), light.direction),
    Math.min(degrees(across.asArray(), w), degrees(across.asArray(), scale(w, -1))),
    degrees(up.asArray(), h),
  );
}

// A studio's lamps as Babylon RectAreaLights (`studio`: a `--sun split` bake's .env,
// irradiance .env and sun.json, the .env and irradiance .env of the bake with the lamps
// kept, and where the page serves Babylon's LTC tables): PBRMaterial spheres under the
// residual IBL and the lights (rectAreaLightFrom; a light without rect_light a
// DirectionalLight, sunLightFrom), both environments as the README recipe sets them, and
// under the kept IBL alone, seen 40° from the first light. The lights are shaded first as
// Babylon ships its shader (`plain_sphere_*`), then with js/splitsum-babylon.js's
// compensateRectAreaLights (`sphere_*`): the engine's compiled effects are released in
// between and the material is a new one, and the page counts the compiled effects that
// hold the patch (none before it, some after: shaderPatch). Their linear RGBA float rows
// (from the bottom, STUDIO_SIZE²) and the camera, as measure.pinhole takes it in Babylon's
// (left-handed) world, are for tests/engine_renders.rs to hold against the truth; then the
// unit check of the area light (areaLightUnit), as shipped and patched.
async function studioCase(studio, roughness) {
  // Babylon's LTC tables from this server (check.mjs writes them) instead of its CDN.
  B.Tools.AssetBaseUrl = studio.assetBaseUrl;
  const split = await ready(new B.CubeTexture(studio.env, scene));
  split.irradianceTexture = await ready(new B.CubeTexture(studio.irradiance, scene));
  const kept = await ready(new B.CubeTexture(studio.keptEnv, scene));
  kept.irradianceTexture = await ready(new B.CubeTexture(studio.keptIrradiance, scene));
  const sun = await (await fetch(studio.sun)).json();
  const all = [sun, ...(sun.additional_lights ?? [])];
  const lights = all.map((l) => {
    if (l.rect_light) return rectAreaLightFrom(l);
    const light = sunLightFrom(l);
    return { light, scale: intensityScale(light), dispose: () => light.dispose() };
  });
  const areas = all.flatMap((l, k) => (l.rect_light ? [[l, lights[k]]] : []));
  await ltcReady(areas.map(([, area]) => area.light));
  const eye = scale(measure.turnedFrom(sun.direction, 40), SPHERE_DISTANCE);
  const sphere = B.MeshBuilder.CreateSphere('studio sphere', { diameter: 2, segments: 96 }, scene);
  const newMaterial = (name) => {
    const material = new B.PBRMaterial(name, scene);
    material.albedoColor = new B.Color3(1, 1, 1);
    material.maxSimultaneousLights = Math.max(4, lights.length);
    sphere.material = material;
    return material;
  };
  const e0 = 0.6 / measure.cubeStats(await faces(kept), kept.getSize().width).mean;
  const sphereWith = async (texture, withLights) => {
    scene.environmentTexture = texture;
    for (const l of lights) l.light.setEnabled(withLights);
    lightScales.length = 0;
    if (withLights) lightScales.push(...lights.map((l) => l.scale));
    aim(eye, [0, 0, 0], SPHERE_FOV);
    const px = await render([sphere], STUDIO_SIZE, e0);
    return measure.maskSphere(px, eye, (p) => pixelRay(p, STUDIO_SIZE), STUDIO_SIZE);
  };
  const images = {}, raw = {}, spheres = [];
  // Whether every pixel is finite, and the mean luminance over the sphere.
  const summary = (px) => {
    let sum = 0, n = 0;
    for (let i = 0; i < STUDIO_SIZE * STUDIO_SIZE; i++) {
      if (px[4 * i + 3] === 1) {
        sum += measure.luminance(px, 4 * i);
        n++;
      }
    }
    return { finite: px.every(Number.isFinite), mean: sum / n };
  };
  // The engine's compiled effects whose fragment shader holds the patch.
  const patchedEffects = () => Object.values(engine._compiledEffects).filter((e) => (e.fragmentSourceCode ?? '').includes('splitsumAreaSpecularLighting')).length;
  // As Babylon ships it (with the lamps kept in the IBL beside them), then patched.
  let material = newMaterial('studio plain');
  for (const metallic of [1, 0]) {
    for (const r of roughness) {
      material.metallic = metallic;
      material.roughness = r;
      const got = await sphereWith(split, true);
      const keep = await sphereWith(kept, false);
      images[`sphere_m${metallic}_r${r}_plain_area_lights`] = measure.toPng(got, STUDIO_SIZE);
      images[`sphere_m${metallic}_r${r}_kept`] = measure.toPng(keep, STUDIO_SIZE);
      raw[`plain_sphere_m${metallic}_r${r}.rgba32f`] = measure.base64(got);
      raw[`kept_sphere_m${metallic}_r${r}.rgba32f`] = measure.base64(keep);
      spheres.push({ metallic, roughness: r, plain: true, ...summary(got) }, { metallic, roughness: r, kept: true, ...summary(keep) });
    }
  }
  const orientation = Math.max(0, ...areas.map(([l, area]) => rectError(l, area)));
  for (const l of lights) l.light.setEnabled(false);
  scene.environmentTexture = null;
  lightScales.length = 0;
  sphere.setEnabled(false);
  const areaUnitPlain = await areaLightUnit(images, 'plain_');
  sphere.setEnabled(true);
  const shaderPatch = { before: patchedEffects() };
  shaderPatch.patchedNow = compensateRectAreaLights(B);
  engine.releaseEffects();
  material.dispose();
  material = newMaterial('studio');
  for (const metallic of [1, 0]) {
    for (const r of roughness) {
      material.metallic = metallic;
      material.roughness = r;
      const got = await sphereWith(split, true);
      images[`sphere_m${metallic}_r${r}_area_lights`] = measure.toPng(got, STUDIO_SIZE);
      raw[`sphere_m${metallic}_r${r}.rgba32f`] = measure.base64(got);
      spheres.push({ metallic, roughness: r, ...summary(got) });
    }
  }
  shaderPatch.after = patchedEffects();
  for (const l of lights) l.dispose();
  for (const m of [sphere, material, split, kept]) m.dispose();
  scene.environmentTexture = null;
  lightScales.length = 0;
  const out = {
    areaLights: areas.length,
    directionalLights: lights.length - areas.length,
    rectError: orientation,
    spheres,
    sphereCamera: { eye, fov: SPHERE_FOV, size: STUDIO_SIZE },
    areaUnitPlain,
    areaUnit: await areaLightUnit(images, ''),
    shaderPatch,
    path: `${areas.length} RectAreaLight(s) ${AREA_DISTANCE} units away (radiance in a 1×1 float emissionTexture; specular compensated, js/splitsum-babylon.js), ${lights.length - areas.length} DirectionalLight(s)`,
  };
  out.renderer = engine.description;
  return { out, images, raw };
}

// The unit check of the area light (judged in check.mjs, AREA_BARS): one RectAreaLight as
// rectAreaLightFrom makes it, alone (no environment), of radiance UNIT_RADIANCE and each of
// UNIT_LIGHTS' angular half-sizes, AREA_DISTANCE away, facing a unit sphere seen from the
// light's side. Where the sphere faces it (the pixels whose normal is within UNIT_CAP° of
// the light's direction; the point on its axis at d = AREA_DISTANCE − 1 from it, n = v =
// the axis), against:
// - diffuse: a white Lambertian sphere (metallic 0, roughness 1, F0 = 0 and with it no
//   specular, metallicF0Factor), L · F, F the rectangle's form factor there,
//   (2/π)[a/√(1+a²) atan(b/√(1+a²)) + b/√(1+b²) atan(a/√(1+b²))], a = w/(2d), b = h/(2d);
// - specular: a white metal at r = 1 (F0 = F90 = 1, so F = 1) without Babylon's
//   multiple-scattering gain (brdf.useEnergyConservation), L ∫ f(l, v) (n·l) dω over the
//   rectangle, f the GGX BRDF as Babylon shades it (α = r² + 0.0005, height-correlated
//   Smith visibility), summed over UNIT_CELLS² cells of it. Under compensateRectAreaLights
//   that is Babylon's GGX at the centre × Ω plus the LTC's variation over the rectangle;
//   as Babylon ships it, the LTC lobe alone.
// Its images are named with `tag` before them (the check runs it as shipped and patched).
async function areaLightUnit(images, tag) {
  const toLight = normalize(UNIT_DIRECTION);
  const across = normalize(measure.cross(toLight, [0, 1, 0]));
  const up = measure.cross(toLight, across);
  const eye = scale(toLight, SPHERE_DISTANCE);
  const sphere = B.MeshBuilder.CreateSphere('unit sphere', { diameter: 2, segments: 96 }, scene);
  const material = new B.PBRMaterial('unit', scene);
  material.albedoColor = new B.Color3(1, 1, 1);
  material.roughness = 1;
  // Lambert's diffuse (Babylon shades an area light's diffuse so whatever this says) and no
  // multiple-scattering gain on the metal's specular.
  material.baseDiffuseModel = B.Constants.MATERIAL_DIFFUSE_MODEL_LAMBERT;
  material.brdf.useEnergyConservation = false;
  sphere.material = material;
  scene.environmentTexture = null;
  const results = [];
  for (const [alpha, beta] of UNIT_LIGHTS) {
    const light = {
      direction: toLight,
      rect_light: { half_width_deg: alpha, half_height_deg: beta, width_axis: across, height_axis: up, radiance: [UNIT_RADIANCE, UNIT_RADIANCE, UNIT_RADIANCE], luminance: UNIT_RADIANCE },
    };
    const area = rectAreaLightFrom(light);
    await ltcReady([area.light]);
    lightScales.push(area.scale);
    const d = AREA_DISTANCE - 1;
    const w = 2 * AREA_DISTANCE * Math.tan((alpha * Math.PI) / 180), h = 2 * AREA_DISTANCE * Math.tan((beta * Math.PI) / 180);
    const terms = [
      { term: 'diffuse', metallic: 0, want: UNIT_RADIANCE * formFactor(w / d, h / d) },
      { term: 'specular', metallic: 1, want: UNIT_RADIANCE * ggxOverRect(d, w, h) },
    ];
    for (const { term, metallic, want } of terms) {
      material.metallic = metallic;
      // No specular on the diffuse sphere: F0 = 0.
      material.metallicF0Factor = metallic;
      aim(eye, [0, 0, 0], SPHERE_FOV);
      const px = await render([sphere], SIZE, 1);
      images[`${tag}area_unit_${term}_${alpha}x${beta}`] = measure.toPng(px, SIZE);
      const { lit } = measure.sphereSides(eye, (p) => pixelRay(p, SIZE), SIZE, toLight, Math.cos((UNIT_CAP * Math.PI) / 180));
      const got = lit.reduce((sum, [i]) => sum + measure.luminance(px, 4 * i), 0) / lit.length;
      results.push({ term, what: `${term} under a ${2 * alpha}° × ${2 * beta}° light of radiance ${UNIT_RADIANCE}`, got, want, ratio: got / want, pixels: lit.length });
    }
    // One-sided: the same rectangle turned to shine away from the sphere (its frame half a
    // turn about x, the light at z = −distance in it: the same place) lights nothing.
    area.frame.rotationQuaternion = B.Quaternion.RotationQuaternionFromAxis(B.Vector3.Cross(new B.Vector3(...up), new B.Vector3(...toLight)), new B.Vector3(...scale(up, -1)), new B.Vector3(...scale(toLight, -1)));
    area.frame.computeWorldMatrix(true);
    area.light.position = new B.Vector3(0, 0, -AREA_DISTANCE);
    material.metallic = 0;
    material.metallicF0Factor = 0;
    const back = await render([sphere], SIZE, 1);
    let brightest = 0;
    for (let i = 0; i < SIZE * SIZE; i++) brightest = Math.max(brightest, measure.luminance(back, 4 * i));
    results.push({ term: 'back', what: `the ${2 * alpha}° × ${2 * beta}° light turned away: the brightest pixel`, got: brightest, want: 0 });
    area.dispose();
    lightScales.length = 0;
  }
  sphere.dispose();
  material.dispose();
  return results;
}

// The form factor of a w × h rectangle from a point on its axis at distance 1, facing it,
// a = w/2 and b = h/2 there (in units of the distance).
function formFactor(w, h) {
  const a = w / 2, b = h / 2;
  const sa = Math.sqrt(1 + a * a), sb = Math.sqrt(1 + b * b);
  return (2 / Math.PI) * ((a / sa) * Math.atan(b / sa) + (b / sb) * Math.atan(a / sb));
}

// ∫ f(l, n) (n·l) dω over a w × h rectangle facing a point d away on its axis, n = v its
// axis: f the GGX BRDF at r = 1 with F = 1 as Babylon's PBRMaterial shades it (alphaG =
// r² + 0.0005, convertRoughnessToAverageSlope; normalDistributionFunction_TrowbridgeReitzGGX
// and the height-correlated smithVisibility_GGXCorrelated at n·v = 1).
function ggxOverRect(d, w, h) {
  const a2 = (1 + 0.0005) ** 2;
  let sum = 0;
  for (let j = 0; j < UNIT_CELLS; j++) {
    for (let i = 0; i < UNIT_CELLS; i++) {
      const x = w * ((i + 0.5) / UNIT_CELLS - 0.5), y = h * ((j + 0.5) / UNIT_CELLS - 0.5);
      const r2 = x * x + y * y + d * d;
      const nl = d / Math.sqrt(r2);
      // The cell's solid angle: its area × cos at the cell / distance².
      const omega = ((w * h) / (UNIT_CELLS * UNIT_CELLS)) * nl / r2;
      const nh = Math.sqrt((1 + nl) / 2);
      const ggx = a2 / (Math.PI * (nh * nh * (a2 - 1) + 1) ** 2);
      const vis = 0.5 / (nl + Math.sqrt(nl * nl * (1 - a2) + a2));
      sum += ggx * vis * nl * omega;
    }
  }
  return sum;
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
  lightScales.push(intensityScale(light));
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
  lightScales.length = 0;
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
