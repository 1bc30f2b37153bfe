//! The prefiltered Charlie sheen chain: the environment convolved with the Charlie sheen
//! distribution (Estevez & Kulla 2017, KHR_materials_sheen's D with α = r²), with n = v as
//! for GGX, for the glTF Sample Viewer's `u_CharlieEnvSampler` (read at lod = sheen
//! roughness · (M − 1), the GGX chain's mapping).
//!
//! Estimator: the exact sum P(n) = Σ L(l) D(h) (n·l) Ω / Σ D(h) (n·l) Ω over every texel of a
//! source mip plus the hot cells at the source's resolution ([`exact_source_texels`]), h =
//! normalize(n + l) — what glTF-IBL-Sampler's Monte Carlo filter converges to: it draws h
//! with density D(h)(n·h) (sin θ = ξ^(α/(2α + 1))) and weights each l by n·l. With n = v,
//! sin²θh = (1 − n·l)/2, so D ∝ (1 − n·l)^(1/(2α)): the lobe is a ring towards n's horizon,
//! about 2α wide in n·l for small α (see [`charlie_prefilter_weight`]).
//!
//! The Charlie lobe is broad at every roughness the chain holds past level 0 (the ring at
//! r = 1/6 spans several degrees), so each level is integrated at a fixed edge
//! ([`sheen_level_plan`]) from a source mip of at most [`SHEEN_SOURCE_SIZE`] plus the hot
//! cells; larger levels interpolate the integration (seamless bilinear), the smallest are
//! fitted to it through the lookup a shader makes. `tests/sheen.rs` measures the result
//! against a brute-force sum over every texel of the source equirect.

use crate::cpu::cube_sample::sample_cube_lod;
use crate::cpu::equirect_to_cube::fill_cube_level;
use crate::cpu::irradiance::SourceTexel;
use crate::cpu::prefilter_specular::{
    exact_source_texels, prefilter_lobe_texel, ExactSource, SpecularChain,
};
use crate::cpu::roughest_level::fit_level_for_lookup;
use crate::environment::{Cubemap, IrradianceSource};
use crate::math::brdf::{alpha_from_roughness, charlie_prefilter_weight};
use crate::math::cubemap::cube_texel_direction;

/// Edge at which a sheen level is integrated when its lobe is broad (r ≥
/// [`SHEEN_THIN_RING`]); larger levels interpolate it, smaller ones are fitted to it.
pub const SHEEN_INTEGRATION_SIZE: u32 = 32;
/// Edge at which the thin-ring levels (r < [`SHEEN_THIN_RING`]) are integrated: the ring
/// is a few degrees wide there, and a sun crossing it changes the value within a degree.
pub const SHEEN_THIN_RING_INTEGRATION_SIZE: u32 = 64;
/// Below this roughness the Charlie ring is thin (about 2α in n·l).
pub const SHEEN_THIN_RING: f32 = 0.3;
/// Largest source mip of a sheen level's exact sum (the hot cells come at the source's
/// own resolution whatever this is).
pub const SHEEN_SOURCE_SIZE: u32 = 32;
/// Levels at most this edge are fitted (least squares, through the bilinear lookup) to
/// the integrated level instead of holding its values at their own texel centres: a 4² or
/// 8² face interpolated between centres misses the lobe of a sun by up to 70 % and 36 %.
pub const SHEEN_FIT_MAX_SIZE: u32 = 8;

/// The roughness sheen level `m` is prefiltered at: the chain's, except level 0, where
/// sheen roughness 0 has no lobe (D concentrates on half vectors at 90°, whose reflection
/// is −n; glTF-IBL-Sampler's filter writes black there): it holds the first level's lobe,
/// the thinnest the chain resolves, so a lookup below that roughness reads it.
pub fn sheen_level_roughness(chain: &SpecularChain, m: u32) -> f32 {
    chain.mip_roughness(m.max(1).min(chain.levels.saturating_sub(1)))
}

/// Exact Charlie-prefiltered radiance around unit `n` at `roughness` over `source` (see the
/// module documentation). The GPU mirror is mode 2 of `shaders/convolve_exact.wgsl`.
pub fn prefilter_charlie_texel(source: &[SourceTexel], n: [f32; 3], roughness: f32) -> [f32; 4] {
    let alpha = alpha_from_roughness(roughness);
    prefilter_lobe_texel(source, n, |n_dot_l| {
        charlie_prefilter_weight(n_dot_l, alpha)
    })
}

