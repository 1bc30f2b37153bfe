//! The ground truth of a surface point ([`truth_shade`], also the viewer's) and the
//! preview's truth render: per sphere pixel, the full reflectance integral
//! L_o(v) = ∫ f(l, v) L(l) (n·l) dl of the preview BRDF over the environment, with the real
//! view direction (no v = n assumption, no separable product). CPU mirror of
//! `shaders/common/truth.wgsl` and `shaders/preview_truth.wgsl` (same function names).
//!
//! The BRDF: f = kD(h) c/π + D(h) G(l, v) F(v·h) / (4 (n·l)(n·v)), GGX D with α = r²,
//! G = G1(n·l) G1(n·v) Schlick-GGX with k = r²/2, F Fresnel-Schlick, and
//! kD(h) = (1 − F(v·h))(1 − metallic) (docs/conventions.md, "Roughness, BRDF"); in an
//! engine's mode ([`crate::plan::shading`]) that engine's: G the height-correlated Smith,
//! kD = 1 − metallic where its Lambert is not Fresnel-weighted, and the specular scaled by
//! its multiple-scattering compensation 1 + F0 (1/Ess − 1) (Ess from its LUT) where it has
//! one.
//!
//! The environment is the bake's own cube (level 0), split as the specular bake splits it
//! (`plan::sources::split_hot_texels`): its hot texels (a sun, lamps: at most 512,
//! each with its radiance centroid and solid angle) are summed exactly,
//! Σ L Ω f (n·l); the cold rest, whose dynamic range is low, is integrated by
//! quasi-Monte Carlo with one estimator per lobe:
//! - specular: N GGX visible normals h (Heitz 2018), l = reflect(−v, h), each weighted
//!   f (n·l) / pdf(l) = F(v·h) G(l, v) / G1_Smith(n·v) (bounded, so the estimate
//!   converges quickly even at grazing n·v);
//! - diffuse: N cosine-distributed l, each weighted kD(h) c.
//!
//! Both draw the same N Hammersley points mapped to the unit disk (a table built once,
//! [`disk_points`](crate::plan::scene::disk_points)), rotated per pixel in azimuth and shifted in radius by a hash of the
//! pixel index (Cranley-Patterson), so neighbouring pixels' quadrature errors are
//! uncorrelated. Cold lookups are seamless bilinear reads of level 0 (no prefiltering, so
//! no bias). At r = 0 the specular lobe is a mirror: F(n·v) L(reflect(−v, n)) from the
//! whole cube, as the split-sum reads it.

use glam::Vec3;
use rayon::prelude::*;

use crate::environment::sample::sample_cube_lod;
use crate::environment::texels::SourceTexel;
use crate::cpu::preview_split_sum::{sample_lut, specular_compensation};
use crate::math::brdf::{
    alpha_from_roughness, g1_schlick_ggx, g1_smith_ggx, smith_correlated_lambda,
};
use crate::math::sampling::{
    cosine_hemisphere_from_disk, pcg_hash, sample_ggx_vndf, tangent_frame, unit_float,
};
use crate::plan::material::{directional_light, diffuse_weight, fresnel3, ShadeMaterial};
use crate::plan::shading::{LightBrdf, Masking};
use crate::plan::scene::{
    pixel_geometry, preview_material, PixelGeometry, SceneUniform, TruthInputs, TruthLight,
    MIN_N_DOT_V,
};

/// An estimate's quadrature shift: (radial shift s ∈ [0, 1), cos ψ, sin ψ) of its azimuthal
/// rotation ψ, from hashes of `seed` (the preview's pixel index; the angle need not be
/// uniform: any rotation of the point set is an equally good rule).
pub fn pixel_shift(seed: u32) -> [f32; 3] {
    let h1 = pcg_hash(seed);
    let h2 = pcg_hash(h1);
    let h3 = pcg_hash(h2);
    let (x, y) = (2.0 * unit_float(h2) - 1.0, 2.0 * unit_float(h3) - 1.0);
    let len = (x * x + y * y).sqrt();
    if len < 1e-3 {
        return [unit_float(h1), 1.0, 0.0];
    }
    [unit_float(h1), x / len, y / len]
}

/// Point `p` of the table for a pixel with shift `shift`, on the unit disk.
pub fn shifted_disk_point(p: [f32; 4], shift: [f32; 3]) -> [f32; 2] {
    let u = p[0] + shift[0];
    let r = (u - u.floor()).sqrt();
    let (c, s) = (
        p[1] * shift[1] - p[2] * shift[2],
        p[1] * shift[2] + p[2] * shift[1],
    );
    [r * c, r * s]
}

/// The exact part: Σ L Ω f (n·l) over the hot texels with `brdf`, split into (specular,
/// diffuse / c). At r = 0 (`alpha` 0) the specular part is left to the mirror lookup.
#[allow(clippy::too_many_arguments)]
pub fn hot_texels_shade(
    hot: &[SourceTexel],
    n: Vec3,
    v: Vec3,
    n_dot_v: f32,
    alpha: f32,
    f0: Vec3,
    metallic: f32,
    brdf: LightBrdf,
) -> (Vec3, Vec3) {
    hot.iter().fold((Vec3::ZERO, Vec3::ZERO), |(spec, diff), t| {
        let l = Vec3::from_slice(&t.dir_omega[..3]);
        let e = Vec3::from_slice(&t.radiance[..3]) * t.dir_omega[3];
        let (s, d) = directional_light(n, v, n_dot_v, alpha, f0, metallic, l, e, brdf);
        (spec + s, diff + d)
    })
}

