//! The sun (`environment::sun`): found on synthetic environments of known sun (a smooth sky
//! plus a disc rasterised with its coverage of every texel) at the equator, near a pole,
//! across the equirect's seam and on cube face edges; not found where there is none; and
//! taken out with the energy kept, on every bundled HDRI.

mod common;

use std::f64::consts::PI;

use splitsum::environment::{Cubemap, Environment, Equirect};
use splitsum::math::cubemap::cube_face_direction;
use splitsum::{find_sun, split_sun, Sun};

use common::{
    brute_force_irradiance, direction, dot, light_irradiance, normalize, test_equirect,
    uniform_directions,
};

/// The synthetic sun's irradiance E⊥ per channel (the sky's is about 2.3, so the sun
/// holds about two thirds of the light, as outdoor HDRIs' suns do).
const SUN_E: [f64; 3] = [6.0, 5.0, 4.0];
/// Sub-samples per axis a texel near the disc is rasterised with (its coverage to
/// 1/1024 of a texel: E⊥ to well under the 0.5 % bar).
const SUPERSAMPLE: usize = 32;
/// Limb darkening of the discs, I(μ) = 1 − u (1 − μ) (the visible sun's u ≈ 0.6): a real
/// sun has no flat top, while a uniform disc wider than a few texels is a plateau, as a
/// saturated camera's sun is (`a_flat_topped_sun_reads_as_clipped`).
const LIMB_DARKENING: f64 = 0.6;

fn angle_deg(a: [f64; 3], b: [f64; 3]) -> f64 {
    let c = [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ];
    dot(c, c).sqrt().atan2(dot(a, b)).to_degrees()
}

/// A smooth sky, positive everywhere.
fn sky(d: [f64; 3]) -> [f64; 3] {
    [
        0.5 + 0.3 * d[1] + 0.1 * d[0],
        0.6 + 0.3 * d[1],
        0.8 + 0.3 * d[1] - 0.1 * d[2],
    ]
}

/// A sun disc: its centre, angular radius, and the radiance profile I(γ/ρ) relative to
/// its centre's (uniform or limb-darkened).
struct Disc {
    centre: [f64; 3],
    radius: f64,
    limb: f64,
}

impl Disc {
    /// Relative radiance at direction d (0 outside).
    fn profile(&self, d: [f64; 3]) -> f64 {
        let g = angle_deg(d, self.centre).to_radians();
        if g >= self.radius {
            return 0.0;
        }
        let x = g / self.radius;
        1.0 - self.limb * (1.0 - (1.0 - x * x).sqrt())
    }
}

/// Rasterises `disc` over a sky: `texel(k)` yields texel k's sub-sample directions with
/// their solid-angle weights; texels whose centre lies farther than `margin` from the
/// disc's edge are sky alone. Returns each texel's mean radiance (per unit of the sun's
/// central radiance, then scaled so the image holds exactly [`SUN_E`]) and the centre
/// direction list. The sun is added to the sky (E⊥ is what it adds).
fn rasterise(
    centres: &[[f64; 3]],
    omegas: &[f64],
    subsamples: &dyn Fn(usize) -> Vec<([f64; 3], f64)>,
    disc: &Disc,
) -> Vec<[f32; 3]> {
    let margin = disc.radius + 1f64.to_radians();
    let mut coverage = vec![0.0f64; centres.len()];
    for (k, c) in centres.iter().enumerate() {
        if angle_deg(*c, disc.centre).to_radians() < margin {
            let subs = subsamples(k);
            let total: f64 = subs.iter().map(|s| s.1).sum();
            coverage[k] = subs.iter().map(|s| s.1 * disc.profile(s.0)).sum::<f64>() / total;
        }
    }
    // Scale so the image's sun is E⊥ exactly: Σ coverage Ω L₀ = E.
    let flux: f64 = coverage.iter().zip(omegas).map(|(c, o)| c * o).sum();
    centres
        .iter()
        .zip(&coverage)
        .map(|(d, c)| {
            let s = sky(*d);
            [0, 1, 2].map(|i| (s[i] + c * SUN_E[i] / flux) as f32)
        })
        .collect()
}

