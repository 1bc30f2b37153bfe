//! CPU twin of `shaders/prefilter_sampled.wgsl`: the split-sum prefiltered radiance
//! (Karis 2013), with n = v = r, of an importance-sampled level.
//!
//! Estimator: P(n) = Σ L(lᵢ) (n·lᵢ) / Σ (n·lᵢ), lᵢ = reflect(−n, hᵢ) with hᵢ GGX-distributed
//! (Hammersley points), which converges to ∫ L D (n·l) dl / ∫ D (n·l) dl. The samples
//! depend only on the level, so they are computed once per level in n's tangent frame
//! ([`crate::plan::sources::ggx_lobe_samples`], filtered importance sampling) and rotated
//! to each texel; the hot texels split off the source are summed exactly.

use crate::environment::texels::SourceTexel;
use crate::math::brdf::{alpha_from_roughness, d_ggx};
use crate::math::sampling::tangent_frame;
use crate::plan::sources::SampledSource;

/// The exact part of a sampled texel: Σ L Ω (n·l) pdf(l) over the hot texels, with
/// pdf(l) = D(n·h)/4 (the density the samples are drawn from, for v = n).
pub fn hot_texels_sum(hot: &[SourceTexel], n: [f32; 3], alpha: f32) -> [f32; 3] {
    let mut sum = [0.0f32; 3];
    for t in hot {
        let l = t.dir_omega;
        let n_dot_l = n[0] * l[0] + n[1] * l[1] + n[2] * l[2];
        if n_dot_l > 0.0 {
            let n_dot_h = (0.5 * (1.0 + n_dot_l)).sqrt();
            let w = l[3] * n_dot_l * d_ggx(n_dot_h, alpha) * 0.25;
            for (s, r) in sum.iter_mut().zip(&t.radiance) {
                *s += w * r;
            }
        }
    }
    sum
}

/// Prefiltered radiance around unit direction `n`: filtered importance sampling of
/// `src.rest` with the `lobe` of [`ggx_lobe_samples`](crate::plan::sources::ggx_lobe_samples) (drawn from `samples` points) plus
/// the exact sum of `src.hot` at `roughness`, both over the sampled normaliser:
/// (Σᵢ L(lᵢ)(n·lᵢ) + N·Σ_hot) / Σᵢ (n·lᵢ).
pub fn prefilter_texel(
    src: &SampledSource,
    n: [f32; 3],
    roughness: f32,
    lobe: &[[f32; 4]],
    samples: u32,
) -> [f32; 4] {
    let (t, b) = tangent_frame(n);
    let mut sum = [0.0f32; 3];
    let mut weight = 0.0f32;
    for s in lobe {
        let l = [0, 1, 2].map(|k| t[k] * s[0] + b[k] * s[1] + n[k] * s[2]);
        let v = src.bordered.sample_lod(l, s[3]);
        for c in 0..3 {
            sum[c] += v[c] * s[2];
        }
        weight += s[2];
    }
    let hot = hot_texels_sum(&src.hot, n, alpha_from_roughness(roughness));
    let k = samples as f32;
    [
        (sum[0] + k * hot[0]) / weight,
        (sum[1] + k * hot[1]) / weight,
        (sum[2] + k * hot[2]) / weight,
        1.0,
    ]
}
