//! CPU twin of `shaders/convolve_exact.wgsl`: exact convolutions over every texel of a
//! small source mip (no noise), texel by texel as the kernel does them:
//! - mode 0, prefiltered specular ([`prefilter_exact_texel`]): Σ L D(n·h) (n·l) Ω /
//!   Σ D(n·h) (n·l) Ω, h = normalize(n + l);
//! - mode 1, irradiance ([`irradiance_texel`]): E(n)/π as a sum of max(0, n · Mₖ), Mₖ =
//!   ∫ L l dω, over every texel of the cold ≤ 64² cube and every cell of the hot texels
//!   split off at the source's resolution ([`crate::environment::hot`]). The clamped
//!   cosine is linear in l above the horizon, so this equals the full-resolution integral
//!   except for the texels and cells straddling n's horizon, which are modelled as caps
//!   (clipped in closed form); a sun keeps its exact direction and its terminator is
//!   resolved to a quarter of a source texel;
//! - mode 2, prefiltered sheen ([`prefilter_charlie_texel`]): the Charlie lobe's sum, as
//!   mode 0 with the Charlie weight.
//!
//! The CPU backend sums the same terms faster (`backend::cpu`: lanes, runs); these are the
//! references it and the GPU are checked against.

use std::f32::consts::PI;

use crate::environment::texels::MomentTexel;
#[cfg(any(test, feature = "internals"))]
use crate::environment::texels::SourceTexel;
#[cfg(any(test, feature = "internals"))]
use crate::math::brdf::{alpha_from_roughness, charlie_prefilter_weight, ggx_prefilter_weight};
use crate::math::trig::{acos_precise, atan_precise};

#[cfg(any(test, feature = "internals"))]
/// Exact prefiltered radiance around unit `n`: Σ L D(n·h) (n·l) Ω / Σ D(n·h) (n·l) Ω over
/// every texel of a source mip, h = normalize(n + l). No noise and no leak of a bright sun
/// beyond its true lobe; used where the lobe is wide enough that a small mip resolves it.
pub fn prefilter_exact_texel(source: &[SourceTexel], n: [f32; 3], roughness: f32) -> [f32; 4] {
    let alpha = alpha_from_roughness(roughness);
    prefilter_lobe_texel(source, n, |n_dot_l| ggx_prefilter_weight(n_dot_l, alpha))
}

#[cfg(any(test, feature = "internals"))]
/// Σ L w(n·l) Ω / Σ w(n·l) Ω over the texels of `source` above n's horizon, for a lobe
/// weight `lobe` (D times n·l with n = v: [`ggx_prefilter_weight`], or
/// [`crate::math::brdf::charlie_prefilter_weight`] for sheen). A hot cell's normaliser
/// weight (`radiance[3]`) is 0: it adds light, not solid angle. The GPU mirror is
/// `prefilter_lobe_texel` in `shaders/convolve_exact.wgsl`.
pub fn prefilter_lobe_texel(
    source: &[SourceTexel],
    n: [f32; 3],
    lobe: impl Fn(f32) -> f32,
) -> [f32; 4] {
    let mut sum = [0.0f32; 3];
    let mut weight = 0.0f32;
    for t in source {
        let l = t.dir_omega;
        let n_dot_l = n[0] * l[0] + n[1] * l[1] + n[2] * l[2];
        if n_dot_l > 0.0 {
            let w = lobe(n_dot_l) * l[3];
            for (sc, lc) in sum.iter_mut().zip(&t.radiance) {
                *sc += w * lc;
            }
            weight += w * t.radiance[3];
        }
    }
    [sum[0] / weight, sum[1] / weight, sum[2] / weight, 1.0]
}

#[cfg(any(test, feature = "internals"))]
/// Exact Charlie-prefiltered radiance around unit `n` at `roughness` over `source` (see the
/// module documentation). The GPU mirror is mode 2 of `shaders/convolve_exact.wgsl`.
pub fn prefilter_charlie_texel(source: &[SourceTexel], n: [f32; 3], roughness: f32) -> [f32; 4] {
    let alpha = alpha_from_roughness(roughness);
    prefilter_lobe_texel(source, n, |n_dot_l| {
        charlie_prefilter_weight(n_dot_l, alpha)
    })
}


/// Below this sin²σ (σ ≈ 1.8°) [`clipped_cap_cosine`] treats the cap as a flat disk: the
/// closed form's terms cancel to O(σ³) there, which f32 cannot resolve (at sin²σ = 1e-6
/// it is ~10 % off), while the disk's error is O(σ²) relative (< 1e-3).
pub const SMALL_CAP_SIN2: f32 = 1e-3;

