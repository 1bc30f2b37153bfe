// Image measurements shared by the engine checks' pages (engines/three, engines/filament,
// engines/gltf, engines/babylon): every image function takes a square RGBA float image of
// `size`² pixels as a graphics API reads it back (row 0 at the bottom), linear radiance in
// R, G, B and coverage in A. Below them, the vector and pinhole-camera helpers the checks
// that cannot read back an engine's own camera use.

// The views the Filament, Babylon and glTF checks render: SIZE² images (MIRROR_SIZE² for the
// mirror sphere), spheres of radius 1 at the origin seen from SPHERE_DISTANCE with a
// SPHERE_FOV° vertical field of view (a sphere fills most of the image), the sky in
// SKY_FOV° views.
export const SIZE = 160;
export const MIRROR_SIZE = 512;
export const SPHERE_DISTANCE = 4.2;
export const SPHERE_FOV = 30;
export const SKY_FOV = 50;

export const luminance = (p, i) => 0.2126 * p[i] + 0.7152 * p[i + 1] + 0.0722 * p[i + 2];

// Index of the pixel of largest luminance.
export function brightestPixel(px, size) {
  let best = 0;
  for (let i = 1; i < size * size; i++) if (luminance(px, 4 * i) > luminance(px, 4 * best)) best = i;
  return best;
}

// Centroid (in pixels, from the bottom-left corner) of the pixels above half the image's
// maximum luminance, weighted by luminance.
export function brightCentroid(px, size) {
  let max = 0;
  for (let i = 0; i < size * size; i++) max = Math.max(max, luminance(px, 4 * i));
  let sx = 0, sy = 0, sw = 0;
  for (let i = 0; i < size * size; i++) {
    const l = luminance(px, 4 * i);
    if (l < 0.5 * max) continue;
    sx += l * ((i % size) + 0.5);
    sy += l * (Math.floor(i / size) + 0.5);
    sw += l;
  }
  return [sx / sw, sy / sw];
}

// Mean |Δ ln(1 + L)| over the pixels both images cover.
export function logDiff(a, b, size) {
  let s = 0, n = 0;
  for (let i = 0; i < size * size; i++) {
    if (a[4 * i + 3] === 0 || b[4 * i + 3] === 0) continue;
    for (let c = 0; c < 3; c++) s += Math.abs(Math.log1p(a[4 * i + c]) - Math.log1p(b[4 * i + c]));
    n += 3;
  }
  return s / n;
}

const mean = (v) => v.reduce((a, b) => a + b, 0) / v.length;

// Pearson correlation of two equally long lists.
export function correlation(x, y) {
  const mx = mean(x), my = mean(y);
  let sxy = 0, sxx = 0, syy = 0;
  for (let i = 0; i < x.length; i++) {
    sxy += (x[i] - mx) * (y[i] - my);
    sxx += (x[i] - mx) ** 2;
    syy += (y[i] - my) ** 2;
  }
  return sxy / Math.sqrt(sxx * syy);
}

// Mean luminance ratio and correlation over the pixels both images cover fully (alpha 1).
export function compareSpheres(got, want, size) {
  const g = [], w = [];
  for (let i = 0; i < size * size; i++) {
    if (got[4 * i + 3] < 1 || want[4 * i + 3] < 1) continue;
    g.push(luminance(got, 4 * i));
    w.push(luminance(want, 4 * i));
  }
  return { pixels: g.length, ratio: mean(g) / mean(w), correlation: correlation(g, w) };
}

// An 8-bit RGBA read-back decoded to radiance: `decode` maps a byte to the linear value the
// engine encoded, divided by the exposure `e`; alpha 0 where a channel saturates (254 or
// more), which carries no radiance. Also returns the largest byte.
export function decode8(bytes, decode, e) {
  const px = new Float32Array(bytes.length);
  let max = 0;
  for (let i = 0; i < bytes.length; i += 4) {
    let top = 0;
    for (let c = 0; c < 3; c++) {
      px[i + c] = decode[bytes[i + c]] / e;
      top = Math.max(top, bytes[i + c]);
    }
    px[i + 3] = top < 254 ? 1 : 0;
    max = Math.max(max, top);
  }
  return { px, max };
}

