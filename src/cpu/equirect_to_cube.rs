//! CPU reference for `shaders/equirect_to_cube.wgsl`: each cube texel is the solid-angle
//! weighted mean of the environment over the texel's footprint.
//!
//! Estimator: S×S stratified sub-texel samples per texel, each weighted by the face's
//! solid-angle density 1/(1+s²+t²)^{3/2}; each sample reads the equirect pyramid
//! trilinearly at the level whose texel solid angle matches the sample's (Ω_texel / S²),
//! so the pyramid's exact area filter does the prefiltering and downsizing a 4k/8k HDRI to
//! a small cube does not alias (the idea of filtered importance sampling, Colbert &
//! Křivánek 2007, applied to a deterministic footprint).

use std::f32::consts::PI;

use rayon::prelude::*;

use crate::environment::{pyramid_level_count, Cubemap, Equirect, EquirectPyramid};
use crate::math::cubemap::{
    cube_face_direction, cube_face_jacobian, cube_texel_solid_angle, equirect_uv, normalize,
    rotate_y,
};

/// Sub-texel samples per axis (S); S² samples per texel.
pub const SAMPLES_PER_AXIS: u32 = 2;

/// Parameters shared by both backends.
#[derive(Clone, Copy, Debug)]
pub struct EquirectToCubeParams {
    /// Edge of the output cube face.
    pub face_size: u32,
    /// Sub-texel samples per axis.
    pub samples_per_axis: u32,
    /// Finest pyramid level any sample can use (coarser levels only below it).
    pub base_level: u32,
    /// cos and sin of the environment's rotation about +Y.
    pub rotation: [f32; 2],
}

impl EquirectToCubeParams {
    /// Parameters for a `face_size` cube from an equirect `source_height` texels high,
    /// rotated by `rotate_degrees`. Build the pyramid with `first_level = base_level`.
    pub fn new(face_size: u32, source_height: u32, rotate_degrees: f32) -> Self {
        let r = rotate_degrees.to_radians();
        EquirectToCubeParams {
            face_size,
            samples_per_axis: SAMPLES_PER_AXIS,
            base_level: finest_needed_level(
                face_size,
                SAMPLES_PER_AXIS,
                source_height,
                pyramid_level_count(source_height),
            ),
            rotation: [r.cos(), r.sin()],
        }
    }
}

/// The finest pyramid level any sample of a `face_size` cube can select (the smallest
/// sample footprint is at the face corners).
/// Levels finer than this need not be uploaded to the GPU.
pub fn finest_needed_level(face_size: u32, samples: u32, height: u32, levels: u32) -> u32 {
    let omega_sample = cube_texel_solid_angle(0, 0, face_size) / (samples * samples) as f32;
    let lod = equirect_lod(omega_sample, height);
    (lod.floor().max(0.0) as u32).min(levels - 1)
}

/// Pyramid level (fractional, relative to level 0) whose texels, as prefiltered by
/// `prefilter_latitude` (a patch (π/H) tall and as wide in arc at every latitude), have
/// the solid angle `omega_sample`: level-0 patches subtend (π/H)², each level 4× more.
pub fn equirect_lod(omega_sample: f32, height: u32) -> f32 {
    let texel = PI / height as f32;
    0.5 * (omega_sample / (texel * texel)).log2()
}

/// Bilinear lookup of one pyramid level at (u, v): columns wrap, rows clamp.
pub fn sample_equirect_bilinear(level: &Equirect, u: f32, v: f32) -> [f32; 3] {
    let (w, h) = (level.width as i32, level.height as i32);
    let x = u * w as f32 - 0.5;
    let y = v * h as f32 - 0.5;
    let (x0, y0) = (x.floor(), y.floor());
    let (fx, fy) = (x - x0, y - y0);
    let xi = |dx: i32| ((x0 as i32 + dx).rem_euclid(w)) as u32;
    let yi = |dy: i32| ((y0 as i32 + dy).clamp(0, h - 1)) as u32;
    let mut out = [0.0f32; 3];
    for (dx, dy, wgt) in [
        (0, 0, (1.0 - fx) * (1.0 - fy)),
        (1, 0, fx * (1.0 - fy)),
        (0, 1, (1.0 - fx) * fy),
        (1, 1, fx * fy),
    ] {
        let t = level.get(xi(dx), yi(dy));
        for c in 0..3 {
            out[c] += wgt * t[c];
        }
    }
    out
}

/// Trilinear lookup of the pyramid in direction `d` at fractional level `lod`
/// (clamped to [first kept level, last level]).
pub fn sample_equirect_lod(pyramid: &EquirectPyramid, d: [f32; 3], lod: f32) -> [f32; 3] {
    let last = pyramid.level_count() - 1;
    let lod = lod.clamp(pyramid.first_level as f32, last as f32);
    let l0 = lod.floor();
    let f = lod - l0;
    let (u, v) = equirect_uv(d);
    let a = sample_equirect_bilinear(pyramid.level(l0 as u32), u, v);
    let b = sample_equirect_bilinear(pyramid.level((l0 as u32 + 1).min(last)), u, v);
    [0, 1, 2].map(|c| a[c] + f * (b[c] - a[c]))
}

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

/// One output texel: the footprint mean of the environment.
pub fn equirect_to_cube_texel(
    pyramid: &EquirectPyramid,
    p: &EquirectToCubeParams,
    face: u32,
    i: u32,
    j: u32,
) -> [f32; 4] {
    footprint_mean(
        face,
        i,
        j,
        p.face_size,
        p.samples_per_axis,
        |d, omega_sample| {
            // The environment rotated by +angle shows, in direction d, what the source shows
            // in direction R(−angle)·d.
            let d = rotate_y(d, p.rotation[0], -p.rotation[1]);
            let lod = equirect_lod(omega_sample, pyramid.height);
            sample_equirect_lod(pyramid, d, lod)
        },
    )
}

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

/// Level 0 of the cube (one level; see `cube_downsample` for the chain).
pub fn equirect_to_cube(pyramid: &EquirectPyramid, p: &EquirectToCubeParams) -> Cubemap {
    let level = fill_cube_level(p.face_size, |face, i, j| {
        equirect_to_cube_texel(pyramid, p, face, i, j)
    });
    Cubemap {
        size: p.face_size,
        levels: vec![level],
    }
}
