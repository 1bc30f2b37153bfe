//! The prefiltered Charlie sheen chain's plan and driver, shared by both backends: the
//! environment convolved with the Charlie sheen distribution (Estevez & Kulla 2017,
//! KHR_materials_sheen's D with α = r²), with n = v as for GGX, for the glTF Sample
//! Viewer's `u_CharlieEnvSampler` (read at lod = sheen roughness · (M − 1), the GGX
//! chain's mapping).
//!
//! Estimator: the exact sum P(n) = Σ L(l) D(h) (n·l) Ω / Σ D(h) (n·l) Ω over every texel of a
//! source mip plus the hot cells at the source's resolution ([`exact_source_texels`]), h =
//! normalize(n + l) — what glTF-IBL-Sampler's Monte Carlo filter converges to: it draws h
//! with density D(h)(n·h) (sin θ = ξ^(α/(2α + 1))) and weights each l by n·l. With n = v,
//! sin²θh = (1 − n·l)/2, so D ∝ (1 − n·l)^(1/(2α)): the lobe is a ring towards n's horizon,
//! about 2α wide in n·l for small α (see [`crate::math::brdf::charlie_prefilter_weight`]).
//!
//! The Charlie lobe is broad at every roughness the chain holds past level 0 (the ring at
//! r = 1/6 spans several degrees), so each level is integrated at a fixed edge
//! ([`sheen_level_plan`]) from a source mip of at most [`SHEEN_SOURCE_SIZE`] plus the hot
//! cells; larger levels interpolate the integration (seamless bilinear), the smallest are
//! fitted to it through the lookup a shader makes. `tests/sheen.rs` measures the result
//! against a brute-force sum over every texel of the source equirect.

use crate::environment::sample::sample_cube_lod;
use crate::environment::texels::SourceTexel;
use crate::environment::walk::fill_cube_level;
use crate::environment::{Cubemap, IrradianceSource};
use crate::math::cubemap::cube_texel_direction;
use crate::plan::chain::SpecularChain;
use crate::plan::fit::fit_level_for_lookup;
use crate::plan::sources::exact_source_texels;


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
/// — [`prefilter_charlie_texel`](crate::cpu::convolve_exact::prefilter_charlie_texel) at every texel on the CPU, mode 2 of
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
