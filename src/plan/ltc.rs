//! The LTC table of a light BRDF, and area lights shaded from it.
//!
//! Per cell (r, √(1 − n·v)) of a [`LtcTable`], the linearly transformed cosine
//! ([`crate::math::ltc`]) that best matches the BRDF's cosine-weighted specular lobe
//! f(l, v) (n·l) with F = 1, and the lobe's magnitude: ∫ f (n·l) dl with F = 1 (A + B of
//! the split-sum) and its Fresnel part ∫ f (n·l) (1 − v·h)⁵ dl (B), so F0 A + B scales it
//! (Heitz, Dupuy, Hill, Neubelt 2016, their `fitLTC.cpp`, step for step):
//!
//! - the view v = (sin θ, 0, cos θ), cos θ = 1 − x² for the row's x, at least
//!   [`MIN_FIT_N_DOT_V`] (θ at most 1.57);
//!   α = max(r², [`MIN_ALPHA`]);
//! - the magnitude, Fresnel part and the lobe's mean direction from
//!   [`FIT_SAMPLES`]² GGX samples;
//! - M = [X Y Z] · [[m11, 0, m13], [0, m22, 0], [0, 0, 1]], the frame X, Y, Z the
//!   lobe's (Z its mean direction, Y the normal of the plane of incidence); at normal
//!   incidence the lobe is isotropic (m22 = m11, m13 = 0);
//! - (m11, m22, m13) by Nelder-Mead from the previous cell's (the rougher cell at normal
//!   incidence, the previous θ otherwise), minimising the cube of |f (n·l) − A D(l)| by
//!   multiple importance sampling of both (each [`FIT_SAMPLES`]² points, weights
//!   1 / (pdf_LTC + pdf_BRDF)).
//!
//! The fit is a kernel with two twins: `cpu::ltc_fit` (`LtcTable::fit`) and `gpu::ltc_fit`
//! (shaders/ltc_fit.wgsl); this module holds what both read and write.
//!
//! A cell stores M⁻¹ divided by its (1, 1) entry as (x, y, z, w) = (M⁻¹₀₀, M⁻¹₂₀, M⁻¹₀₂,
//! M⁻¹₂₂) (row, column): three.js's `LTC_1` layout, whose `mat3(vec3(x, 0, y), vec3(0, 1,
//! 0), vec3(z, 0, w))` is M⁻¹ by columns; and (A + B, B), its `LTC_2`'s x and y.
//!
//! [`shade_polygon`] shades a polygonal light of uniform radiance L at infinity. Its
//! specular uses the LTC as a control variate: the LTC over the polygon,
//! L (F0 A + B) ∫_P D, corrected by β times the difference between the BRDF itself and
//! the LTC at the polygon's centre c, L Ω_P (f(c, v) (n·c) − (F0 A + B) D(c)). The LTC's
//! fit error is largest at grazing views (tens of per cent on the lobe's peak), but it
//! cancels where the light is small against the lobe, which the exact point term then
//! carries. β = Ω_lobe / (Ω_lobe + Ω_P), Ω_lobe = 4π α² the reflected lobe's solid angle
//! (its half-vector lobe α wide, doubled by the reflection): 1 for a light far narrower
//! than the lobe, 0 for a mirror, whose image of the light the LTC alone draws.
//! The diffuse is Lambert's exact L ∫_P (n·l)/π (the LTC with M = I), weighted as the
//! BRDF's diffuse at c.
//!
//! [`LtcPoint::shade_quad`] is the same shading in real-time form, what the viewer draws
//! (shaders/common/ltc.wgsl is its twin): the light is the quadrilateral an engine's rect
//! light draws ([`QuadLight`]); its edges' integrals come from a rational fit of θ / sin θ
//! and the horizon clips the polygon's vector form factor as a sphere
//! ([`crate::math::ltc::horizon_form_factor`]) instead of edge by edge; the light's
//! centre, solid angle and world-space vector form factor (the diffuse's) are computed
//! once a frame.

use crate::{Error, Result};

use glam::{Mat3, Vec3};

use crate::math::ltc::{
    edge_vector_form_factor, horizon_form_factor, inverse_density, polygon_form_factor, polygon_solid_angle,
    polygon_vector_form_factor, Ltc,
};
use crate::plan::material::{diffuse_weight, directional_light, ShadeMaterial};
use crate::plan::lut::LutModel;
use crate::plan::shading::{DiffuseLobe, LightBrdf, Masking};