// The GL cube-face table (docs/conventions.md, "Cube faces"): the direction through face coordinates (s, t).
export const faceDirection = (face, s, t) => [[1, -t, -s], [-1, -t, s], [s, 1, t], [s, -1, -t], [s, -t, 1], [-s, -t, -1]][face];

// Calls visit(face, i, j, s, t, w) for every texel of an n² cube, face by face, rows as GL
// reads them back: (s, t) its centre's face coordinates, w = 1 / (s² + t² + 1)^1.5 its
// solid angle over that of a (2/n)² patch at the face's centre.
export function forEachTexel(n, visit) {
  for (let f = 0; f < 6; f++) {
    for (let j = 0; j < n; j++) {
      for (let i = 0; i < n; i++) {
        const s = (2 * (i + 0.5)) / n - 1, t = (2 * (j + 0.5)) / n - 1;
        visit(f, i, j, s, t, 1 / (s * s + t * t + 1) ** 1.5);
      }
    }
  }
}

// Of a cube's level 0 (six RGBA float faces of n², rows as GL reads them): the direction of
// the texels above half the largest luminance, that largest value, and the solid-angle
// mean. Non-finite texels (an engine's own half-float filtering of a sun) count as 0.
export function cubeStats(level0, n) {
  let max = 0, sum = 0, total = 0;
  const texels = [];
  forEachTexel(n, (f, i, j, s, t, w) => {
    const l = luminance(level0[f], 4 * (j * n + i)) || 0;
    texels.push([l, faceDirection(f, s, t), w]);
    max = Math.max(max, l);
    sum += l * w;
    total += w;
  });
  let sun = [0, 0, 0];
  for (const [l, d, w] of texels) if (l >= 0.5 * max) sun = add(sun, scale(normalize(d), l * w));
  return { sun: normalize(sun), max, mean: sum / total };
}

// The texel of an n² cube (faces as GL reads them back, the table above) that direction d
// falls in: [face, i, j].
export function cubeTexel(d, n) {
  const [x, y, z] = d, ax = Math.abs(x), ay = Math.abs(y), az = Math.abs(z);
  let face, s, t;
  if (ax >= ay && ax >= az) [face, s, t] = x > 0 ? [0, -z / ax, -y / ax] : [1, z / ax, -y / ax];
  else if (ay >= az) [face, s, t] = y > 0 ? [2, x / ay, z / ay] : [3, x / ay, -z / ay];
  else [face, s, t] = z > 0 ? [4, x / az, -y / az] : [5, -x / az, -y / az];
  const index = (u) => Math.min(n - 1, Math.max(0, Math.floor(((u + 1) / 2) * n)));
  return [face, index(s), index(t)];
}

// The irradiance over π, E(d)/π = (1/π) ∫ L(l) max(0, d·l) dω, RGB for each direction of
// `dirs`, summed over every texel of a level-0 cube (each texel's solid angle
// (2/n)² / (s² + t² + 1)^1.5 at its centre): a brute-force truth for an engine's
// Lambertian cube, computed from the radiance cube the engine holds. Non-finite texels
// count as 0.
export function bruteIrradiance(level0, n, dirs) {
  const count = 6 * n * n, texels = new Float32Array(6 * count);
  let k = 0;
  forEachTexel(n, (f, i, j, s, t, w) => {
    const omega = (4 / (n * n)) * w / Math.PI;
    const d = normalize(faceDirection(f, s, t));
    for (let c = 0; c < 3; c++) {
      const v = level0[f][4 * (j * n + i) + c];
      texels[6 * k + c] = d[c];
      texels[6 * k + 3 + c] = Number.isFinite(v) ? v * omega : 0;
    }
    k++;
  });
  return dirs.map(([x, y, z]) => {
    let r = 0, g = 0, b = 0;
    for (let i = 0; i < 6 * count; i += 6) {
      const c = x * texels[i] + y * texels[i + 1] + z * texels[i + 2];
      if (c > 0) {
        r += c * texels[i + 3];
        g += c * texels[i + 4];
        b += c * texels[i + 5];
      }
    }
    return [r, g, b];
  });
}

