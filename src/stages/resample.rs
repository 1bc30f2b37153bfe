//! Cube → cube resampling (size change and rotation of cubemap inputs), CPU only: cube
//! inputs are already cubemaps, so this is a one-off preparation step, not a bake kernel.
//! Estimator: 2×2 footprint samples per texel (weighted by the face's solid-angle density),
//! reading the source cube's
//! solid-angle-correct mip chain trilinearly (seamlessly) at the level matching each sample.

use crate::environment::mips::build_mips;
use crate::environment::sample::{cube_texel_solid_angle_at, sample_cube_lod};
use crate::environment::walk::fill_cube_level;
use crate::environment::Cubemap;
use crate::math::cubemap::{
    cube_face_direction, cube_face_jacobian, cube_texel_solid_angle, normalize, rotate_y,
};

/// Sub-texel samples per axis (S); S² samples per texel.
pub const SAMPLES_PER_AXIS: u32 = 2;

/// The solid-angle-weighted mean of `radiance` over texel (i, j) of `face` of an n×n cube:
/// S×S stratified samples, each weighted by the face's solid-angle density. `radiance`
/// receives the unit direction (before rotation) and the sample's solid angle Ω_texel/S².
pub fn footprint_mean(
    face: u32,
    i: u32,
    j: u32,
    n: u32,
    samples_per_axis: u32,
    mut radiance: impl FnMut([f32; 3], f32) -> [f32; 3],
) -> [f32; 4] {
    let s_count = samples_per_axis;
    let omega_sample = cube_texel_solid_angle(i, j, n) / (s_count * s_count) as f32;
    let mut sum = [0.0f32; 3];
    let mut weight = 0.0f32;
    for sy in 0..s_count {
        for sx in 0..s_count {
            let s = (i as f32 + (sx as f32 + 0.5) / s_count as f32) * 2.0 / n as f32 - 1.0;
            let t = (j as f32 + (sy as f32 + 0.5) / s_count as f32) * 2.0 / n as f32 - 1.0;
            let w = cube_face_jacobian(s, t);
            let v = radiance(normalize(cube_face_direction(face, s, t)), omega_sample);
            for c in 0..3 {
                sum[c] += w * v[c];
            }
            weight += w;
        }
    }
    [sum[0] / weight, sum[1] / weight, sum[2] / weight, 1.0]
}

/// Trilinear lookup of a cube with mips in direction `d` whose footprint is `omega`
/// steradians (0 for the finest level), seamless across faces.
pub fn sample_cube(cube: &Cubemap, d: [f32; 3], omega: f32) -> [f32; 3] {
    let lod = if omega > 0.0 {
        0.5 * (omega / cube_texel_solid_angle_at(cube, d)).log2()
    } else {
        0.0
    };
    sample_cube_lod(cube, d, lod)
}

/// Resamples `source` (level 0 used; its mip chain is built here) to a `face_size` cube
/// rotated by `rotate_degrees` about +Y.
pub fn cube_resample(source: &Cubemap, face_size: u32, rotate_degrees: f32) -> Cubemap {
    let mut src = Cubemap {
        size: source.size,
        levels: vec![source.levels[0].clone()],
    };
    let full = Cubemap::full_mip_count(src.size);
    build_mips(&mut src, full);
    let r = rotate_degrees.to_radians();
    let (c, s) = (r.cos(), r.sin());
    let level = fill_cube_level(face_size, |face, i, j| {
        footprint_mean(face, i, j, face_size, SAMPLES_PER_AXIS, |d, omega| {
            sample_cube(&src, rotate_y(d, c, -s), omega)
        })
    });
    Cubemap {
        size: face_size,
        levels: vec![level],
    }
}
