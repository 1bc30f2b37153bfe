// The HDRI as an engine's own path would see it after an exact conversion: splitsum's exact
// size² cube (each texel the solid-angle mean of the HDRI over its footprint, flux within
// 4e-6 of the HDRI's, tests/conversion_exact.rs) written back as an equirect, drawn from the
// cube resampled to 4× its size (so 4096×2048 for 256²), fine enough that an engine reading
// it at its own size² cube's texel centres, nearest or bilinear, reads the exact texels
// (blurred by the resampling's bilinear reconstruction by a fraction of a texel, and
// quantised by RGBE's 8-bit mantissas: through Babylon's path its level 0 keeps 99.8 % of
// venice_sunset's flux and 98.6 % of quarry_01's, whose sun sits in a few texels).
//
// The Babylon.js and glTF Sample Viewer checks feed it to the engine's own HDRI path
// (equirect to cube, SH, prefiltering): the engine's prefiltering of the cube splitsum bakes
// from, without the engine's conversion, which samples the HDRI at texel centres and loses
// or gains a small sun's light. The Filament check does the converse (splitsum bakes cmgen's
// cube).
import { execFileSync } from 'node:child_process';
import { mkdirSync } from 'node:fs';
import { join } from 'node:path';

// Upsampling factor per axis from the cube to the one the equirect is drawn from.
const FINE = 4;

// Writes `<dir>/<name>_cells.hdr` for the HDRI `input` (a path relative to `root`) and
// returns that path relative to `root`.
export function exactPanorama({ splitsum, root, input, name, dir, size }) {
  mkdirSync(join(root, dir), { recursive: true });
  const run = (...args) => execFileSync(splitsum, args, { cwd: root, stdio: 'inherit' });
  const cube = join(dir, `${name}_${size}.ktx2`), panorama = join(dir, `${name}_cells.hdr`);
  run('cubemap', input, '--size', String(size), '--pixel-format', 'rgba32f', '--no-zstd', '-o', cube);
  run('cubemap', cube, '--size', String(FINE * size), '--layout', 'equirect', '-o', panorama);
  return panorama;
}
