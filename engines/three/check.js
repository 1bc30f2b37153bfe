// Runs in the page: renders a splitsum `--target three` bake with three.js's own
// materials and background, and the same HDRI through three's own path (HDRLoader as
// float, equirect background, three's run-time PMREM for the spheres), and returns the
// measurements for check.mjs to judge. Every render goes to a float target (no tone
// mapping), so the numbers are linear radiance.
import * as THREE from 'three';
import { HDRLoader } from 'three/addons/loaders/HDRLoader.js';
import {
  compensateRectAreaLights,
  loadSplitsumBake,
  loadSplitsumCube,
  pickSplitsumBake,
  supportsAstcHdr,
  supportsBc6h,
} from '/js/splitsum-three.js';
import * as measure from '/engines/measure.js';

// Edge of the renders; the mirror sphere is rendered larger, since one pixel of it turns
// the reflected direction by twice the normal's change (about 2.3° at 160 px).
let SIZE = 160;
const MIRROR_SIZE = 512;
// Edge of the studio case's sphere renders, which tests/engine_renders.rs integrates the
// truth of per pixel (its cost grows with the square of this).
const STUDIO_SIZE = 96;

const renderer = new THREE.WebGLRenderer({ antialias: false });
renderer.setSize(SIZE, SIZE);
renderer.toneMapping = THREE.NoToneMapping;
document.body.appendChild(renderer.domElement);
let target = new THREE.WebGLRenderTarget(SIZE, SIZE, { type: THREE.FloatType });

function setSize(size) {
  SIZE = size;
  target.dispose();
  target = new THREE.WebGLRenderTarget(SIZE, SIZE, { type: THREE.FloatType });
}

function render(scene, camera) {
  renderer.setRenderTarget(target);
  renderer.setClearColor(0x000000, 0);
  renderer.render(scene, camera);
  const px = new Float32Array(SIZE * SIZE * 4);
  renderer.readRenderTargetPixels(target, 0, 0, SIZE, SIZE, px);
  renderer.setRenderTarget(null);
  return px;
}

// engines/measure.js at the current render size.
const luminance = measure.luminance;
const brightCentroid = (px) => measure.brightCentroid(px, SIZE);
const logDiff = (a, b) => measure.logDiff(a, b, SIZE);
const compareSpheres = (got, want) => measure.compareSpheres(got, want, SIZE);
const toPng = (px) => measure.toPng(px, SIZE);

// The HDRI's sun: luminance-weighted mean direction of the texels above half the maximum
// (three's equirect convention: u = atan(z, x)/2π + 0.5, the first row at +y).
function sunDirection(hdr) {
  const { data, width, height } = hdr.image;
  let max = 0;
  for (let i = 0; i < width * height; i++) max = Math.max(max, luminance(data, 4 * i));
  const d = new THREE.Vector3();
  for (let y = 0; y < height; y++) {
    const theta = (Math.PI * (y + 0.5)) / height;
    for (let x = 0; x < width; x++) {
      const l = luminance(data, 4 * (y * width + x));
      if (l < 0.5 * max) continue;
      const phi = 2 * Math.PI * ((x + 0.5) / width - 0.5);
      const w = l * Math.sin(theta);
      d.x += w * Math.sin(theta) * Math.cos(phi);
      d.y += w * Math.cos(theta);
      d.z += w * Math.sin(theta) * Math.sin(phi);
    }
  }
  return d.normalize();
}

// The world ray through pixel (x, y) of a readRenderTargetPixels image (row 0 at the bottom).
function pixelRay(camera, [x, y]) {
  const ndc = new THREE.Vector3((2 * x) / SIZE - 1, (2 * y) / SIZE - 1, 0.5);
  const dir = ndc.unproject(camera).sub(camera.position).normalize();
  return new THREE.Ray(camera.position.clone(), dir);
}

const degrees = (a, b) => THREE.MathUtils.radToDeg(a.angleTo(b));

// What each block format needs, as the loader's error names it.
const BLOCK_NEEDS = {
  bc6h: { supported: supportsBc6h, needs: 'EXT_texture_compression_bptc' },
  'astc-4x4-hdr': { supported: supportsAstcHdr, needs: 'WEBGL_compressed_texture_astc' },
};

