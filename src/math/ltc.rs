//! Linearly transformed cosines (Heitz, Dupuy, Hill, Neubelt, "Real-Time Polygonal-Light
//! Shading with Linearly Transformed Cosines", SIGGRAPH 2016): a distribution D over
//! directions made by transforming the clamped cosine D_o(ω_o) = max(0, z)/π with a 3 × 3
//! matrix M, D(ω) = D_o(ω_o) |det M⁻¹| / |M⁻¹ ω|³ with ω_o = M⁻¹ω / |M⁻¹ω| (eq. 2), whose
//! integral over a spherical polygon is the clamped cosine's over the polygon transformed
//! by M⁻¹: the closed form of Lambert (1760) for a polygon's irradiance form factor
//! ([`polygon_form_factor`]). The fit of a table ([`crate::plan::ltc`]) and the preview's
//! shading of area lights read it; the viewer shades with the real-time form
//! ([`polygon_vector_form_factor`], [`horizon_form_factor`]), whose WGSL twin is
//! shaders/common/ltc.wgsl.

use glam::{DMat3, DVec3, Mat3, Vec3};

/// An LTC: M = [X Y Z] · [[m11, 0, m13], [0, m22, 0], [0, 0, 1]] (the parameters Heitz's
/// `fitLTC` fits: a scale of the cosine along X and Y, a skew of Z toward X, in the frame
/// X, Y, Z), with its inverse and |det M|.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Ltc {
    /// The matrix M (columns).
    pub m: Mat3,
    /// M⁻¹.
    pub inverse: Mat3,
    /// |det M|.
    pub det: f32,
}

impl Ltc {
    /// The LTC of parameters (m11, m22, m13) in the orthonormal frame (x, y, z).
    pub fn new(m11: f32, m22: f32, m13: f32, frame: [Vec3; 3]) -> Ltc {
        let shape = Mat3::from_cols(
            Vec3::new(m11, 0.0, 0.0),
            Vec3::new(0.0, m22, 0.0),
            Vec3::new(m13, 0.0, 1.0),
        );
        let m = Mat3::from_cols(frame[0], frame[1], frame[2]) * shape;
        Ltc {
            m,
            inverse: m.inverse(),
            det: m.determinant().abs(),
        }
    }

    /// The LTC of a stored inverse matrix (any non-zero scale of M⁻¹ gives the same
    /// distribution: a table stores it divided by its (1, 1) entry).
    pub fn from_inverse(inverse: Mat3) -> Ltc {
        let m = inverse.inverse();
        Ltc {
            m,
            inverse,
            det: m.determinant().abs(),
        }
    }

    /// The density D(ω) of unit direction `l` (it integrates to 1 over the sphere).
    pub fn density(&self, l: Vec3) -> f32 {
        let original = (self.inverse * l).normalize();
        let transformed = (self.m * original).length();
        // D_o(ω_o) / Jacobian, the Jacobian ∂ω/∂ω_o = |det M| / |M ω_o|³ (eq. 2).
        original.z.max(0.0) / std::f32::consts::PI * transformed.powi(3) / self.det
    }

    /// The direction of cosine-distributed point (u1, u2) ∈ [0, 1)² transformed by M: a
    /// sample of D.
    pub fn sample(&self, u1: f32, u2: f32) -> Vec3 {
        let (s, c) = (u1.sqrt(), (1.0 - u1).max(0.0).sqrt());
        let phi = 2.0 * std::f32::consts::PI * u2;
        (self.m * Vec3::new(s * phi.cos(), s * phi.sin(), c)).normalize()
    }

    /// ∫ D over the spherical polygon of unit vertices `polygon` (in either winding): the
    /// clamped cosine's integral over the polygon transformed by M⁻¹ (the LTC's defining
    /// property, Heitz et al. 2016, section 3.2).
    pub fn integrate_polygon(&self, polygon: &[Vec3]) -> f32 {
        let inverse = DMat3::from_cols(
            self.inverse.x_axis.as_dvec3(),
            self.inverse.y_axis.as_dvec3(),
            self.inverse.z_axis.as_dvec3(),
        );
        let transformed: Vec<DVec3> = polygon
            .iter()
            .map(|&p| (inverse * p.as_dvec3()).normalize())
            .collect();
        form_factor(&transformed) as f32
    }
}

