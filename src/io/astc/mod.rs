//! Reading ASTC images back: a pure-Rust decoder of 2D ASTC blocks as the HDR profile
//! decodes them, to RGBA f32 texels that are each an FP16 value widened exactly. It is an
//! independent implementation of the Khronos Data Format Specification 1.3, ASTC chapter
//! ("ASTC Compressed Texture Image Formats", the "HDR Profile Support" subset), written to
//! check what the vendored encoder writes and to read ASTC KTX2 files; on every block it
//! returns what Arm's astc-encoder returns for `ASTCENC_PRF_HDR` with f32 output.
//!
//! The work per block: `block` reads the fields (the block mode in `block_mode`, integer
//! sequences in `ise`), `endpoints` unquantises the colour values and decodes each
//! partition's endpoints, `weights` unquantises and infills the weights, `partition`
//! assigns texels to partitions, and `fp16` turns the interpolated 16-bit values into FP16
//! ("Weight Application"). `tests` checks whole blocks against Arm's decoder.

mod block;
mod block_mode;
mod endpoints;
mod fp16;
mod ise;
mod partition;
mod weights;

use block::{Block, Parsed};
use fp16::{fp16_to_f32, lns_to_fp16, unorm16_to_fp16};
use weights::{MAX_TEXELS, WEIGHT_MAX};

/// Bytes of an ASTC block.
pub const BLOCK_BYTES: usize = 16;

/// The texel an illegal block decodes to: in every channel the HDR profile's error value,
/// FP16 0xFFFF (DFS "LDR and HDR Modes": "Vector of NaNs (0xFFFF)"), widened to the f32
/// NaN with bits 0xFFFFE000.
pub const ERROR_TEXEL: [f32; 4] = [f32::from_bits(0xFFFF_E000); 4];

/// The texel of image areas whose block bytes are missing: opaque black.
pub const MISSING_TEXEL: [f32; 4] = [0.0, 0.0, 0.0, 1.0];

/// The 2D footprints (width, height) the spec allows (DFS table "ASTC 2D footprint and bit
/// rates").
pub const FOOTPRINTS: [(u32, u32); 14] = [
    (4, 4),
    (5, 4),
    (5, 5),
    (6, 5),
    (6, 6),
    (8, 5),
    (8, 6),
    (10, 5),
    (10, 6),
    (8, 8),
    (10, 8),
    (10, 10),
    (12, 10),
    (12, 12),
];

/// Whether `block_w`×`block_h` is one of the spec's 14 2D footprints.
pub fn is_legal_footprint(block_w: u32, block_h: u32) -> bool {
    FOOTPRINTS.contains(&(block_w, block_h))
}

/// Decodes one 2D block of footprint `block_w`×`block_h` as the HDR RGBA profile does:
/// `out` receives the texels row-major as RGBA f32, each an FP16 value widened (when `out`
/// holds fewer than `block_w × block_h` texels, only those that fit are written). Every
/// 16-byte pattern decodes: illegal encodings, and any footprint that is not one of
/// [`FOOTPRINTS`], give [`ERROR_TEXEL`] everywhere, as Arm's decoder does.
pub fn decode_block(block: &[u8; BLOCK_BYTES], block_w: u32, block_h: u32, out: &mut [[f32; 4]]) {
    let texels = (block_w as usize * block_h as usize).min(out.len());
    let out = &mut out[..texels];
    if !is_legal_footprint(block_w, block_h) {
        out.fill(ERROR_TEXEL);
        return;
    }
    match block::parse(block, block_w, block_h) {
        Parsed::Error => out.fill(ERROR_TEXEL),
        Parsed::VoidExtent { hdr, color } => {
            // FP16 colours are returned as stored; UNORM16 ones convert as LDR channels do.
            let texel = color.map(|c| fp16_to_f32(if hdr { c } else { unorm16_to_fp16(c) }));
            out.fill(texel);
        }
        Parsed::Normal(b) => decode_normal(&b, block_w, block_h, out),
    }
}