window.runCheck = async function ({ hdrUrl, bakeDir, fallbackDir, cubeUrl, roughness, splitDir, studio }) {
  if (studio) return studioCase(studio, roughness);
  const manifest = await (await fetch(`${bakeDir}/manifest.json`)).json();
  const format = manifest.parameters.pixel_format;
  const block = BLOCK_NEEDS[format];
  if (block && !block.supported(renderer)) {
    // What a page on this context gets: the loader's error, and the fallback chosen.
    const refused = await loadSplitsumBake(bakeDir, renderer).then(
      () => null,
      (e) => e.message,
    );
    const picked = pickSplitsumBake(renderer, [
      { url: bakeDir, pixelFormat: format },
      { url: fallbackDir, pixelFormat: 'rgba16f' },
    ]);
    return {
      out: {
        skipped: true,
        path: `${format} not rendered: this WebGL context has no ${block.needs}${format.startsWith('astc') ? ' with the "hdr" profile' : ''}`,
        unsupported: { refused, picked, fallbackDir, needs: block.needs },
      },
      images: {},
    };
  }
  const hdr = await new HDRLoader().setDataType(THREE.FloatType).loadAsync(hdrUrl);
  hdr.mapping = THREE.EquirectangularReflectionMapping;
  const bake = await loadSplitsumBake(bakeDir, renderer);
  // splitsum's exact 256² cube (`cubemap --target three`), as a plain cube that three
  // PMREMs at run time: tells three's equirect → cube step from its PMREM filtering.
  const exactCube = await loadSplitsumCube(cubeUrl, renderer, { pmrem: false });
  const sun = sunDirection(hdr);
  const images = {};
  const out = {
    sun: sun.toArray(),
    levels: bake.envMap.image[0].mipmaps.length,
    path: block ? `${format}, uploaded compressed` : `${format} cube`,
  };

  // Background, looking at the sun: three's equirect path against the bake's cube.
  const camera = new THREE.PerspectiveCamera(50, 1, 0.1, 10);
  camera.position.set(0, 0, 0);
  camera.lookAt(sun);
  camera.updateMatrixWorld();
  const scene = new THREE.Scene();
  scene.background = hdr;
  const refSky = render(scene, camera);
  scene.background = bake.envMap;
  const gotSky = render(scene, camera);
  const refSun = pixelRay(camera, brightCentroid(refSky)).direction;
  const gotSun = pixelRay(camera, brightCentroid(gotSky)).direction;
  out.background = {
    sunError: degrees(gotSun, refSun),
    threeSunVsEquirect: degrees(refSun, sun),
    logDiff: logDiff(gotSky, refSky),
  };
  images.sky_three = toPng(refSky);
  images.sky_splitsum = toPng(gotSky);

  // Six axis views of the whole background.
  let sum = 0;
  for (const d of [[1, 0, 0], [-1, 0, 0], [0, 1, 0.001], [0, -1, 0.001], [0, 0, 1], [0, 0, -1]]) {
    camera.lookAt(new THREE.Vector3(...d));
    camera.updateMatrixWorld();
    scene.background = hdr;
    const a = render(scene, camera);
    scene.background = bake.envMap;
    sum += logDiff(render(scene, camera), a) / 6;
  }
  out.background.logDiffAllViews = sum;

  // Spheres. The camera sits 40° from the sun so each sphere shows its lit and shaded side.
  const sphereScene = new THREE.Scene();
  const material = new THREE.MeshStandardMaterial({ color: 0xffffff });
  const sphere = new THREE.Mesh(new THREE.SphereGeometry(1, 128, 64), material);
  sphereScene.add(sphere);
  const axis = new THREE.Vector3(0, 1, 0).cross(sun).normalize();
  const view = sun.clone().applyAxisAngle(axis, THREE.MathUtils.degToRad(40));
  const sphereCamera = new THREE.PerspectiveCamera(30, 1, 0.1, 100);
  sphereCamera.position.copy(view.clone().multiplyScalar(4.2));
  sphereCamera.lookAt(0, 0, 0);
  sphereCamera.updateMatrixWorld();
  const withEnvironment = (env) => {
    sphereScene.environment = env;
    material.needsUpdate = true;
    return render(sphereScene, sphereCamera);
  };
  // The bake used as it is, and three's run-time PMREM of the equirect.
  const both = () => [withEnvironment(bake.envMap), withEnvironment(hdr)];

  // A mirror sphere: the sun's reflection against three's own path.
  material.metalness = 1;
  material.roughness = 0;
  setSize(MIRROR_SIZE);
  const [gotMirror, refMirror] = both();
  setSize(160);
  const reflected = (px) => {
    const ray = pixelRay(sphereCamera, brightCentroid(px));
    const hit = ray.intersectSphere(new THREE.Sphere(new THREE.Vector3(), 1), new THREE.Vector3());
    const n = hit.clone().normalize();
    return ray.direction.clone().reflect(n);
  };
  out.mirror = {
    sunError: degrees(reflected(gotMirror), reflected(refMirror)),
    threeSunVsEquirect: degrees(reflected(refMirror), sun),
  };
  images.mirror_three = toPng(refMirror);
  images.mirror_splitsum = toPng(gotMirror);

  out.spheres = [];
  // The spheres as rendered from the bake, linear RGBA float rows from the bottom, for the
  // preview's three.js mode to be held against (tests/engine_renders.rs): the camera as
  // measure.pinhole takes it.
  const raw = {};
  out.sphereCamera = { eye: sphereCamera.position.toArray(), fov: 30, size: SIZE };
  for (const metalness of [1, 0]) {
    for (const r of roughness) {
      material.metalness = metalness;
      material.roughness = r;
      const [got, want] = both();
      const viaExactCube = compareSpheres(got, withEnvironment(exactCube));
      out.spheres.push({
        metalness,
        roughness: r,
        ...compareSpheres(got, want),
        ratioToThreePmremOfExactCube: viaExactCube.ratio,
      });
      images[`sphere_m${metalness}_r${r}_three`] = toPng(want);
      images[`sphere_m${metalness}_r${r}_splitsum`] = toPng(got);
      if (!block) raw[`sphere_m${metalness}_r${r}.rgba32f`] = measure.base64(got);
    }
  }

  // The bake's SH as a THREE.LightProbe (radiance_sh9 as it is) against three's PMREM
  // diffuse: a white sphere with no specular (MeshPhysicalMaterial, specularIntensity 0).
  if (bake.lightProbe) {
    const diffuse = new THREE.MeshPhysicalMaterial({ color: 0xffffff, metalness: 0, roughness: 1, specularIntensity: 0 });
    const probeScene = new THREE.Scene();
    probeScene.add(new THREE.Mesh(sphere.geometry, diffuse));
    probeScene.add(bake.lightProbe);
    const got = render(probeScene, sphereCamera);
    const pmremScene = new THREE.Scene();
    pmremScene.add(new THREE.Mesh(sphere.geometry, diffuse));
    pmremScene.environment = hdr;
    const want = render(pmremScene, sphereCamera);
    out.lightProbe = compareSpheres(got, want);
    images.probe_splitsum = toPng(got);
    images.probe_three = toPng(want);
  }

  if (splitDir) out.sunLight = await sunLight(bake, splitDir, images);

  out.renderer = renderer.getContext().getParameter(renderer.getContext().VERSION);
  return { out, images, raw };
};

