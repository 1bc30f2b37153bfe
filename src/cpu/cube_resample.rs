//! Cube → cube resampling (size change and rotation of cubemap inputs), CPU only: cube
//! inputs are already cubemaps, so this is a one-off preparation step, not a bake kernel.
//! Same footprint estimator as `equirect_to_cube`, reading the source cube's
//! solid-angle-correct mip chain trilinearly at the level matching each sample.

use crate::cpu::cube_downsample::build_mips;
use crate::cpu::equirect_to_cube::{fill_cube_level, footprint_mean, SAMPLES_PER_AXIS};
use crate::environment::Cubemap;
use crate::math::cubemap::{cube_face_coords, cube_face_jacobian, rotate_y};

/// Bilinear lookup of `face` at mip `m` at face coordinates (s, t), clamped to the face.
pub fn sample_cube_face_bilinear(cube: &Cubemap, m: usize, face: u32, s: f32, t: f32) -> [f32; 3] {
    let n = cube.level_size(m) as i32;
    let x = (s + 1.0) * 0.5 * n as f32 - 0.5;
    let y = (t + 1.0) * 0.5 * n as f32 - 0.5;
    let (x0, y0) = (x.floor(), y.floor());
    let (fx, fy) = (x - x0, y - y0);
    let c = |v: i32| v.clamp(0, n - 1) as u32;
    let mut out = [0.0f32; 3];
    for (dx, dy, w) in [
        (0, 0, (1.0 - fx) * (1.0 - fy)),
        (1, 0, fx * (1.0 - fy)),
        (0, 1, (1.0 - fx) * fy),
        (1, 1, fx * fy),
    ] {
        let t = cube.texel(m, face, c(x0 as i32 + dx), c(y0 as i32 + dy));
        for k in 0..3 {
            out[k] += w * t[k];
        }
    }
    out
}

/// Trilinear lookup of a cube with mips in direction `d` whose footprint is `omega`
/// steradians (0 for the finest level).
pub fn sample_cube(cube: &Cubemap, d: [f32; 3], omega: f32) -> [f32; 3] {
    let (face, s, t) = cube_face_coords(d);
    let n0 = cube.size as f32;
    let omega0 = (2.0 / n0) * (2.0 / n0) * cube_face_jacobian(s, t);
    let last = (cube.levels.len() - 1) as f32;
    let lod = if omega > 0.0 {
        (0.5 * (omega / omega0).log2()).clamp(0.0, last)
    } else {
        0.0
    };
    let l0 = lod.floor();
    let f = lod - l0;
    let a = sample_cube_face_bilinear(cube, l0 as usize, face, s, t);
    if f <= 0.0 {
        return a;
    }
    let b = sample_cube_face_bilinear(cube, (l0 as usize + 1).min(last as usize), face, s, t);
    [0, 1, 2].map(|k| a[k] + f * (b[k] - a[k]))
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
