//! Reading BC6H (unsigned float) images back: each 4×4 block through the
//! `block_compression` crate's decoder, cropped to the face's own size (a 2² or 1² face is
//! the top-left texels of one block). The encoders are the backends' (`plan::bc6h`).

use block_compression::decode::decode_block_bc6h_float;

/// Bytes of a BC6H block.
const BLOCK_BYTES: usize = 16;

/// The RGBA texels (A = 1) of an `n`² face stored as BC6H blocks in `bytes` (row-major
/// blocks; missing bytes decode as black).
pub fn decode_face(bytes: &[u8], n: u32) -> Vec<[f32; 4]> {
    let per_row = n.div_ceil(4) as usize;
    let padded = per_row * 4;
    // One row of slack: the decoder steps past its last row.
    let mut rgb = vec![0.0f32; (padded + 1) * padded * 3];
    for (k, block) in bytes.chunks_exact(BLOCK_BYTES).take(per_row * per_row).enumerate() {
        let (bx, by) = (k % per_row, k / per_row);
        let at = (by * 4 * padded + bx * 4) * 3;
        decode_block_bc6h_float(block, &mut rgb[at..], padded * 3, false);
    }
    let n = n as usize;
    (0..n * n)
        .map(|k| {
            let (x, y) = (k % n, k / n);
            let i = (y * padded + x) * 3;
            [rgb[i], rgb[i + 1], rgb[i + 2], 1.0]
        })
        .collect()
}
