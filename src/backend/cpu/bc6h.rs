//! BC6H on the CPU: the `block_compression` crate's CPU port of ISPC's kernel, on the input
//! both backends read ([`crate::plan::bc6h::encoder_input`]), one row of blocks of one face
//! per task.

use block_compression::encode::compress_rgba16;
use block_compression::CompressionVariant;
use rayon::prelude::*;

use crate::environment::Cubemap;
use crate::plan::bc6h::{
    blocks_per_row, encoder_input, face_bytes, padded_edge, Bc6hQuality, BLOCK_BYTES, BLOCK_EDGE,
};

/// The BC6H blocks of every level of `cube`, each level its six faces one after the other.
pub fn encode_bc6h(cube: &Cubemap, quality: Bc6hQuality) -> Vec<Vec<u8>> {
    (0..cube.levels.len())
        .map(|m| {
            let n = cube.level_size(m);
            let variant = CompressionVariant::BC6H(quality.settings(n));
            let p = padded_edge(n);
            let inputs: Vec<_> = (0..6).map(|face| encoder_input(cube, m, face)).collect();
            let row_bytes = blocks_per_row(n) as usize * BLOCK_BYTES;
            let row_texels = (BLOCK_EDGE * p * 4) as usize;
            let mut level = vec![0u8; 6 * face_bytes(n)];
            level
                .par_chunks_mut(row_bytes)
                .enumerate()
                .for_each(|(row, blocks)| {
                    let (face, block_row) = (row / blocks_per_row(n) as usize, row % blocks_per_row(n) as usize);
                    let input = &inputs[face][block_row * row_texels..(block_row + 1) * row_texels];
                    compress_rgba16(variant, input, blocks, p, BLOCK_EDGE, p * 4);
                });
            level
        })
        .collect()
}
