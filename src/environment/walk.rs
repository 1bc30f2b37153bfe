//! Walking a cube's texels: the one place that turns (face, column, row) into texel
//! centres and fills a level, in parallel over rows.

use rayon::prelude::*;

use crate::environment::Cubemap;
use crate::math::cubemap::{cube_texel_direction, FACES};

/// Fills level 0 of an n×n cube with `texel(face, i, j)`, in parallel over rows.
pub fn fill_cube_level(n: u32, texel: impl Fn(u32, u32, u32) -> [f32; 4] + Sync) -> Vec<[f32; 4]> {
    let mut level = vec![[0.0f32; 4]; Cubemap::level_len(n)];
    level
        .par_chunks_mut(n as usize)
        .enumerate()
        .for_each(|(row, out)| {
            let face = (row / n as usize) as u32;
            let j = (row % n as usize) as u32;
            for (i, t) in out.iter_mut().enumerate() {
                *t = texel(face, i as u32, j);
            }
        });
    level
}

/// Every texel of an n² cube level in storage order (face-major, then rows top to bottom,
/// then columns): `(face, i, j, d)` with d the unit direction through the texel's centre.
pub fn texel_centres(n: u32) -> impl Iterator<Item = (u32, u32, u32, [f32; 3])> {
    (0..FACES as u32).flat_map(move |face| {
        (0..n).flat_map(move |j| {
            (0..n).map(move |i| {
                (
                    face,
                    i,
                    j,
                    cube_texel_direction(face, i as i32, j as i32, n),
                )
            })
        })
    })
}