/// The irradiance form factor of a spherical polygon (unit vertices, either winding): the
/// integral of max(0, z)/π over its part above the horizon z = 0. The polygon is clipped
/// to the horizon (its edges are great-circle arcs; an arc crosses z = 0 where its chord
/// does), then Lambert's closed form, |Σ θ_i (p_i × p_{i+1}).z / |p_i × p_{i+1}|| / 2π,
/// θ_i the arc's angle (atan2, exact for the arcs of a light a texel wide). In f64: for a
/// light a fraction of a degree wide the terms cancel to a thousandth of their size.
pub fn polygon_form_factor(polygon: &[Vec3]) -> f32 {
    let polygon: Vec<DVec3> = polygon.iter().map(|p| p.as_dvec3()).collect();
    form_factor(&polygon) as f32
}

/// [`polygon_form_factor`] of f64 vertices.
fn form_factor(polygon: &[DVec3]) -> f64 {
    let clipped = clip_to_horizon(polygon);
    if clipped.len() < 3 {
        return 0.0;
    }
    let mut sum = 0.0f64;
    for (i, &a) in clipped.iter().enumerate() {
        let b = clipped[(i + 1) % clipped.len()];
        let c = a.cross(b);
        let s = c.length();
        if s > 0.0 {
            sum += s.atan2(a.dot(b)) * c.z / s;
        }
    }
    sum.abs() / (2.0 * std::f64::consts::PI)
}

/// The density D(ω) of unit direction `l` of the LTC of inverse matrix `inverse` (any
/// non-zero scale of M⁻¹): D_o(M⁻¹l / |M⁻¹l|) |det M⁻¹| / |M⁻¹l|³, [`Ltc::density`]
/// without inverting M⁻¹ (the viewer's form, per shaded point).
pub fn inverse_density(inverse: Mat3, l: Vec3) -> f32 {
    let o = inverse * l;
    let len = o.length();
    (o.z / len).max(0.0) / std::f32::consts::PI * inverse.determinant().abs() / (len * len * len)
}

/// Coefficients of the rational fit θ / (2π sin θ) ≈ (c₀ + (c₁ + c₂ y) y) / (c₃ + (c₄ + y) y),
/// y = |cos θ|, of Hill and Heitz ("Real-Time Area Lighting: a Journey from Research to
/// Production", SIGGRAPH 2016 course, the `IntegrateEdge` fit that three.js's
/// `LTC_EdgeVectorFormFactor` uses): within 0.1 % of the arc's θ / sin θ for cos θ > 0 and
/// no inverse trigonometry (`tests::the_edge_fit_follows_the_arc`).
pub const EDGE_FIT: [f32; 5] = [0.854_398_5, 0.496_515_5, 0.014_520_6, 3.417_594, 4.161_672_4];

/// The vector form factor of the great-circle arc from unit `a` to unit `b`:
/// (a × b) θ / (2π sin θ), θ the arc's angle, by [`EDGE_FIT`] (for cos θ < 0 through
/// θ = π − θ′: π / sin θ less the fit). The sum over a polygon's edges is its vector form
/// factor, whose z is the polygon's form factor about the normal z where the whole
/// polygon is above the horizon.
pub fn edge_vector_form_factor(a: Vec3, b: Vec3) -> Vec3 {
    let [c0, c1, c2, c3, c4] = EDGE_FIT;
    let x = a.dot(b);
    let y = x.abs();
    let fit = (c0 + (c1 + c2 * y) * y) / (c3 + (c4 + y) * y);
    let theta_over_sin = if x > 0.0 {
        fit
    } else {
        0.5 / (1.0 - x * x).max(MIN_SIN_SQUARED).sqrt() - fit
    };
    a.cross(b) * theta_over_sin
}

/// The floor of sin² θ in [`edge_vector_form_factor`] for an arc of nearly opposite ends
/// (three.js's): only a degenerate polygon has one.
pub const MIN_SIN_SQUARED: f32 = 1e-7;

/// The vector form factor of a spherical polygon (unit vertices, in order): the sum of its
/// edges' [`edge_vector_form_factor`]. It points toward the polygon for a
/// counter-clockwise winding seen from the origin, away for the other.
pub fn polygon_vector_form_factor(polygon: &[Vec3]) -> Vec3 {
    polygon
        .iter()
        .zip(polygon.iter().cycle().skip(1))
        .map(|(&a, &b)| edge_vector_form_factor(a, b))
        .sum()
}

/// The form factor above the horizon z = 0 of a polygon of vector form factor `f` (from a
/// counter-clockwise winding): f.z where the whole polygon is above (`above`); otherwise
/// the horizon-clipped sphere of the same vector form factor, (|f|² + f.z) / (|f| + 1)
/// (Hill and Heitz's approximation of the clipped polygon, three.js's
/// `LTC_ClippedSphereFormFactor`), so that no vertex is clipped one by one.
pub fn horizon_form_factor(f: Vec3, above: bool) -> f32 {
    if above {
        f.z.max(0.0)
    } else {
        let l = f.length();
        ((l * l + f.z) / (l + 1.0)).max(0.0)
    }
}

