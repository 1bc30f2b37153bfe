//! Cube → cube resampling (size change and rotation of cubemap inputs), CPU only: cube
//! inputs are already cubemaps, so this is a one-off preparation step, not a bake kernel.
//! Same footprint estimator as `equirect_to_cube`, reading the source cube's
//! solid-angle-correct mip chain trilinearly (seamlessly) at the level matching each sample.

use crate::cpu::cube_downsample::build_mips;
use crate::cpu::cube_sample::{cube_texel_solid_angle_at, sample_cube_lod};
use crate::cpu::equirect_to_cube::{fill_cube_level, footprint_mean, SAMPLES_PER_AXIS};
use crate::environment::Cubemap;
use crate::math::cubemap::rotate_y;

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