// The texel-centre directions of an n² cube, face by face, rows as GL reads them back.
export function cubeDirections(n) {
  const dirs = [];
  forEachTexel(n, (f, i, j, s, t) => dirs.push(normalize(faceDirection(f, s, t))));
  return dirs;
}

// A Lambertian cube (n², as GL reads it back) against bruteIrradiance of the radiance cube
// it was made from (`truth`, at `dirs`): the ratio of their luminance sums (the cube's
// brightness over those directions) and the largest |ratio − 1| of a single direction.
export function lambertianError(lambertian, n, truth, dirs) {
  let got = 0, want = 0, worst = 0;
  dirs.forEach((d, k) => {
    const [f, i, j] = cubeTexel(d, n);
    const v = luminance(lambertian[f], 4 * (j * n + i)), e = luminance(truth[k], 0);
    got += v;
    want += e;
    worst = Math.max(worst, Math.abs(v / e - 1));
  });
  return { ratio: got / want, worst };
}

// Correlation of ln(1 + L) between two level-0 cubes, over 8×8-texel blocks.
export function cubeCorrelation(a, b, n) {
  const blocks = (level0) => {
    const out = [];
    for (let f = 0; f < 6; f++) {
      for (let bj = 0; bj < n / 8; bj++) {
        for (let bi = 0; bi < n / 8; bi++) {
          let s = 0;
          for (let j = 8 * bj; j < 8 * bj + 8; j++) for (let i = 8 * bi; i < 8 * bi + 8; i++) s += luminance(level0[f], 4 * (j * n + i)) || 0;
          out.push(Math.log1p(s / 64));
        }
      }
    }
    return out;
  };
  return correlation(blocks(a), blocks(b));
}

// A size × size canvas added to the page, for an engine to draw into.
export function pageCanvas(size) {
  const canvas = document.createElement('canvas');
  canvas.width = canvas.height = size;
  document.body.appendChild(canvas);
  return canvas;
}

// An RGBA8 PNG (data URL) of a float image, Reinhard-mapped and flipped upright, for the
// record.
export function toPng(px, size) {
  const canvas = document.createElement('canvas');
  canvas.width = canvas.height = size;
  const ctx = canvas.getContext('2d');
  const img = ctx.createImageData(size, size);
  for (let y = 0; y < size; y++) {
    for (let x = 0; x < size; x++) {
      const s = 4 * ((size - 1 - y) * size + x), d = 4 * (y * size + x);
      for (let c = 0; c < 3; c++) {
        const v = px[s + c] / (1 + px[s + c]);
        img.data[d + c] = Math.round(255 * Math.pow(v, 1 / 2.2));
      }
      img.data[d + 3] = 255;
    }
  }
  ctx.putImageData(img, 0, 0);
  return canvas.toDataURL('image/png');
}

// Vectors as 3-arrays.
export const add = (a, b) => a.map((v, i) => v + b[i]);
export const scale = (a, k) => a.map((v) => v * k);
export const dot = (a, b) => a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
export const cross = (a, b) => [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]];
export const normalize = (a) => scale(a, 1 / Math.hypot(...a));
export const degrees = (a, b) => (Math.acos(Math.min(1, Math.max(-1, dot(normalize(a), normalize(b))))) * 180) / Math.PI;

// The bytes of a typed array as base64 (a runCheck's `raw` files).
export function base64(array) {
  const bytes = new Uint8Array(array.buffer, array.byteOffset, array.byteLength);
  let text = '';
  for (let i = 0; i < bytes.length; i += 0x8000) {
    text += String.fromCharCode(...bytes.subarray(i, i + 0x8000));
  }
  return btoa(text);
}