fn equirect_with_sun(width: u32, disc: &Disc) -> Equirect {
    let (w, h) = (width as usize, width as usize / 2);
    let mut centres = Vec::with_capacity(w * h);
    let mut omegas = Vec::with_capacity(w * h);
    for y in 0..h {
        let (t0, t1) = (PI * y as f64 / h as f64, PI * (y + 1) as f64 / h as f64);
        let omega = 2.0 * PI / w as f64 * (t0.cos() - t1.cos());
        for x in 0..w {
            let (u, v) = ((x as f64 + 0.5) / w as f64, (y as f64 + 0.5) / h as f64);
            let (phi, theta) = ((u - 0.5) * 2.0 * PI, v * PI);
            centres.push([
                theta.sin() * phi.cos(),
                theta.cos(),
                theta.sin() * phi.sin(),
            ]);
            omegas.push(omega);
        }
    }
    // Sub-samples of equal solid angle: uniform in φ and in cos θ.
    let subsamples = |k: usize| {
        let (x, y) = (k % w, k / w);
        let (c0, c1) = (
            (PI * y as f64 / h as f64).cos(),
            (PI * (y + 1) as f64 / h as f64).cos(),
        );
        let mut out = Vec::with_capacity(SUPERSAMPLE * SUPERSAMPLE);
        for b in 0..SUPERSAMPLE {
            let cos_t = c0 + (c1 - c0) * (b as f64 + 0.5) / SUPERSAMPLE as f64;
            let sin_t = (1.0 - cos_t * cos_t).max(0.0).sqrt();
            for a in 0..SUPERSAMPLE {
                let u = (x as f64 + (a as f64 + 0.5) / SUPERSAMPLE as f64) / w as f64;
                let phi = (u - 0.5) * 2.0 * PI;
                out.push(([sin_t * phi.cos(), cos_t, sin_t * phi.sin()], 1.0));
            }
        }
        out
    };
    Equirect {
        width,
        height: width / 2,
        data: rasterise(&centres, &omegas, &subsamples, disc),
    }
}

fn cube_with_sun(n: u32, disc: &Disc) -> Cubemap {
    let n_us = n as usize;
    let mut centres = Vec::new();
    let mut omegas = Vec::new();
    for face in 0..6 {
        for j in 0..n {
            for i in 0..n {
                centres.push(
                    splitsum::math::cubemap::cube_texel_direction(face, i as i32, j as i32, n)
                        .map(f64::from),
                );
                omegas.push(f64::from(splitsum::math::cubemap::cube_texel_solid_angle(
                    i, j, n,
                )));
            }
        }
    }
    // Sub-samples uniform on the face, weighted by the solid-angle density (1 + s² + t²)^(−3/2).
    let subsamples = |k: usize| {
        let (face, j, i) = (k / (n_us * n_us), k % (n_us * n_us) / n_us, k % n_us);
        let mut out = Vec::with_capacity(SUPERSAMPLE * SUPERSAMPLE);
        for b in 0..SUPERSAMPLE {
            let t = ((j as f64 + (b as f64 + 0.5) / SUPERSAMPLE as f64) * 2.0 / n as f64) - 1.0;
            for a in 0..SUPERSAMPLE {
                let s = ((i as f64 + (a as f64 + 0.5) / SUPERSAMPLE as f64) * 2.0 / n as f64) - 1.0;
                let d = cube_face_direction(face as u32, s as f32, t as f32).map(f64::from);
                out.push((normalize(d), (1.0 + s * s + t * t).powf(-1.5)));
            }
        }
        out
    };
    let data = rasterise(&centres, &omegas, &subsamples, disc);
    Cubemap {
        size: n,
        levels: vec![data.into_iter().map(|l| [l[0], l[1], l[2], 1.0]).collect()],
    }
}