// The sun as a light (a `--sun split` bake in `splitDir`, beside the kept bake `full`): a
// white diffuse sphere lit by the full IBL against the residual IBL plus
// `bake.sunLight`, seen 90° from the sun (half lit, half shaded); then a box floating above
// a floor, lit by the sun alone with its shadow, seen from straight above.
async function sunLight(full, splitDir, images) {
  const split = await loadSplitsumBake(splitDir, renderer);
  if (!split.sunLight) throw new Error(`${splitDir}: no sun.json (bake with --sun split)`);
  const toSun = split.sunLight.position.clone().normalize();
  const sun = toSun.toArray();
  const eye = measure.scale(measure.turnedFrom(sun, 90), measure.SPHERE_DISTANCE);
  const cam = measure.pinhole(eye, [0, 0, 0], measure.SPHERE_FOV);
  const camera = new THREE.PerspectiveCamera(measure.SPHERE_FOV, 1, 0.1, 100);
  camera.position.set(...eye);
  camera.up.set(...cam.up);
  camera.lookAt(0, 0, 0);
  camera.updateMatrixWorld();
  const diffuse = new THREE.MeshPhysicalMaterial({ color: 0xffffff, metalness: 0, roughness: 1, specularIntensity: 0 });
  const sphere = new THREE.Mesh(new THREE.SphereGeometry(1, 128, 64), diffuse);
  const sides = (scene) => {
    scene.add(sphere);
    const px = render(scene, camera);
    return { px, ...measure.sideMeans(px, eye, (p) => measure.pixelRay(cam, p, SIZE), SIZE, sun) };
  };
  const fullScene = new THREE.Scene();
  fullScene.environment = full.envMap;
  const want = sides(fullScene);
  const splitScene = new THREE.Scene();
  splitScene.environment = split.envMap;
  splitScene.add(split.sunLight, split.sunLight.target, ...split.lights, ...split.areaLights);
  const got = sides(splitScene);
  images.sun_sphere_full_ibl = toPng(want.px);
  images.sun_sphere_split = toPng(got.px);

  // The shadow: the sun alone (no environment), shadows on.
  const HEIGHT = 1, EXTENT = 10, SHADOW_SIZE = 256;
  renderer.shadowMap.enabled = true;
  renderer.shadowMap.type = THREE.PCFShadowMap;
  const scene = new THREE.Scene();
  const floor = new THREE.Mesh(new THREE.PlaneGeometry(4 * EXTENT, 4 * EXTENT), new THREE.MeshStandardMaterial({ color: 0xffffff, roughness: 1 }));
  floor.rotation.x = -Math.PI / 2;
  floor.receiveShadow = true;
  const box = new THREE.Mesh(new THREE.BoxGeometry(1, 1, 1), new THREE.MeshStandardMaterial({ color: 0xffffff, roughness: 1 }));
  box.position.set(0, HEIGHT, 0);
  box.castShadow = true;
  scene.add(floor, box, split.sunLight, split.sunLight.target);
  const top = new THREE.OrthographicCamera(-EXTENT, EXTENT, EXTENT, -EXTENT, 0.1, 100);
  top.position.set(0, 50, 0);
  top.up.set(0, 0, -1);
  top.lookAt(0, 0, 0);
  top.updateMatrixWorld();
  const saved = SIZE;
  setSize(SHADOW_SIZE);
  const px = render(scene, top);
  setSize(saved);
  renderer.shadowMap.enabled = false;
  images.sun_shadow = measure.toPng(px, SHADOW_SIZE);
  return {
    direction: sun,
    intensity: split.sunLight.intensity,
    ...measure.sideRatios(got, want),
    // The orthographic camera from above: pixel x along +x, pixel y along −z.
    shadow: measure.shadowAzimuth(px, SHADOW_SIZE, ([x, y]) => [((2 * x) / SHADOW_SIZE - 1) * EXTENT, -((2 * y) / SHADOW_SIZE - 1) * EXTENT], sun, HEIGHT),
  };
}

