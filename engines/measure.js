// Image measurements shared by the engine checks' pages (engines/three, engines/filament,
// engines/gltf, engines/babylon): every image function takes a square RGBA float image of
// `size`² pixels as a graphics API reads it back (row 0 at the bottom), linear radiance in
// R, G, B and coverage in A. Below them, the vector and pinhole-camera helpers the checks
// that cannot read back an engine's own camera use.

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

// Mean luminance ratio and correlation over the pixels both images cover fully (alpha 1).
export function compareSpheres(got, want, size) {
  const g = [], w = [];
  for (let i = 0; i < size * size; i++) {
    if (got[4 * i + 3] < 1 || want[4 * i + 3] < 1) continue;
    g.push(luminance(got, 4 * i));
    w.push(luminance(want, 4 * i));
  }
  const mean = (v) => v.reduce((a, b) => a + b, 0) / v.length;
  const mg = mean(g), mw = mean(w);
  let sgw = 0, sgg = 0, sww = 0;
  for (let i = 0; i < g.length; i++) {
    sgw += (g[i] - mg) * (w[i] - mw);
    sgg += (g[i] - mg) ** 2;
    sww += (w[i] - mw) ** 2;
  }
  return { pixels: g.length, ratio: mg / mw, correlation: sgw / Math.sqrt(sgg * sww) };
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
// Where the ray from the camera through (x, y) meets the unit sphere, if it does.
export function sphereHit(cam, px, size) {
  const d = pixelRay(cam, px, size);
  const b = dot(cam.eye, d), c = dot(cam.eye, cam.eye) - 1;
  const disc = b * b - c;
  if (disc < 0) return null;
  return { d, p: add(cam.eye, scale(d, -b - Math.sqrt(disc))), depth: Math.sqrt(disc) };
}

// The direction `angle` degrees from `sun`, turned towards +y about cross(+y, sun): where
// the checks put the camera so that a sphere shows its lit and its shaded side.
export function turnedFrom(sun, angle) {
  const k = normalize(cross([0, 1, 0], sun));
  const a = (angle * Math.PI) / 180;
  return add(add(scale(sun, Math.cos(a)), scale(cross(k, sun), Math.sin(a))), scale(k, dot(k, sun) * (1 - Math.cos(a))));
}