/// Checks a found sun against the disc: direction within 0.05°, E⊥ within 0.5 % per
/// channel, radius within 15 % (the bars of the sun's specification).
fn check(name: &str, sun: Option<Sun>, disc: &Disc) {
    let sun = sun.unwrap_or_else(|| panic!("{name}: no sun found"));
    let off = angle_deg(sun.direction.map(f64::from), disc.centre);
    assert!(off < 0.05, "{name}: direction {off:.4}° off ({sun:?})");
    for (c, e) in SUN_E.iter().enumerate() {
        let rel = (f64::from(sun.irradiance[c]) / e - 1.0).abs();
        assert!(
            rel < 0.005,
            "{name}: E channel {c} {:.3} % off ({sun:?})",
            100.0 * rel
        );
    }
    let rel = (f64::from(sun.angular_radius_deg) / disc.radius.to_degrees() - 1.0).abs();
    assert!(
        rel < 0.15,
        "{name}: radius {:.3}° for {:.3}° ({sun:?})",
        sun.angular_radius_deg,
        disc.radius.to_degrees()
    );
    assert!(
        !sun.clipped,
        "{name}: a sun with no plateau read as clipped"
    );
    eprintln!(
        "{name}: direction {off:.4}° off, E {:?}, radius {:.3}° for {:.3}°, {} texels",
        sun.irradiance,
        sun.angular_radius_deg,
        disc.radius.to_degrees(),
        sun.texels
    );
}

/// A limb-darkened disc, like the real sun.
fn disc(azimuth: f64, elevation: f64, radius_deg: f64) -> Disc {
    Disc {
        centre: direction(azimuth, elevation),
        radius: radius_deg.to_radians(),
        limb: LIMB_DARKENING,
    }
}

#[test]
fn equirect_suns_are_found_where_they_are() {
    for (place, azimuth, elevation) in [
        ("equator", 30.0, 0.0),
        ("near the pole", 120.0, 84.0),
        ("across the seam", 180.0, 25.0),
    ] {
        for radius in [0.3, 2.0] {
            let d = disc(azimuth, elevation, radius);
            let env = Environment::Equirect(equirect_with_sun(1024, &d));
            check(
                &format!("equirect, {place}, {radius}°"),
                find_sun(&env).map(|f| f.sun),
                &d,
            );
        }
    }
}

/// The cube inputs' face edge: texels of 0.11°–0.22°. (At 256², a face's central texels
/// are 0.45° wide: a 0.3° disc centred on a texel corner then lies in four texels of
/// equal coverage whatever its radius, so no estimator can measure the radius; the
/// direction and E⊥ are still found to the bars.)
const CUBE_SIZE: u32 = 512;

#[test]
fn cube_suns_are_found_on_face_edges() {
    for (place, azimuth, elevation) in [
        ("+X/+Z edge", 45.0, 10.0),
        ("+X/+Y edge", 0.0, 45.0),
        ("corner", -45.0, 35.264),
        ("face centre", 90.0, 0.0),
    ] {
        for radius in [0.3, 2.0] {
            let d = disc(azimuth, elevation, radius);
            let env = Environment::Cube(cube_with_sun(CUBE_SIZE, &d));
            check(
                &format!("cube, {place}, {radius}°"),
                find_sun(&env).map(|f| f.sun),
                &d,
            );
        }
    }
}

#[test]
fn a_flat_topped_sun_reads_as_clipped() {
    // A uniform 2° disc: dozens of texels at one value, as a saturated camera writes them.
    let d = Disc {
        centre: direction(-60.0, 30.0),
        radius: 2f64.to_radians(),
        limb: 0.0,
    };
    let sun = find_sun(&Environment::Equirect(equirect_with_sun(1024, &d)))
        .expect("a sun")
        .sun;
    assert!(sun.clipped, "{sun:?}");
}

#[test]
fn sunless_environments_have_no_sun() {
    // Overcast, a clipped sunset whose sun holds 0.05 % of the light, and a studio whose
    // soft boxes (6° and wider) are not one sun.
    for name in [
        "pedestrian_overpass_1k.hdr",
        "venice_sunset_1k.hdr",
        "studio_small_03_1k.hdr",
    ] {
        let env = Environment::Equirect(test_equirect(name));
        let sun = find_sun(&env).map(|f| f.sun);
        assert!(sun.is_none(), "{name}: {sun:?}");
    }
    // A smooth sky alone.
    let sky_only = Equirect {
        width: 256,
        height: 128,
        data: (0..256 * 128)
            .map(|k| {
                let (x, y) = (k % 256, k / 256);
                let d = direction(
                    ((x as f64 + 0.5) / 256.0 - 0.5) * 360.0,
                    90.0 - (y as f64 + 0.5) / 128.0 * 180.0,
                );
                sky(d).map(|v| v as f32)
            })
            .collect(),
    };
    assert!(find_sun(&Environment::Equirect(sky_only)).is_none());
}