/// The specular weight of a visible normal's direction besides F, G(l, v) / G1_Smith(v),
/// for n·l > 0 (the VNDF's pdf holds D and the exact Smith G1(v); Heitz 2018):
/// Schlick-GGX G1(n·l) G1(n·v) / G1_Smith(n·v) with k = α/2, or the height-correlated
/// G2 / G1(v) = n·l (n·v + Λ'(v)) / (n·l Λ'(v) + n·v Λ'(l)).
pub fn vndf_masking_weight(brdf: LightBrdf, n_dot_l: f32, n_dot_v: f32, alpha: f32) -> f32 {
    let a2 = alpha * alpha;
    match brdf.masking {
        Masking::SmithCorrelated => {
            let lv = smith_correlated_lambda(n_dot_v, a2);
            n_dot_l * (n_dot_v + lv)
                / (n_dot_l * lv + n_dot_v * smith_correlated_lambda(n_dot_l, a2))
        }
        Masking::SchlickGgx => {
            let k = 0.5 * alpha;
            g1_schlick_ggx(n_dot_l, k) * g1_schlick_ggx(n_dot_v, k) / g1_smith_ggx(n_dot_v, a2)
        }
    }
}

/// One estimate of the light towards `v` of a point with normal `n`, its quadrature
/// rotated by `shift` ([`pixel_shift`]), as (specular, diffuse times the albedo) with the
/// light's BRDF; `n_dot_v` is n·v clamped away from 0 by the caller.
pub fn truth_shade_parts(
    light: &TruthLight,
    n: Vec3,
    v: Vec3,
    n_dot_v: f32,
    m: &ShadeMaterial,
    shift: [f32; 3],
) -> (Vec3, Vec3) {
    let (r, f0, metallic, albedo) = (m.roughness, m.f0, m.metallic, m.albedo);
    let brdf = light.brdf;
    let alpha = alpha_from_roughness(r);
    let (t0, b0) = tangent_frame(n.into());
    let (t0, b0) = (Vec3::from(t0), Vec3::from(b0));
    let vt = Vec3::new(v.dot(t0), v.dot(b0), n_dot_v);
    let count = light.points.len() as f32;

    let (mut spec, mut diff) =
        hot_texels_shade(light.hot, n, v, n_dot_v, alpha, f0, metallic, brdf);
    if alpha > 0.0 {
        let mut sum = Vec3::ZERO;
        for &p in light.points {
            let h = Vec3::from(sample_ggx_vndf(
                vt.into(),
                alpha,
                shifted_disk_point(p, shift),
            ));
            let v_dot_h = vt.dot(h);
            let lt = 2.0 * v_dot_h * h - vt;
            if lt.z > 0.0 {
                let l = lt.x * t0 + lt.y * b0 + lt.z * n;
                let radiance = Vec3::from(sample_cube_lod(light.cold, l.into(), 0.0));
                sum += radiance
                    * fresnel3(f0, v_dot_h.max(0.0))
                    * vndf_masking_weight(brdf, lt.z, n_dot_v, alpha);
            }
        }
        spec += sum / count;
    } else {
        let refl = 2.0 * n.dot(v) * n - v;
        spec = Vec3::from(sample_cube_lod(light.env, refl.into(), 0.0)) * fresnel3(f0, n_dot_v);
    }
    if metallic < 1.0 {
        let mut sum = Vec3::ZERO;
        for &p in light.points {
            let lt = Vec3::from(cosine_hemisphere_from_disk(shifted_disk_point(p, shift)));
            let l = lt.x * t0 + lt.y * b0 + lt.z * n;
            let radiance = Vec3::from(sample_cube_lod(light.cold, l.into(), 0.0));
            let h = (vt + lt).normalize();
            sum += radiance * diffuse_weight(brdf, f0, lt.z, n_dot_v, vt.dot(h).max(0.0), alpha);
        }
        diff += sum * ((1.0 - metallic) / count);
    }
    (spec, diff * albedo)
}

/// One estimate of the radiance towards `v` of a point with normal `n`
/// ([`truth_shade_parts`], the two parts summed).
pub fn truth_shade(
    light: &TruthLight,
    n: Vec3,
    v: Vec3,
    n_dot_v: f32,
    m: &ShadeMaterial,
    shift: [f32; 3],
) -> Vec3 {
    let (spec, diff) = truth_shade_parts(light, n, v, n_dot_v, m, shift);
    spec + diff
}

/// The truth panel, row-major linear RGB.
pub fn render_truth(scene: &SceneUniform, inputs: &TruthInputs) -> Vec<[f32; 3]> {
    (0..scene.height)
        .into_par_iter()
        .flat_map_iter(|y| {
            (0..scene.width).map(move |x| match pixel_geometry(scene, x, y) {
                PixelGeometry::Background { dir } => sample_cube_lod(inputs.light.env, dir.into(), 0.0),
                PixelGeometry::Sphere {
                    n,
                    v,
                    material,
                    column,
                } => {
                    let m = preview_material(inputs.spheres, inputs.materials, scene.columns as usize, material, column);
                    let shift = pixel_shift(y * scene.width + x);
                    let n_dot_v = n.dot(v).max(MIN_N_DOT_V);
                    let (mut spec, diff) = truth_shade_parts(&inputs.light, n, v, n_dot_v, &m, shift);
                    if inputs.light.brdf.compensated {
                        spec *= specular_compensation(
                            sample_lut(inputs.lut, n_dot_v, m.roughness),
                            m.f0,
                        );
                    }
                    (spec + diff).into()
                }
            })
        })
        .collect()
}