/// The solid angle of a convex spherical polygon (unit vertices in order): the sum over
/// the fan of triangles from its first vertex, each by Van Oosterom and Strackee's
/// tan(Ω/2) = |a · (b × c)| / (1 + a·b + b·c + c·a) (IEEE Trans. Biomed. Eng. 1983), in
/// f64 (a light a fraction of a degree wide has triple products of 1e-6).
pub fn polygon_solid_angle(polygon: &[Vec3]) -> f32 {
    let a = polygon[0].as_dvec3();
    polygon
        .windows(2)
        .skip(1)
        .map(|w| {
            let (b, c) = (w[0].as_dvec3(), w[1].as_dvec3());
            let numerator = a.dot(b.cross(c)).abs();
            let denominator = 1.0 + a.dot(b) + b.dot(c) + c.dot(a);
            2.0 * numerator.atan2(denominator)
        })
        .sum::<f64>() as f32
}

/// The part of a spherical polygon above z = 0 (Sutherland-Hodgman on the arcs: each
/// crossing is the normalised chord point a + t (b − a), t = a.z / (a.z − b.z)).
fn clip_to_horizon(polygon: &[DVec3]) -> Vec<DVec3> {
    let mut out = Vec::with_capacity(polygon.len() + 2);
    for (i, &a) in polygon.iter().enumerate() {
        let b = polygon[(i + 1) % polygon.len()];
        if a.z >= 0.0 {
            out.push(a);
        }
        if (a.z >= 0.0) != (b.z >= 0.0) {
            let t = a.z / (a.z - b.z);
            out.push((a + t * (b - a)).normalize());
        }
    }
    out
}

/// The directions of the corners of a gnomonic rectangle about unit `centre`: half-sides
/// tan α and tan β along the unit `width_axis` (perpendicular to `centre`) and the axis
/// across it, in order around it.
pub fn rect_polygon(centre: Vec3, width_axis: Vec3, half_width: f32, half_height: f32) -> [Vec3; 4] {
    let across = centre.cross(width_axis);
    let (a, b) = (half_width.tan(), half_height.tan());
    [(1.0, 1.0), (-1.0, 1.0), (-1.0, -1.0), (1.0, -1.0)]
        .map(|(s, t)| (centre + s * a * width_axis + t * b * across).normalize())
}

/// Sides of the regular polygon a disc is shaded as: the polygon of the disc's area on
/// its tangent plane departs from the disc by under 1 % of its radius.
pub const DISC_SIDES: usize = 16;