/// How the power (1 − n·l)^(1/(2α)) of the Charlie weight is taken in the lane sum: by
/// repeated squaring where the exponent is 2, 4, 8 or 16 (the viewer's chain at r = 1/2
/// and 1/4: 2 and 8), by a square root where it is ½ (r = 1), all of which vectorise,
/// and by `powf` otherwise.
#[derive(Clone, Copy, Debug, PartialEq)]
enum LanePower {
    Squarings(u32),
    Sqrt,
    Powf(f32),
}

impl LanePower {
    fn new(exponent: f32) -> Self {
        match exponent {
            0.5 => LanePower::Sqrt,
            2.0 => LanePower::Squarings(1),
            4.0 => LanePower::Squarings(2),
            8.0 => LanePower::Squarings(3),
            16.0 => LanePower::Squarings(4),
            e => LanePower::Powf(e),
        }
    }
}

/// [`prefilter_charlie_texel`] over the lane-packed texels of `source`: the same sum in
/// [`ExactSource::lobe_sum`]'s branch-free form, the power taken as [`LanePower`] says
/// (the CPU backend's sum; the reference and the GPU kernel keep the texel-by-texel loop
/// and `pow`).
pub fn prefilter_charlie_lanes(source: &ExactSource, n: [f32; 3], roughness: f32) -> [f32; 4] {
    let power = LanePower::new(0.5 / alpha_from_roughness(roughness));
    #[cfg(target_arch = "x86_64")]
    if std::is_x86_feature_detected!("avx") {
        // SAFETY: the CPU has AVX, checked just above.
        return unsafe { charlie_sum_avx(source, n, power) };
    }
    charlie_sum(source, n, power)
}

/// [`charlie_sum`] compiled for AVX (without FMA, as [`ExactSource::prefilter`]).
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx")]
fn charlie_sum_avx(source: &ExactSource, n: [f32; 3], power: LanePower) -> [f32; 4] {
    charlie_sum(source, n, power)
}

/// x^(2^S) by S squarings.
#[inline(always)]
fn squared<const S: u32>(x: f32) -> f32 {
    (0..S).fold(x, |x, _| x * x)
}

#[inline(always)]
fn charlie_sum(source: &ExactSource, n: [f32; 3], power: LanePower) -> [f32; 4] {
    // The weight (1 − n·l)^e (n·l) Ω in the order charlie_prefilter_weight takes it; a
    // texel below the horizon has n·l clamped to 0 and so weight 0.
    let x = |n_dot_l: f32| (1.0 - n_dot_l).max(0.0);
    match power {
        LanePower::Squarings(1) => source.lobe_sum(n, |c, o| squared::<1>(x(c)) * c * o),
        LanePower::Squarings(2) => source.lobe_sum(n, |c, o| squared::<2>(x(c)) * c * o),
        LanePower::Squarings(3) => source.lobe_sum(n, |c, o| squared::<3>(x(c)) * c * o),
        LanePower::Squarings(_) => source.lobe_sum(n, |c, o| squared::<4>(x(c)) * c * o),
        LanePower::Sqrt => source.lobe_sum(n, |c, o| x(c).sqrt() * c * o),
        LanePower::Powf(e) => source.lobe_sum(n, |c, o| x(c).powf(e) * c * o),
    }
}

/// How a sheen level is made from its integration.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SheenFinish {
    /// The integrated texels are the level's.
    AsIs,
    /// The level interpolates the (smaller) integrated level, seamless bilinear.
    Interpolate,
    /// The level's texels are fitted to the (larger) integrated level through the lookup
    /// (`cpu::roughest_level::fit_level_for_lookup`).
    Fit,
}

/// How level `m` (edge `size`, at `roughness`) of an `env_size` chain is computed.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct SheenPlan {
    /// Edge of the exact sum's output.
    pub integration: u32,
    /// From the integration to the level.
    pub finish: SheenFinish,
}

/// The source mip every level's exact sum reads: the largest of at most
/// [`SHEEN_SOURCE_SIZE`] (the hot cells come at the source's own resolution).
pub fn sheen_source_mip(env_size: u32) -> u32 {
    (env_size / env_size.min(SHEEN_SOURCE_SIZE)).trailing_zeros()
}

/// The plan of level `m` of an `env_size` chain at `roughness`.
pub fn sheen_level_plan(env_size: u32, m: u32, roughness: f32) -> SheenPlan {
    let size = (env_size >> m).max(1);
    let wanted = if roughness < SHEEN_THIN_RING {
        SHEEN_THIN_RING_INTEGRATION_SIZE
    } else {
        SHEEN_INTEGRATION_SIZE
    };
    let (integration, finish) = if size > wanted {
        (wanted, SheenFinish::Interpolate)
    } else if size <= SHEEN_FIT_MAX_SIZE && wanted.min(env_size) >= 2 * size {
        (wanted.min(env_size), SheenFinish::Fit)
    } else {
        (size, SheenFinish::AsIs)
    };
    SheenPlan {
        integration,
        finish,
    }
}

