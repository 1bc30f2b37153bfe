// Image measurements shared by the engine checks' pages (engines/three, engines/filament):
// every function takes a square RGBA float image of `size`² pixels as a graphics API reads
// it back (row 0 at the bottom), linear radiance in R, G, B and coverage in A.

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