// A pinhole camera: eye, forward, up and vertical field of view; the ray through pixel
// (x, y) of a read-back image (row 0 at the bottom).
export function pinhole(eye, target, fov) {
  const forward = normalize(add(target, scale(eye, -1)));
  const right = normalize(cross(forward, Math.abs(forward[1]) > 0.999 ? [0, 0, 1] : [0, 1, 0]));
  const up = cross(right, forward);
  return { eye, forward, right, up, fov };
}
export function pixelRay(cam, [x, y], size) {
  const t = Math.tan((cam.fov * Math.PI) / 360);
  const sx = ((2 * x) / size - 1) * t, sy = ((2 * y) / size - 1) * t;
  return normalize(add(cam.forward, add(scale(cam.right, sx), scale(cam.up, sy))));
}
// Where the ray from `eye` along unit `d` meets the unit sphere at the origin, if it does:
// the point, and half the chord (how deep inside the silhouette the ray passes).
function sphereHit(eye, d) {
  const b = dot(eye, d), c = dot(eye, eye) - 1;
  const disc = b * b - c;
  if (disc < 0) return null;
  return { d, p: add(eye, scale(d, -b - Math.sqrt(disc))), depth: Math.sqrt(disc) };
}

// The sphere renders of the checks (the unit sphere at the origin seen from `eye`; `ray`
// gives the world ray through a pixel position of the `size`² image): alpha 0 on the pixels
// whose ray misses it or crosses it along a half chord of at most 0.15 (its rim), so that a
// comparison covers the sphere well inside its silhouette only.
export function maskSphere(px, eye, ray, size) {
  for (let y = 0; y < size; y++) {
    for (let x = 0; x < size; x++) {
      const hit = sphereHit(eye, ray([x + 0.5, y + 0.5]));
      if (!(hit && hit.depth > 0.15)) px[4 * (y * size + x) + 3] = 0;
    }
  }
  return px;
}

// Where a mirror sphere's image (as for maskSphere) shows the sun: the direction its bright
// centroid reflects the view ray to.
export function mirrorSun(px, eye, ray, size) {
  const hit = sphereHit(eye, ray(brightCentroid(px, size)));
  if (!hit) throw new Error("the mirror sphere's bright spot lies off the sphere");
  const n = normalize(hit.p);
  return add(hit.d, scale(n, -2 * dot(hit.d, n)));
}

// The direction `angle` degrees from `sun`, turned towards +y about cross(+y, sun): where
// the checks put the camera so that a sphere shows its lit and its shaded side.
export function turnedFrom(sun, angle) {
  const k = normalize(cross([0, 1, 0], sun));
  const a = (angle * Math.PI) / 180;
  return add(add(scale(sun, Math.cos(a)), scale(cross(k, sun), Math.sin(a))), scale(k, dot(k, sun) * (1 - Math.cos(a))));
}

// Renders through `renderAt(e)` (→ { px, max }: the decoded radiance and the largest 8-bit
// channel value read back) at exposure `e0`, then 8× lower each time until no channel
// reaches 254 or the exposure reaches `minExposure`; `clipped` says whether pixels are
// still saturated then (a sun may be: its centroid is still the saturated disc's), and
// `exposure` which exposure the pixels were read at.
export async function renderUnclipped(renderAt, e0, minExposure) {
  let e = Math.max(e0, minExposure);
  for (;;) {
    const { px, max } = await renderAt(e);
    if (max < 254) return { px, clipped: false, exposure: e };
    if (e <= minExposure) return { px, clipped: true, exposure: e };
    e = Math.max(e / 8, minExposure);
  }
}

