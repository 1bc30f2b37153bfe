//! HDRI → cubemap conversion: the step shared by `splitsum cubemap` and the bake.

use std::borrow::Cow;

use crate::cpu::cube_downsample::build_mips;
use crate::cpu::cube_resample::cube_resample;
use crate::cpu::equirect_to_cube::EquirectToCubeParams;
use crate::environment::{Cubemap, Environment, Equirect, EquirectIntegral, EquirectReducer};
use crate::{Backend, Error, Result};

/// Largest cube face edge accepted.
pub const MAX_CUBE_SIZE: u32 = 8192;

/// The default face size for an environment: the largest power of two ≤ width/4 for an
/// equirect (a cube face then has about the equirect's angular resolution at the equator),
/// the input's own face size for a cube, capped at [`MAX_CUBE_SIZE`].
pub fn default_cube_size(env: &Environment) -> u32 {
    let target = match env {
        Environment::Equirect(e) => (e.width / 4).max(1),
        Environment::Cube(c) => c.size,
    };
    (1u32 << (31 - target.leading_zeros())).min(MAX_CUBE_SIZE)
}

/// Checks a requested face size: a power of two in 1..=[`MAX_CUBE_SIZE`], so that every
/// mip halves exactly.
pub fn validate_cube_size(size: u32) -> Result<()> {
    if size == 0 || size > MAX_CUBE_SIZE || !size.is_power_of_two() {
        return Err(Error::InvalidParameter {
            name: "--size",
            message: format!("cube size {size} must be a power of two in 1..={MAX_CUBE_SIZE}"),
        });
    }
    Ok(())
}

/// Converts `env` to a `size` cube rotated by `rotate_degrees`, with the full mip
/// chain when `mips` is set. Equirects run on `backend`; cube inputs are resampled on the
/// CPU (see `cpu::cube_resample`), or kept as they are when size and rotation allow.
pub fn environment_to_cube(
    backend: &dyn Backend,
    env: &Environment,
    size: u32,
    mips: bool,
    rotate_degrees: f32,
) -> Result<Cubemap> {
    convert(backend, Cow::Borrowed(env), size, mips, rotate_degrees)
}

/// As [`environment_to_cube`], consuming `env`: an equirect's finest kept level or a
/// cube's level 0 is used in place instead of copied (what a bake does, to keep its peak
/// memory down).
pub fn environment_into_cube(
    backend: &dyn Backend,
    env: Environment,
    size: u32,
    mips: bool,
    rotate_degrees: f32,
) -> Result<Cubemap> {
    convert(backend, Cow::Owned(env), size, mips, rotate_degrees)
}

fn convert(
    backend: &dyn Backend,
    env: Cow<'_, Environment>,
    size: u32,
    mips: bool,
    rotate_degrees: f32,
) -> Result<Cubemap> {
    validate_cube_size(size)?;
    if !rotate_degrees.is_finite() {
        return Err(Error::InvalidParameter {
            name: "--rotate",
            message: format!("{rotate_degrees} is not a finite angle"),
        });
    }
    let levels = if mips {
        Cubemap::full_mip_count(size)
    } else {
        1
    };
    let keep = |c: &Cubemap| c.size == size && rotate_degrees.rem_euclid(360.0) == 0.0;
    match env {
        Cow::Borrowed(Environment::Equirect(e)) => {
            let params = EquirectToCubeParams::new(size, e.width, e.height, rotate_degrees);
            let level = if params.base_level == 0 {
                e.clone()
            } else {
                reduce(e, params.base_level)
            };
            backend.equirect_to_cube(&EquirectIntegral::new(level), &params, levels)
        }
        Cow::Owned(Environment::Equirect(e)) => {
            let params = EquirectToCubeParams::new(size, e.width, e.height, rotate_degrees);
            let level = if params.base_level == 0 {
                e
            } else {
                reduce(&e, params.base_level)
            };
            backend.equirect_to_cube(&EquirectIntegral::new(level), &params, levels)
        }
        Cow::Borrowed(Environment::Cube(c)) => {
            let mut cube = if keep(c) {
                Cubemap {
                    size,
                    levels: vec![c.levels[0].clone()],
                }
            } else {
                cube_resample(c, size, rotate_degrees)
            };
            build_mips(&mut cube, levels);
            Ok(cube)
        }
        Cow::Owned(Environment::Cube(mut c)) => {
            let mut cube = if keep(&c) {
                c.levels.truncate(1);
                c
            } else {
                cube_resample(&c, size, rotate_degrees)
            };
            build_mips(&mut cube, levels);
            Ok(cube)
        }
    }
}

/// `image` reduced by `levels` exact area halvings.
fn reduce(image: &Equirect, levels: u32) -> Equirect {
    let mut reducer = EquirectReducer::new(image.width, image.height, levels);
    reducer.push_all(&image.data);
    reducer.finish()
}
