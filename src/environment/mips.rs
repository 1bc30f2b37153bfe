//! CPU reference for `shaders/cube_downsample.wgsl`: the next mip of a cube face is the
//! solid-angle-weighted mean of each 2×2 block, Σ Lᵢ Ωᵢ / Σ Ωᵢ, so ∫ L dω over the sphere
//! is the same at every level (a plain box filter would over-weight the face corners).

use rayon::prelude::*;

use crate::environment::Cubemap;
use crate::math::cubemap::cube_texel_solid_angle;

/// Parent texel (i, j) of mip level with edge `n`, from the child level of edge 2n.
pub fn cube_downsample_texel(child: &[[f32; 4]], n: u32, face: u32, i: u32, j: u32) -> [f32; 4] {
    let cn = 2 * n;
    let mut sum = [0.0f32; 4];
    let mut weight = 0.0f32;
    for dy in 0..2 {
        for dx in 0..2 {
            let (ci, cj) = (2 * i + dx, 2 * j + dy);
            let w = cube_texel_solid_angle(ci, cj, cn);
            let t = child[((face * cn + cj) * cn + ci) as usize];
            for c in 0..4 {
                sum[c] += w * t[c];
            }
            weight += w;
        }
    }
    sum.map(|v| v / weight)
}

/// Appends mips to `cube` until it has `levels` levels (at most down to 1×1).
pub fn build_mips(cube: &mut Cubemap, levels: u32) {
    let levels = levels.min(Cubemap::full_mip_count(cube.size)) as usize;
    while cube.levels.len() < levels {
        let m = cube.levels.len();
        let n = cube.level_size(m);
        let child = &cube.levels[m - 1];
        let mut out = vec![[0.0f32; 4]; Cubemap::level_len(n)];
        out.par_chunks_mut(n as usize)
            .enumerate()
            .for_each(|(row, texels)| {
                let face = (row / n as usize) as u32;
                let j = (row % n as usize) as u32;
                for (i, t) in texels.iter_mut().enumerate() {
                    *t = cube_downsample_texel(child, n, face, i as u32, j);
                }
            });
        cube.levels.push(out);
    }
}