// Whether an 8-bit read-back decodes linearly: the radiance decoded from `renderAt(e / 4)`
// over that from `renderAt(e)` (→ { px }), summed over the pixels between 0.2 and 0.9 of
// full scale at `e`. 1 for a linear decode.
export async function readbackLinearity(renderAt, e, size) {
  const a = (await renderAt(e)).px, b = (await renderAt(e / 4)).px;
  let sa = 0, sb = 0;
  for (let i = 0; i < size * size; i++) {
    const la = luminance(a, 4 * i), lb = luminance(b, 4 * i);
    if (la * e > 0.2 && la * e < 0.9) { sa += la; sb += lb; }
  }
  return sb / sa;
}

// The six axis directions, the 90° views that cover the sphere.
const SIX_VIEWS = [[1, 0, 0], [-1, 0, 0], [0, 1, 0], [0, -1, 0], [0, 0, 1], [0, 0, -1]];

// Where an engine shows a sky's sun: the brightest pixel of six 90° views (96²), then the
// bright centroid of a `fov`° view (`size`²) centred there. `look(dir, fov, size)` renders
// the view towards `dir` and returns { px, ray }: the image and the world ray through a
// pixel position of it.
export async function locateSun(look, fov, size) {
  let best = { l: -1 };
  for (const d of SIX_VIEWS) {
    const { px, ray } = await look(d, 90, 96);
    const i = brightestPixel(px, 96);
    const l = luminance(px, 4 * i);
    if (l > best.l) best = { l, d: ray([(i % 96) + 0.5, Math.floor(i / 96) + 0.5]) };
  }
  const { px, ray } = await look(best.d, fov, size);
  return ray(brightCentroid(px, size));
}

// What a README recipe's page reports (engines/recipe.mjs): from a white sphere rendered as
// above with the recipe's environment (`lit`) and without it (`unlit`), the mean luminance
// over the middle of the sphere in each, and over the four corners (the sky) of `lit`.
export function recipeReport(lit, unlit, size) {
  const c = (size - 1) / 2;
  const middle = (x, y) => Math.hypot(x - c, y - c) < size / 6;
  const corner = (x, y) => Math.min(x, size - 1 - x) < size / 10 && Math.min(y, size - 1 - y) < size / 10;
  const mean = (px, inside) => {
    let sum = 0;
    let n = 0;
    for (let y = 0; y < size; y++) {
      for (let x = 0; x < size; x++) {
        if (inside(x, y)) {
          sum += luminance(px, 4 * (y * size + x));
          n += 1;
        }
      }
    }
    return sum / n;
  };
  return { sphere: mean(lit, middle), sphereUnlit: mean(unlit, middle), sky: mean(lit, corner) };
}

// The sun checks (docs/engines.md, "The sun as a light"). The pixels of a unit sphere's
// render (as for maskSphere) on its lit side (n·sun ≥ `edge`) and on its shaded side
// (n·sun ≤ −`edge`), each [pixel index, normal]: the pixels near the terminator, where a
// light and a blurred lobe differ most in shape, are left out of both.
export function sphereSides(eye, ray, size, sun, edge = 0.2) {
  const lit = [], shaded = [];
  for (let y = 0; y < size; y++) {
    for (let x = 0; x < size; x++) {
      const hit = sphereHit(eye, ray([x + 0.5, y + 0.5]));
      if (!(hit && hit.depth > 0.15)) continue;
      const n = normalize(hit.p);
      const c = dot(n, sun);
      if (c >= edge) lit.push([y * size + x, n]);
      if (c <= -edge) shaded.push([y * size + x, n]);
    }
  }
  return { lit, shaded };
}

// The mean luminance of a render's pixels on each side (sphereSides) of a diffuse sphere.
export function sideMeans(px, eye, ray, size, sun, edge = 0.2) {
  const sides = sphereSides(eye, ray, size, sun, edge);
  const mean = (side) => side.reduce((m, [i]) => m + luminance(px, 4 * i), 0) / side.length;
  return { lit: mean(sides.lit), shaded: mean(sides.shaded), litPixels: sides.lit.length, shadedPixels: sides.shaded.length };
}