/// The directions of the corners of the regular [`DISC_SIDES`]-gon with the area of the
/// gnomonic disc of angular radius `radius` about unit `centre`: circumradius
/// tan ρ √(2π / (N sin(2π/N))).
pub fn disc_polygon(centre: Vec3, radius: f32) -> Vec<Vec3> {
    let n = DISC_SIDES as f32;
    let step = 2.0 * std::f32::consts::PI / n;
    let r = radius.tan() * (2.0 * std::f32::consts::PI / (n * step.sin())).sqrt();
    let (t1, t2) = crate::math::sampling::tangent_frame(centre.into());
    let (t1, t2) = (Vec3::from(t1), Vec3::from(t2));
    (0..DISC_SIDES)
        .map(|k| {
            let phi = step * k as f32;
            (centre + r * (phi.cos() * t1 + phi.sin() * t2)).normalize()
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A clamped cosine (M = I) over a cap about the zenith of half-angle ρ (as a polygon
    /// of many sides) is sin²ρ; over the whole upper hemisphere, 1.
    #[test]
    fn the_form_factor_of_a_cap_is_sin_squared() {
        for rho in [0.01f32, 0.3, 1.0, 1.5] {
            let n = 2048;
            let poly: Vec<Vec3> = (0..n)
                .map(|k| {
                    let phi = 2.0 * std::f32::consts::PI * k as f32 / n as f32;
                    Vec3::new(rho.sin() * phi.cos(), rho.sin() * phi.sin(), rho.cos())
                })
                .collect();
            let f = polygon_form_factor(&poly);
            let want = rho.sin().powi(2);
            assert!((f / want - 1.0).abs() < 2e-3, "{rho}: {f} vs {want}");
        }
    }

    /// A small gnomonic square's solid angle is its area over the unit sphere; the rectangle
    /// of half-sides α, β on its axis is 4 asin(sin α sin β).
    #[test]
    fn polygon_solid_angles() {
        let (a, b) = (0.3f32, 0.1f32);
        let rect = rect_polygon(Vec3::Z, Vec3::X, a, b);
        let want = 4.0 * (a.sin() * b.sin()).asin();
        assert!((polygon_solid_angle(&rect) / want - 1.0).abs() < 1e-5);
        let disc = disc_polygon(Vec3::new(0.0, 0.6, 0.8), 0.1);
        let cap = 2.0 * std::f32::consts::PI * (1.0 - 0.1f32.cos());
        assert!((polygon_solid_angle(&disc) / cap - 1.0).abs() < 0.01, "{}", polygon_solid_angle(&disc) / cap);
    }

    /// A polygon below the horizon gives nothing; one straddling it, its upper part.
    #[test]
    fn the_horizon_clips() {
        let square = |z: f32| {
            [(0.2, 0.2), (-0.2, 0.2), (-0.2, -0.2), (0.2, -0.2)]
                .map(|(x, y)| Vec3::new(x, y, z).normalize())
        };
        assert_eq!(polygon_form_factor(&square(-0.5)), 0.0);
        // A square around the horizon (in the xz-plane) loses its lower half.
        let straddle = [(0.2, 0.2), (-0.2, 0.2), (-0.2, -0.2), (0.2, -0.2)]
            .map(|(y, z)| Vec3::new(1.0, y, z).normalize());
        let upper = [(0.2, 0.2), (-0.2, 0.2), (-0.2, 0.0), (0.2, 0.0)]
            .map(|(y, z)| Vec3::new(1.0, y, z).normalize());
        let (a, b) = (polygon_form_factor(&straddle), polygon_form_factor(&upper));
        assert!((a - b).abs() < 1e-6 && a > 0.0, "{a} {b}");
    }

    /// The rational fit of θ / sin θ follows the arc: the vector form factor of a square
    /// above the horizon is the exact form factor within 1e-4 (measured: 2e-6), at every
    /// size and elevation. A straddling square's clipped-sphere form factor (the
    /// approximation real-time engines shade with) is off the clipped polygon's by under
    /// 1.5 % of the light's unclipped form factor |f| for squares up to 11° across and
    /// under 15 % for squares up to 138° across (measured: 1.3 % and 14 %).
    #[test]
    fn the_edge_fit_follows_the_arc() {
        for half in [0.01f32, 0.1, 0.5, 1.2] {
            for elevation in [1.5f32, 1.0, 0.5, 0.1, 0.05, 0.0, -0.05] {
                let centre = Vec3::new(elevation.cos(), 0.0, elevation.sin());
                let width = Vec3::Y;
                let mut rect = rect_polygon(centre, width, half, half).to_vec();
                if polygon_vector_form_factor(&rect).dot(centre) < 0.0 {
                    rect.reverse();
                }
                let above = rect.iter().all(|p| p.z >= 0.0);
                let f = polygon_vector_form_factor(&rect);
                let exact = polygon_form_factor(&rect);
                let fast = horizon_form_factor(f, above);
                if above {
                    assert!((fast / exact - 1.0).abs() < 1e-4, "{half} {elevation}: {fast} vs {exact}");
                } else {
                    let off = (fast - exact).abs() / f.length();
                    assert!(off < 0.15, "{half} {elevation}: {fast} vs {exact}");
                    if half <= 0.1 {
                        assert!(off < 0.015, "{half} {elevation}: {fast} vs {exact}");
                    }
                }
            }
        }
    }

    /// D integrates to 1 over the sphere (a polygon covering the upper hemisphere of the
    /// original cosine: the integral is invariant under M), and its samples follow it.
    #[test]
    fn an_ltc_is_normalised() {
        let frame = [Vec3::X, Vec3::Y, Vec3::Z];
        let ltc = Ltc::new(0.3, 0.5, 0.2, frame);
        // Monte Carlo of D over the sphere by uniform directions.
        let n = 200_000;
        let mut sum = 0.0f64;
        for i in 0..n {
            let [u, v] = crate::math::sampling::hammersley(i, n);
            let z = 1.0 - 2.0 * u;
            let r = (1.0 - z * z).max(0.0).sqrt();
            let phi = 2.0 * std::f32::consts::PI * v;
            sum += f64::from(ltc.density(Vec3::new(r * phi.cos(), r * phi.sin(), z)));
        }
        let total = sum * 4.0 * std::f64::consts::PI / f64::from(n);
        assert!((total - 1.0).abs() < 0.02, "{total}");
    }
}