/// ∫ max(0, n·l) dω over a spherical cap of half-angle σ whose centre makes cos θ with n
/// (the horizon-clipped sphere-light illuminance of Snyder 1996, in the form of Lagarde &
/// de Rousiers, "Moving Frostbite to PBR", 2014), divided by the cap's solid angle
/// 2π(1 − cos σ): the mean clamped cosine over the cap. For a small cap
/// (sin²σ < [`SMALL_CAP_SIN2`]) n·l is linear across it, x₀ + g·w·σ with x₀ = cos θ,
/// g = sin θ and w distributed as a disk's chord, (2/π)√(1 − w²) on [−1, 1]; with
/// t = x₀/(gσ) the mean of its positive part is gσ (t A(t) + B(t)), A(t) =
/// (π/2 + t√(1 − t²) + asin t)/π, B(t) = 2(1 − t²)^{3/2}/(3π).
pub fn clipped_cap_cosine(cos_theta: f32, sin2_sigma: f32) -> f32 {
    if sin2_sigma < 1e-12 {
        return cos_theta.max(0.0);
    }
    if sin2_sigma < SMALL_CAP_SIN2 {
        let sigma = sin2_sigma.sqrt(); // sin σ ≈ σ to O(σ³)
        let g = (1.0 - cos_theta * cos_theta).max(0.0).sqrt();
        let reach = g * sigma;
        if cos_theta >= reach {
            return cos_theta;
        }
        if cos_theta <= -reach {
            return 0.0;
        }
        let t = cos_theta / reach;
        let r = (1.0 - t * t).max(0.0).sqrt();
        let asin_t = atan_precise(t / r.max(1e-9));
        let a = (0.5 * PI + t * r + asin_t) / PI;
        let b = 2.0 * r * r * r / (3.0 * PI);
        return reach * (t * a + b);
    }
    let cap = 2.0 * PI * (1.0 - (1.0 - sin2_sigma).max(0.0).sqrt());
    let e = if cos_theta * cos_theta > sin2_sigma {
        PI * sin2_sigma * cos_theta.max(0.0)
    } else {
        let sin_theta = (1.0 - cos_theta * cos_theta).max(0.0).sqrt();
        let x = (1.0 / sin2_sigma - 1.0).max(0.0).sqrt();
        let y = (-x * cos_theta / sin_theta.max(1e-9)).clamp(-1.0, 1.0);
        let st_y = sin_theta * (1.0 - y * y).max(0.0).sqrt();
        (cos_theta * acos_precise(y) - x * st_y) * sin2_sigma + atan_precise(st_y / x.max(1e-9))
    };
    e.max(0.0) / cap
}

#[cfg(any(test, feature = "internals"))]
/// E(n)/π for unit `n` over every cold source texel and then every hot cell (see
/// [`crate::environment::hot`]): (1/π) Σ n · moment for texels above the horizon, the
/// clipped-cap estimate for texels straddling it. The mirror of the irradiance mode of
/// `convolve_exact.wgsl`; [`irradiance`](crate::backend::cpu::irradiance::irradiance) computes the same sum
/// faster with [`MomentRuns`](crate::backend::cpu::irradiance::MomentRuns).
pub fn irradiance_texel(source: &[MomentTexel], hot: &[MomentTexel], n: [f32; 3]) -> [f32; 4] {
    let mut e = [0.0f32; 3];
    for t in source.iter().chain(hot) {
        add_moment_texel(&mut e, t, n);
    }
    [e[0] / PI, e[1] / PI, e[2] / PI, 1.0]
}

/// Adds one texel's share of E(n) to `e` (see [`irradiance_texel`]).
pub fn add_moment_texel(e: &mut [f32; 3], t: &MomentTexel, n: [f32; 3]) {
    let d = t.dir_sin2;
    let cos_theta = n[0] * d[0] + n[1] * d[1] + n[2] * d[2];
    if cos_theta * cos_theta > d[3] {
        if cos_theta > 0.0 {
            for (c, m) in t.moments.iter().enumerate() {
                e[c] += (n[0] * m[0] + n[1] * m[1] + n[2] * m[2]).max(0.0);
            }
        }
    } else {
        let k = clipped_cap_cosine(cos_theta, d[3]);
        for (ec, lc) in e.iter_mut().zip(&t.radiance_omega) {
            *ec += k * lc;
        }
    }
}