// The sun checks' comparison of two sideMeans: `got` (the residual IBL and the light) over
// `want` (the full IBL) on each side, with the pixel counts.
export function sideRatios(got, want) {
  return { litRatio: got.lit / want.lit, shadedRatio: got.shaded / want.shaded, litPixels: got.litPixels, shadedPixels: got.shadedPixels };
}

// What a white Lambertian sphere shows on each side (sphereSides) under the radiance cube
// `level0` (n², as GL reads it back) and `lights` (sun.json's, each E⊥ max(n·l, 0)),
// E(n)/π's luminance averaged over the side's normals: the brute-force truth, from the
// cube box-averaged to at most 64² first (the cosine lobe is ~60× wider than a 64² texel).
export function sideTruth(level0, n, lights, eye, ray, size, sun, edge = 0.2) {
  let m = n, faces = level0;
  while (m > 64) {
    const half = m / 2;
    faces = faces.map((face) => {
      const out = new Float32Array(4 * half * half);
      for (let j = 0; j < half; j++) {
        for (let i = 0; i < half; i++) {
          for (let c = 0; c < 4; c++) {
            const at = (jj, ii) => face[4 * (jj * m + ii) + c] || 0;
            out[4 * (j * half + i) + c] = 0.25 * (at(2 * j, 2 * i) + at(2 * j, 2 * i + 1) + at(2 * j + 1, 2 * i) + at(2 * j + 1, 2 * i + 1));
          }
        }
      }
      return out;
    });
    m = half;
  }
  const sides = sphereSides(eye, ray, size, sun, edge);
  const direct = (normal) => lights.reduce((e, l) => e + (l.illuminance * Math.max(0, dot(normal, l.direction))) / Math.PI, 0);
  const mean = (side) => bruteIrradiance(faces, m, side.map(([, normal]) => normal))
    .reduce((sum, e, k) => sum + luminance(e, 0) + direct(side[k][1]), 0) / side.length;
  return { lit: mean(sides.lit), shaded: mean(sides.shaded) };
}

// A box floating above a floor at y = 0, lit by the sun alone and seen from above
// (`size`² image; `floorAt` gives the floor point [x, z] a pixel position shows): its
// shadow is the pixels darker than half the lit floor's median. Returns the shadow's
// centroid (x, z), how many pixels it holds, and its azimuth about the box's foot,
// atan2(z, x) in degrees, against where `sun` (toward the sun) puts the shadow of the
// box's centre at `height`: the shadow of a centrally symmetric solid under parallel
// light is centrally symmetric about the shadow of its centre, so the two centroids
// coincide.
export function shadowAzimuth(px, size, floorAt, sun, height) {
  const lums = [];
  for (let i = 0; i < size * size; i++) lums.push(luminance(px, 4 * i));
  const sorted = lums.filter((l) => l > 0).sort((a, b) => a - b);
  const median = sorted[Math.floor(sorted.length / 2)];
  let sx = 0, sz = 0, count = 0;
  for (let y = 0; y < size; y++) {
    for (let x = 0; x < size; x++) {
      if (!(lums[y * size + x] < 0.5 * median)) continue;
      const [fx, fz] = floorAt([x + 0.5, y + 0.5]);
      sx += fx;
      sz += fz;
      count++;
    }
  }
  const centre = [sx / count, sz / count];
  const expected = [(-sun[0] * height) / sun[1], (-sun[2] * height) / sun[1]];
  const azimuth = (v) => (Math.atan2(v[1], v[0]) * 180) / Math.PI;
  let error = Math.abs(azimuth(centre) - azimuth(expected));
  error = Math.min(error, 360 - error);
  return { centre, expected, pixels: count, azimuth: azimuth(centre), expectedAzimuth: azimuth(expected), error };
}

// The floor point (y = 0) [x, z] the ray along `d` from `eye` meets.
export function floorPoint(eye, d) {
  const t = -eye[1] / d[1];
  return [eye[0] + t * d[0], eye[2] + t * d[2]];
}
