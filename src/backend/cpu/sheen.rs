//! The CPU backend's Charlie sheen chain (see [`crate::plan::sheen`]): each level's exact
//! sum in lanes ([`prefilter_charlie_lanes`]), and the texel-by-texel reference the GPU
//! kernel mirrors.

use crate::backend::cpu::lanes::{prefilter_charlie_lanes, ExactSource};
#[cfg(any(test, feature = "internals"))]
use crate::cpu::convolve_exact::prefilter_charlie_texel;
use crate::environment::walk::fill_cube_level;
use crate::environment::{Cubemap, IrradianceSource};
use crate::math::cubemap::cube_texel_direction;
use crate::plan::chain::SpecularChain;
use crate::plan::sheen::sheen_chain;

/// The prefiltered Charlie chain of `env` (every mip present) in `chain`'s layout on the
/// CPU (see the module documentation and [`sheen_chain`]): the CPU backend's, each texel
/// summed in lanes ([`prefilter_charlie_lanes`]).
pub fn prefilter_sheen(
    env: &Cubemap,
    split: Option<&IrradianceSource>,
    chain: SpecularChain,
) -> Cubemap {
    let Ok(cube) = sheen_chain::<std::convert::Infallible>(env, split, chain, |source, n, r| {
        let lanes = ExactSource::new(source);
        Ok(at_texel_centres(n, |d| {
            prefilter_charlie_lanes(&lanes, d, r)
        }))
    });
    cube
}

#[cfg(any(test, feature = "internals"))]
/// [`prefilter_sheen`] with the texel-by-texel reference sum ([`prefilter_charlie_texel`]),
/// the one the GPU kernel mirrors.
pub fn prefilter_sheen_reference(
    env: &Cubemap,
    split: Option<&IrradianceSource>,
    chain: SpecularChain,
) -> Cubemap {
    let Ok(cube) = sheen_chain::<std::convert::Infallible>(env, split, chain, |source, n, r| {
        Ok(at_texel_centres(n, |d| {
            prefilter_charlie_texel(source, d, r)
        }))
    });
    cube
}

/// An n² cube level of `sum(d)` at every texel centre d.
fn at_texel_centres(n: u32, sum: impl Fn([f32; 3]) -> [f32; 4] + Sync) -> Vec<[f32; 4]> {
    fill_cube_level(n, |face, i, j| {
        sum(cube_texel_direction(face, i as i32, j as i32, n))
    })
}