/// The texels of an ordinary block.
fn decode_normal(b: &Block, block_w: u32, block_h: u32, out: &mut [[f32; 4]]) {
    // Unquantise each plane's grid, then infill to one weight per texel.
    let grid_len = (b.mode.grid_w * b.mode.grid_h) as usize;
    let planes = if b.mode.dual_plane { 2 } else { 1 };
    let mut texel_weights = [[0u32; MAX_TEXELS]; 2];
    for (plane, texel_weight) in texel_weights.iter_mut().enumerate().take(planes) {
        let mut grid = [0u32; 64];
        for (i, g) in grid.iter_mut().enumerate().take(grid_len) {
            let stored = b.weights.get(i * planes + plane).copied().unwrap_or(0);
            *g = weights::unquantize(b.mode.weight_range, u32::from(stored));
        }
        weights::infill(
            &grid[..grid_len],
            b.mode.grid_w,
            b.mode.grid_h,
            block_w,
            block_h,
            texel_weight,
        );
    }

    // Each partition's endpoints, from its share of the colour values.
    let mut partitions = [endpoints::decode(0, &[]); 4];
    let mut offset = 0;
    for (p, ends) in partitions
        .iter_mut()
        .enumerate()
        .take(b.partition_count as usize)
    {
        let count = endpoints::value_count(b.cems[p]);
        let values = b.color_values.get(offset..offset + count).unwrap_or(&[]);
        *ends = endpoints::decode(b.cems[p], values);
        offset += count;
    }

    let small_block = block_w * block_h < partition::SMALL_BLOCK_TEXELS;
    for (i, texel) in out.iter_mut().enumerate() {
        let (x, y) = (i as u32 % block_w, i as u32 / block_w);
        let p = if b.partition_count > 1 {
            partition::select_partition(b.partition_index, x, y, 0, b.partition_count, small_block)
        } else {
            0
        };
        let ends = &partitions[p as usize & 3];
        for (c, channel) in texel.iter_mut().enumerate() {
            let plane = usize::from(b.plane2_channel == Some(c));
            let w = texel_weights[plane][i];
            let (c0, c1) = (u32::from(ends.e0[c]), u32::from(ends.e1[c]));
            // DFS "Weight Application": C = floor((C0·(64 − i) + C1·i + 32) / 64).
            let value = ((c0 * (WEIGHT_MAX - w) + c1 * w + 32) >> 6) as u16;
            let h = if ends.hdr[c] {
                lns_to_fp16(value)
            } else {
                unorm16_to_fp16(value)
            };
            *channel = fp16_to_f32(h);
        }
    }
}

/// Decodes a `width`×`height` image stored as row-major blocks of `block_w`×`block_h`
/// (`ceil(width / block_w)` × `ceil(height / block_h)` blocks), cropping the blocks'
/// padding; texels row-major, RGBA f32. Texels whose block is missing from `bytes` (a short
/// buffer) are [`MISSING_TEXEL`], opaque black; bytes past the last block are ignored. A
/// footprint that is not one of [`FOOTPRINTS`] gives [`ERROR_TEXEL`] everywhere, and an
/// image too large to allocate an empty vector.
pub fn decode_image(
    bytes: &[u8],
    width: u32,
    height: u32,
    block_w: u32,
    block_h: u32,
) -> Vec<[f32; 4]> {
    let (w, h) = (width as usize, height as usize);
    let legal = is_legal_footprint(block_w, block_h);
    let mut image = Vec::new();
    // An image too large to allocate comes back empty rather than aborting.
    if image.try_reserve_exact(w.saturating_mul(h)).is_err() {
        return image;
    }
    image.resize(w * h, if legal { MISSING_TEXEL } else { ERROR_TEXEL });
    if !legal {
        return image;
    }
    let (bw, bh) = (block_w as usize, block_h as usize);
    let blocks_x = w.div_ceil(bw);
    let blocks_y = h.div_ceil(bh);
    let mut texels = [[0.0f32; 4]; MAX_TEXELS];
    for (k, chunk) in bytes
        .chunks_exact(BLOCK_BYTES)
        .take(blocks_x * blocks_y)
        .enumerate()
    {
        let mut block = [0u8; BLOCK_BYTES];
        block.copy_from_slice(chunk);
        decode_block(&block, block_w, block_h, &mut texels);
        let (x0, y0) = ((k % blocks_x) * bw, (k / blocks_x) * bh);
        for dy in 0..bh.min(h - y0) {
            let row = (y0 + dy) * w + x0;
            let cols = bw.min(w - x0);
            image[row..row + cols].copy_from_slice(&texels[dy * bw..dy * bw + cols]);
        }
    }
    image
}

#[cfg(test)]
mod tests;