// A studio's lamps as RectAreaLights: the spheres of a `--sun split` bake (the residual IBL,
// its area lights as loadSplitsumBake makes them, any directional light), as three shades
// RectAreaLights (`plain_sphere_*`) and with compensateRectAreaLights (`sphere_*`, what
// the loader does), and of the same HDRI baked with its lamps kept in the IBL
// (`kept_sphere_*`), seen 40° from the first light, returned as linear floats for
// tests/engine_renders.rs to hold against the integral of the HDRI as read (the
// preview's truth, with three's BRDF). The plain renders come first: three caches a
// built-in material's program by its parameters, not its source, so the compensated ones
// use a material of their own program key.
async function studioCase({ splitDir, keptDir }, roughness) {
  const split = await loadSplitsumBake(splitDir, renderer, { compensateAreaLights: false });
  const kept = await loadSplitsumBake(keptDir, renderer);
  if (split.areaLights.length === 0) throw new Error(`${splitDir}: no area light in sun.json`);
  const first = split.areaLights[0].position.clone().normalize();
  const eye = measure.scale(measure.turnedFrom(first.toArray(), 40), measure.SPHERE_DISTANCE);
  const camera = new THREE.PerspectiveCamera(measure.SPHERE_FOV, 1, 0.1, 1000);
  camera.position.set(...eye);
  camera.lookAt(0, 0, 0);
  camera.updateMatrixWorld();
  const geometry = new THREE.SphereGeometry(1, 128, 64);
  const spheres = (scene, material) => {
    const sphere = new THREE.Mesh(geometry, material);
    scene.add(sphere);
    const out = {};
    for (const metalness of [1, 0]) {
      for (const r of roughness) {
        material.metalness = metalness;
        material.roughness = r;
        out[`sphere_m${metalness}_r${r}`] = render(scene, camera);
      }
    }
    scene.remove(sphere);
    return out;
  };
  const splitScene = new THREE.Scene();
  splitScene.environment = split.envMap;
  splitScene.add(...split.areaLights);
  if (split.sunLight) splitScene.add(split.sunLight, split.sunLight.target, ...split.lights);
  const keptScene = new THREE.Scene();
  keptScene.environment = kept.envMap;
  const saved = SIZE;
  setSize(STUDIO_SIZE);
  const plain = spheres(splitScene, new THREE.MeshStandardMaterial({ color: 0xffffff }));
  const keep = spheres(keptScene, new THREE.MeshStandardMaterial({ color: 0xffffff }));
  compensateRectAreaLights();
  const compensated = new THREE.MeshStandardMaterial({ color: 0xffffff });
  compensated.customProgramCacheKey = () => 'splitsum compensated rect area lights';
  const got = spheres(splitScene, compensated);
  setSize(saved);
  const images = {};
  const raw = {};
  for (const [prefix, set] of [['', got], ['plain_', plain], ['kept_', keep]]) {
    for (const [name, px] of Object.entries(set)) {
      images[`${prefix}${name}`] = measure.toPng(px, STUDIO_SIZE);
      raw[`${prefix}${name}.rgba32f`] = measure.base64(px);
    }
  }
  const out = {
    areaLights: split.areaLights.length,
    directionalLights: (split.sunLight ? 1 : 0) + split.lights.length,
    sphereCamera: { eye, fov: measure.SPHERE_FOV, size: STUDIO_SIZE },
    path: `${split.areaLights.length} RectAreaLight(s) at ${split.areaLights.map((l) => l.position.length().toFixed(0)).join(', ')} units`,
  };
  return { out, images, raw };
}

window.checkReady = true;