#[test]
fn non_finite_texels_are_never_a_sun() {
    let mut e = test_equirect("pedestrian_overpass_1k.hdr");
    for k in [1000, 50_000, 50_001, 50_002, 200_000] {
        e.data[k] = [f32::INFINITY, f32::NAN, f32::INFINITY];
    }
    assert!(find_sun(&Environment::Equirect(e)).is_none());
}

#[test]
fn the_bundled_suns_are_where_the_pictures_show_them() {
    // quarry_01: a low sun over the quarry's rim (the brightest texel at column 614,
    // row 227: azimuth 36°, elevation 10°); royal_esplanade: nearly overhead (column 92,
    // row 18).
    for (name, azimuth, elevation, share) in [
        ("quarry_01_1k.hdr", 36.0, 10.1, 0.45..0.52),
        ("royal_esplanade_1k.hdr", -148.8, 83.5, 0.28..0.33),
    ] {
        let sun = find_sun(&Environment::Equirect(test_equirect(name)))
            .unwrap_or_else(|| panic!("{name}: no sun"))
            .sun;
        let off = angle_deg(sun.direction.map(f64::from), direction(azimuth, elevation));
        assert!(
            off < 0.5,
            "{name}: {off}° from the brightest texels ({sun})"
        );
        assert!(share.contains(&sun.share), "{name}: {sun}");
        assert!(!sun.clipped, "{name}: {sun}");
    }
}

fn flux(e: &Equirect) -> [f64; 3] {
    let mut s = [0.0; 3];
    for y in 0..e.height {
        let omega = e.row_solid_angle(y);
        for x in 0..e.width {
            let l = e.get(x, y);
            for c in 0..3 {
                s[c] += f64::from(l[c]) * omega;
            }
        }
    }
    s
}

#[test]
fn the_residual_and_the_light_keep_the_energy() {
    // Every bundled HDRI with a sun: the flux of the residual plus the light's equals the
    // input's within 0.1 %, and at 2000 normals the residual's irradiance plus the sun's
    // (its disc clipped by each normal's horizon) equals the input's within 0.5 %, both at
    // the source's full resolution.
    let normals = uniform_directions(2000, 27);
    let mut found = 0;
    for name in [
        "quarry_01_1k.hdr",
        "royal_esplanade_1k.hdr",
        "blender_studiolight_interior.exr",
        "venice_sunset_1k_f32_piz.exr",
    ] {
        let input = test_equirect(name);
        let mut env = Environment::Equirect(input.clone());
        let Some(sun) = split_sun(&mut env) else {
            continue;
        };
        found += 1;
        let Environment::Equirect(residual) = env else {
            unreachable!()
        };
        let (fi, fr) = (flux(&input), flux(&residual));
        for c in 0..3 {
            let rel = ((fr[c] + f64::from(sun.irradiance[c])) / fi[c] - 1.0).abs();
            assert!(
                rel < 1e-3,
                "{name}: flux channel {c} {:.4} % off",
                100.0 * rel
            );
        }
        let full = brute_force_irradiance(&input, &normals);
        let rest = brute_force_irradiance(&residual, &normals);
        let mut worst: f64 = 0.0;
        for (k, n) in normals.iter().enumerate() {
            let s = light_irradiance(&sun, *n);
            for c in 0..3 {
                let rel = ((rest[k][c] + s[c]) / full[k][c] - 1.0).abs();
                worst = worst.max(rel);
            }
        }
        eprintln!("{name}: worst irradiance {:.4} %", 100.0 * worst);
        assert!(
            worst < 0.005,
            "{name}: irradiance {:.3} % off",
            100.0 * worst
        );
    }
    assert!(found >= 3, "only {found} bundled HDRIs with a sun");
}
