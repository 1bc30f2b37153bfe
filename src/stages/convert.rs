//! HDRI → cubemap conversion: the step shared by `splitsum cubemap` and the bake.

use std::borrow::Cow;

use crate::environment::mips::build_mips;
use crate::stages::resample::cube_resample;
use crate::plan::convert::EquirectToCubeParams;
use crate::environment::texels::IRRADIANCE_SOURCE_SIZE;
use crate::environment::{
    Cubemap, Environment, Equirect, EquirectIntegral, EquirectReducer, IrradianceSource,
};
use crate::backend::Backend;
use crate::{Error, Result};

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

/// Checks a cube edge asked for (`size`): a power of two from 1 to 8192.
pub fn check_cube_size(size: u32) -> Result<()> {
    validate_cube_size("size", size)
}

/// Checks a requested face size, the value of `option`: a power of two from 1 to
/// [`MAX_CUBE_SIZE`], so that every mip halves exactly.
pub fn validate_cube_size(option: &'static str, size: u32) -> Result<()> {
    if size == 0 || size > MAX_CUBE_SIZE || !size.is_power_of_two() {
        return Err(Error::InvalidOption {
            option,
            message: format!("{size} is not a power of two from 1 to {MAX_CUBE_SIZE}"),
        });
    }
    Ok(())
}

/// Converts `env` to a `size` cube rotated by `rotate_degrees`, with the full mip
/// chain when `mips` is set. Equirects run on `backend`; cube inputs are resampled on the
/// CPU (see [`cube_resample`]), or kept as they are when size and rotation allow.
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

/// As [`environment_into_cube`], with the source of the irradiance cube and the SH
/// ([`IrradianceSource`], see [`crate::environment::hot`]): for an equirect, the hot
/// texels of the level the conversion read, taken out, and the rest converted to an
/// [`IRRADIANCE_SOURCE_SIZE`]² cube; for a cube input, the same split of the converted
/// cube's level 0.
pub fn environment_into_cube_with_irradiance(
    backend: &dyn Backend,
    env: Environment,
    size: u32,
    mips: bool,
    rotate_degrees: f32,
) -> Result<(Cubemap, IrradianceSource)> {
    match env {
        Environment::Equirect(e) => {
            let (cube, integral, params) =
                equirect_cube(backend, Cow::Owned(e), size, mips, rotate_degrees)?;
            let mut cold = Equirect {
                width: integral.width,
                height: integral.height,
                data: integral.radiance,
            };
            let hot = crate::environment::hot::split_equirect(&mut cold, params.rotation);
            // The cold rest has no lamp to place to a fraction of a texel: a level of at
            // most COLD_MAX_WIDTH columns (texels ~1/7 of a 64² cube's smallest) keeps
            // the second conversion's tables small.
            while cold.width > COLD_MAX_WIDTH {
                cold = cold.downsample();
            }
            let (cold, _, _) = equirect_cube(
                backend,
                Cow::Owned(cold),
                IRRADIANCE_SOURCE_SIZE,
                true,
                rotate_degrees,
            )?;
            Ok((cube, IrradianceSource { cold, hot }))
        }
        cube => {
            let cube = convert(backend, Cow::Owned(cube), size, mips, rotate_degrees)?;
            let source = IrradianceSource::from_cube(&cube);
            Ok((cube, source))
        }
    }
}

/// Widest equirect level the cold part of the irradiance source is converted from.
pub const COLD_MAX_WIDTH: u32 = 2048;

fn check_rotation(rotate_degrees: f32) -> Result<()> {
    if !rotate_degrees.is_finite() {
        return Err(Error::InvalidOption {
            option: "rotate_degrees",
            message: format!("{rotate_degrees} is not a finite angle"),
        });
    }
    Ok(())
}

fn level_count(size: u32, mips: bool) -> u32 {
    if mips {
        Cubemap::full_mip_count(size)
    } else {
        1
    }
}

/// An equirect's cube, with the integral it was computed from (its radiance is the level
/// the conversion read) and the conversion's parameters.
fn equirect_cube(
    backend: &dyn Backend,
    e: Cow<'_, Equirect>,
    size: u32,
    mips: bool,
    rotate_degrees: f32,
) -> Result<(Cubemap, EquirectIntegral, EquirectToCubeParams)> {
    validate_cube_size("size", size)?;
    check_rotation(rotate_degrees)?;
    let params = EquirectToCubeParams::new(size, e.width, e.height, rotate_degrees);
    let level = match (params.base_level, e) {
        (0, e) => e.into_owned(),
        (levels, e) => reduce(&e, levels),
    };
    let integral = EquirectIntegral::new(level);
    let cube = backend.equirect_to_cube(&integral, &params, level_count(size, mips))?;
    Ok((cube, integral, params))
}

fn convert(
    backend: &dyn Backend,
    env: Cow<'_, Environment>,
    size: u32,
    mips: bool,
    rotate_degrees: f32,
) -> Result<Cubemap> {
    validate_cube_size("size", size)?;
    check_rotation(rotate_degrees)?;
    let levels = level_count(size, mips);
    let keep = |c: &Cubemap| c.size == size && rotate_degrees.rem_euclid(360.0) == 0.0;
    match env {
        Cow::Borrowed(Environment::Equirect(e)) => {
            equirect_cube(backend, Cow::Borrowed(e), size, mips, rotate_degrees).map(|c| c.0)
        }
        Cow::Owned(Environment::Equirect(e)) => {
            equirect_cube(backend, Cow::Owned(e), size, mips, rotate_degrees).map(|c| c.0)
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