/// Level `size`² from its integrated texels (edge `plan.integration`), as `plan` says.
pub fn finish_sheen_level(integrated: Vec<[f32; 4]>, plan: SheenPlan, size: u32) -> Vec<[f32; 4]> {
    let small = |texels| Cubemap {
        size: plan.integration,
        levels: vec![texels],
    };
    // The seamless bilinear values of the integration at the level's texel centres.
    let interpolated = |small: &Cubemap| {
        fill_cube_level(size, |face, i, j| {
            let d = cube_texel_direction(face, i as i32, j as i32, size);
            let [r, g, b] = sample_cube_lod(small, d, 0.0);
            [r, g, b, 1.0]
        })
    };
    match plan.finish {
        SheenFinish::AsIs => integrated,
        SheenFinish::Interpolate => interpolated(&small(integrated)),
        SheenFinish::Fit => {
            let target = small(integrated);
            // Singular normal equations (not seen): the values at the texel centres.
            fit_level_for_lookup(size, &target).unwrap_or_else(|| interpolated(&target))
        }
    }
}

/// The Charlie chain of `env` (every mip present) in `chain`'s layout, each level from the
/// exact sum `integrate(source, n, r)` makes over `source` (the texels of
/// [`sheen_source_mip`] and the hot cells, gathered once) on an `n`² cube at roughness `r`
/// — [`prefilter_charlie_texel`] at every texel on the CPU, mode 2 of
/// `convolve_exact.wgsl` on the GPU — then finished as [`sheen_level_plan`] says. Levels
/// with the same integration and roughness (0 and 1) share one sum.
pub fn sheen_chain<E>(
    env: &Cubemap,
    split: Option<&IrradianceSource>,
    chain: SpecularChain,
    mut integrate: impl FnMut(&[SourceTexel], u32, f32) -> Result<Vec<[f32; 4]>, E>,
) -> Result<Cubemap, E> {
    let levels = chain.levels.clamp(1, Cubemap::full_mip_count(env.size));
    let chain = SpecularChain { levels, ..chain };
    let source = exact_source_texels(env, split, sheen_source_mip(env.size) as usize);
    // The last integration, keyed by its edge and the roughness's bits.
    type Integrated = ((u32, u32), Vec<[f32; 4]>);
    let mut last: Option<Integrated> = None;
    let mut out = Vec::with_capacity(levels as usize);
    for m in 0..levels {
        let r = sheen_level_roughness(&chain, m);
        let plan = sheen_level_plan(env.size, m, r);
        let key = (plan.integration, r.to_bits());
        let integrated = match last.take() {
            Some((k, texels)) if k == key => texels,
            _ => integrate(&source, plan.integration, r)?,
        };
        out.push(finish_sheen_level(
            integrated.clone(),
            plan,
            env.level_size(m as usize),
        ));
        last = Some((key, integrated));
    }
    Ok(Cubemap {
        size: env.size,
        levels: out,
    })
}

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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::cpu::prefilter_specular::{lane_test_normals, lane_test_source};

    /// The lane-packed sum gives the texel-by-texel reference's value at every roughness
    /// of the viewer's chain and between (each kind of power: squarings at r = 1/4 and 1/2,
    /// the square root at 1, powf at 0.3 and 3/4), within 2e-5 relative: two sums of 1533
    /// f32 terms in different orders (~√N·ε ≈ 5e-6), and x⁸ by three squarings against
    /// powf (≤ 7 roundings, 8e-7 per weight); on a source with a bright spot and a texel
    /// count that is not a multiple of the lane width.
    #[test]
    fn lane_sum_equals_the_reference() {
        let texels = lane_test_source();
        let lanes = ExactSource::new(&texels);
        for (r, power) in [
            (0.25f32, LanePower::Squarings(3)),
            (0.5, LanePower::Squarings(1)),
            (1.0, LanePower::Sqrt),
            (0.3, LanePower::Powf(0.5 / 0.09)),
            (0.75, LanePower::Powf(0.5 / 0.5625)),
        ] {
            let exponent = 0.5 / alpha_from_roughness(r);
            assert_eq!(LanePower::new(exponent), power, "r {r}");
            for n in lane_test_normals() {
                let want = prefilter_charlie_texel(&texels, n, r);
                let got = prefilter_charlie_lanes(&lanes, n, r);
                for c in 0..3 {
                    let rel = (got[c] - want[c]).abs() / want[c].abs().max(1e-6);
                    assert!(
                        rel <= 2e-5,
                        "r {r} n {n:?} channel {c}: {} vs {}",
                        got[c],
                        want[c]
                    );
                }
            }
        }
    }
}