/// The light BRDF an LTC table for the split-sum LUT `model` is fitted to: the GGX lobe
/// with its masking (Schlick-GGX for `schlick-ggx` and its multiscatter model, the
/// height-correlated Smith for `smith-correlated`, its multiscatter model and Filament's
/// DFG). The sheen models have no GGX lobe, and a table has 2 to [`MAX_LTC_SIZE`] cells a
/// side: an [`Error::InvalidOption`] otherwise.
pub fn ltc_brdf(model: LutModel, size: u32) -> Result<LightBrdf> {
    let masking = match model {
        LutModel::SchlickGgx | LutModel::MultiscatterSchlickGgx => Masking::SchlickGgx,
        LutModel::SmithCorrelated | LutModel::MultiscatterSmithCorrelated | LutModel::FilamentDfg => {
            Masking::SmithCorrelated
        }
        LutModel::Charlie | LutModel::SheenAlbedo => {
            return Err(Error::InvalidOption {
                option: "model",
                message: format!("{} is a sheen lobe; an LTC table is fitted to a GGX lobe (schlick-ggx or smith-correlated)", model.name()),
            })
        }
    };
    if !(2..=MAX_LTC_SIZE).contains(&size) {
        return Err(Error::InvalidOption {
            option: "size",
            message: format!("{size} cells a side; an LTC table has 2 to {MAX_LTC_SIZE}"),
        });
    }
    Ok(LightBrdf {
        masking,
        diffuse: DiffuseLobe::FresnelWeighted,
        compensated: false,
    })
}

/// The largest table `fit_ltc` fits: 256² cells cost about 16 × a 64² fit
/// (docs/accuracy.md, "The LTC fit on either backend").
pub const MAX_LTC_SIZE: u32 = 256;

/// The smallest α fitted: a mirror has no lobe to fit. Heitz's 1e-5 underflows GGX D in
/// f32 ((n·h)² (α² − 1) + 1 rounds to 0 within f32's 6e-8 of n·h = 1); at 1e-3 the lobe is
/// 0.1° wide, a mirror to any light a texel wide.
pub const MIN_ALPHA: f32 = 1e-3;
/// Points per axis of each of the fit's quadratures (Heitz's 32).
pub const FIT_SAMPLES: u32 = 32;
/// The Nelder-Mead simplex's first step (Heitz's).
pub const SIMPLEX_STEP: f32 = 0.05;
/// The Nelder-Mead's stopping tolerance (Heitz's).
pub const SIMPLEX_TOLERANCE: f32 = 1e-5;
/// At most this many Nelder-Mead iterations a cell (Heitz's 100).
pub const SIMPLEX_ITERATIONS: u32 = 100;
/// The smallest scale of the cosine a fit may reach (Heitz's floor of m11 and m22).
pub const MIN_SCALE: f32 = 1e-7;
/// The smallest n·v fitted: cos 1.57, Heitz's largest θ. The last row's n·v is taken as
/// this constant rather than as the cosine of the clamped angle, which a GPU's cos
/// (absolute error up to 2⁻¹¹ in WGSL) may put below the horizon.
pub const MIN_FIT_N_DOT_V: f32 = 7.963_267e-4;

/// One cell of the table.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LtcCell {
    /// M⁻¹ / M⁻¹₁₁ as (M⁻¹₀₀, M⁻¹₂₀, M⁻¹₀₂, M⁻¹₂₂) (row, column; three.js's `LTC_1`).
    pub inverse: [f32; 4],
    /// ∫ f (n·l) dl with F = 1 (the split-sum's A + B).
    pub norm: f32,
    /// ∫ f (n·l) (1 − v·h)⁵ dl (the split-sum's B).
    pub fresnel: f32,
}

impl LtcCell {
    /// The cell's M⁻¹.
    pub fn inverse_matrix(&self) -> Mat3 {
        let [x, y, z, w] = self.inverse;
        Mat3::from_cols(Vec3::new(x, 0.0, y), Vec3::Y, Vec3::new(z, 0.0, w))
    }
}

/// The LTC table of a BRDF: `size`² cells, roughness r = i / (size − 1) along a row, the
/// row's x = j / (size − 1) = √(1 − n·v).
#[derive(Clone, Debug, PartialEq)]
pub struct LtcTable {
    /// Cells per side.
    pub size: u32,
    /// The BRDF fitted.
    pub brdf: LightBrdf,
    /// Row-major: cell (i, j) at j · size + i.
    pub cells: Vec<LtcCell>,
}

impl LtcTable {
    /// The cell bilinearly interpolated at (n·v, r), clamped to the table (three.js reads
    /// its `LTC_1`/`LTC_2` so, at uv = (r, √(1 − n·v)) with half-texel margins).
    pub fn lookup(&self, n_dot_v: f32, roughness: f32) -> LtcCell {
        let last = (self.size - 1) as f32;
        let u = roughness.clamp(0.0, 1.0) * last;
        let w = (1.0 - n_dot_v.clamp(0.0, 1.0)).sqrt() * last;
        let (i0, j0) = (u.floor().min(last - 1.0), w.floor().min(last - 1.0));
        let (fu, fw) = (u - i0, w - j0);
        let at = |i: f32, j: f32| self.cells[(j as u32 * self.size + i as u32) as usize];
        let mix = |a: LtcCell, b: LtcCell, t: f32| LtcCell {
            inverse: std::array::from_fn(|k| a.inverse[k] + t * (b.inverse[k] - a.inverse[k])),
            norm: a.norm + t * (b.norm - a.norm),
            fresnel: a.fresnel + t * (b.fresnel - a.fresnel),
        };
        mix(
            mix(at(i0, j0), at(i0 + 1.0, j0), fu),
            mix(at(i0, j0 + 1.0), at(i0 + 1.0, j0 + 1.0), fu),
            fw,
        )
    }
}

/// An area light as the viewer shades it: the quadrilateral of unit corners an engine's
/// rect light draws, wound counter-clockwise seen from the origin, with what
/// [`LtcPoint::shade_quad`] reads of it that does not depend on the shaded point.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct QuadLight {
    /// The corners, counter-clockwise seen from the origin (its vector form factor points
    /// toward it).
    pub corners: [Vec3; 4],
    /// The unit direction of the corners' sum, where the control variate is taken.
    pub centre: Vec3,
    /// Its solid angle, steradians.
    pub solid_angle: f32,
    /// Its vector form factor in the frame of the corners (the diffuse's, about any normal).
    pub vector_form_factor: Vec3,
}

impl QuadLight {
    /// The light of corners `corners` (in order around it, either winding).
    pub fn new(corners: [Vec3; 4]) -> QuadLight {
        let centre = corners.iter().copied().sum::<Vec3>().normalize();
        let mut corners = corners;
        if polygon_vector_form_factor(&corners).dot(centre) < 0.0 {
            corners.reverse();
        }
        QuadLight {
            corners,
            centre,
            solid_angle: polygon_solid_angle(&corners),
            vector_form_factor: polygon_vector_form_factor(&corners),
        }
    }
}

/// What a shaded point's area lights share in [`LtcPoint::shade_quad`] (`LtcPoint` in
/// shaders/common/ltc.wgsl): its LTC's inverse matrix, the world-to-shading frame, world to the LTC's
/// cosine space, whether the LTC reflects (−1) or not (1), its α and the lobe's scale
/// F0 (A + B − B) + B.
#[derive(Clone, Copy, Debug)]
pub struct LtcPoint {
    inverse: Mat3,
    to_local: Mat3,
    to_cosine: Mat3,
    orientation: f32,
    alpha: f32,
    scale: Vec3,
    brdf: LightBrdf,
}

impl LtcPoint {
    /// The point of normal `n` seen from `v` (n·v = `n_dot_v`, clamped away from 0 by
    /// the caller) of material `m`, its cell looked up in `table`.
    pub fn new(table: &LtcTable, n: Vec3, v: Vec3, n_dot_v: f32, m: &ShadeMaterial) -> LtcPoint {
        let t1 = (v - n * n.dot(v))
            .try_normalize()
            .unwrap_or_else(|| Vec3::from(crate::math::sampling::tangent_frame(n.into()).0));
        let t2 = n.cross(t1);
        let cell = table.lookup(n_dot_v, m.roughness);
        let to_local = Mat3::from_cols(t1, t2, n).transpose();
        let inverse = cell.inverse_matrix();
        LtcPoint {
            inverse,
            to_local,
            to_cosine: inverse * to_local,
            orientation: inverse.determinant().signum(),
            alpha: crate::math::brdf::alpha_from_roughness(m.roughness),
            scale: m.f0 * (cell.norm - cell.fresnel) + Vec3::splat(cell.fresnel),
            brdf: table.brdf,
        }
    }

    /// [`shade_polygon`] in real-time form (the module's doc): what the quadrilateral
    /// light `light` of uniform radiance `radiance` sends towards `v` off this point (normal
    /// `n`, material `m`), as (specular, diffuse per unit albedo). Mirror of
    /// `ltc_shade_quad` in shaders/common/ltc.wgsl, in the same f32 steps.
    pub fn shade_quad(
        &self,
        n: Vec3,
        v: Vec3,
        n_dot_v: f32,
        m: &ShadeMaterial,
        light: &QuadLight,
        radiance: Vec3,
    ) -> (Vec3, Vec3) {
        // The corners in the LTC's cosine space; a reflection reverses the winding.
        let p = light.corners.map(|c| (self.to_cosine * c).normalize());
        let f: Vec3 = (0..4)
            .map(|i| edge_vector_form_factor(p[(i + 3) % 4], p[i]))
            .sum::<Vec3>();
        let above = p.iter().all(|c| c.z >= 0.0);
        let omega = light.solid_angle;
        let polygon_lobe = radiance * self.scale * horizon_form_factor(f * self.orientation, above);
        let (point, _) = directional_light(n, v, n_dot_v, self.alpha, m.f0, 1.0, light.centre, radiance * omega, self.brdf);
        let density = inverse_density(self.inverse, self.to_local * light.centre);
        let point_ltc = radiance * self.scale * (omega * density);
        let lobe = 4.0 * std::f32::consts::PI * self.alpha * self.alpha;
        let beta = lobe / (lobe + omega);
        let spec = (polygon_lobe + beta * (point - point_ltc)).max(Vec3::ZERO);
        let mut diff = Vec3::ZERO;
        if m.metallic < 1.0 {
            let h = (light.centre + v).normalize();
            let weight = diffuse_weight(
                self.brdf,
                m.f0,
                n.dot(light.centre).max(0.0),
                n_dot_v,
                v.dot(h).max(0.0),
                self.alpha,
            );
            let above = light.corners.iter().all(|c| c.dot(n) >= 0.0);
            let form_factor = horizon_form_factor(self.to_local * light.vector_form_factor, above);
            diff = radiance * weight * ((1.0 - m.metallic) * form_factor);
        }
        (spec, diff)
    }
}

/// What a polygonal light of uniform radiance `radiance` at infinity (unit vertices
/// `polygon`) sends towards `v` off a point with normal `n` and material `m` (its
/// roughness read by `table`), as (specular, diffuse per unit albedo); `n_dot_v` is n·v
/// clamped away from 0 by the caller.
pub fn shade_polygon(
    table: &LtcTable,
    n: Vec3,
    v: Vec3,
    n_dot_v: f32,
    m: &ShadeMaterial,
    polygon: &[Vec3],
    radiance: Vec3,
) -> (Vec3, Vec3) {
    // The shading frame: T1 in the plane of incidence, the table's X.
    let t1 = (v - n * n.dot(v))
        .try_normalize()
        .unwrap_or_else(|| Vec3::from(crate::math::sampling::tangent_frame(n.into()).0));
    let t2 = n.cross(t1);
    let local: Vec<Vec3> = polygon
        .iter()
        .map(|&p| Vec3::new(p.dot(t1), p.dot(t2), p.dot(n)))
        .collect();
    let cell = table.lookup(n_dot_v, m.roughness);
    let ltc = Ltc::from_inverse(cell.inverse_matrix());
    let centre = polygon.iter().copied().sum::<Vec3>().normalize();
    let local_centre = Vec3::new(centre.dot(t1), centre.dot(t2), centre.dot(n));
    let omega = polygon_solid_angle(polygon);
    let alpha = crate::math::brdf::alpha_from_roughness(m.roughness);
    let scale = m.f0 * (cell.norm - cell.fresnel) + Vec3::splat(cell.fresnel);
    let polygon_lobe = radiance * scale * ltc.integrate_polygon(&local);
    // The exact BRDF at the centre (diffuse left out: Lambert's is exact below) less the
    // LTC there, weighted by how small the light is against the lobe.
    let (point, _) = directional_light(n, v, n_dot_v, alpha, m.f0, 1.0, centre, radiance * omega, table.brdf);
    let point_ltc = radiance * scale * (omega * ltc.density(local_centre));
    let lobe = 4.0 * std::f32::consts::PI * alpha * alpha;
    let beta = lobe / (lobe + omega);
    let spec = (polygon_lobe + beta * (point - point_ltc)).max(Vec3::ZERO);
    let mut diff = Vec3::ZERO;
    if m.metallic < 1.0 {
        let h = (centre + v).normalize();
        let weight = diffuse_weight(
            table.brdf,
            m.f0,
            n.dot(centre).max(0.0),
            n_dot_v,
            v.dot(h).max(0.0),
            alpha,
        );
        diff = radiance * weight * ((1.0 - m.metallic) * polygon_form_factor(&local));
    }
    (spec, diff)
}
