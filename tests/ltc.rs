//! The LTC table (`plan::ltc`) against brute force: rectangular and disc lights at
//! infinity shaded from the fitted table (`shade_polygon`: the exact BRDF at the light's
//! centre plus the LTC's extent) against the BRDF summed over the light's area (64 × 64
//! gnomonic cells a light, each a directional light through
//! `plan::material::directional_light`, the preview's and the truth's light shading), on a
//! gold metal and a dielectric at r = 0.25 … 1, n·v = 0.3 … 1, lights of 4.6° × 2.3° to
//! 22.6° × 11.4° and a 5.7° disc on R, beside it and above the normal.

mod common;

use glam::Vec3;
use splitsum::math::ltc::{disc_polygon, rect_polygon};
use splitsum::plan::ltc::{shade_polygon, LtcPoint, LtcTable, QuadLight};
use splitsum::plan::material::{directional_light, ShadeMaterial};
use splitsum::plan::shading::LightBrdf;

/// Cells per side of the brute-force sum over a light.
const CELLS: usize = 64;

/// A light: its centre, width axis and angular half-sides (a disc when `disc`).
#[derive(Clone, Copy, Debug)]
struct Light {
    centre: Vec3,
    axis: Vec3,
    half: (f32, f32),
    disc: bool,
}

impl Light {
    /// Its directions and solid angles, CELLS² gnomonic cells (those inside a disc).
    fn cells(&self) -> Vec<(Vec3, f32)> {
        let across = self.centre.cross(self.axis);
        let (a, b) = (self.half.0.tan(), self.half.1.tan());
        let mut out = Vec::new();
        for j in 0..CELLS {
            for i in 0..CELLS {
                let x = a * (2.0 * (i as f32 + 0.5) / CELLS as f32 - 1.0);
                let y = b * (2.0 * (j as f32 + 0.5) / CELLS as f32 - 1.0);
                if self.disc && (x / a).powi(2) + (y / b).powi(2) > 1.0 {
                    continue;
                }
                let p = self.centre + x * self.axis + y * across;
                // The gnomonic area element over the unit sphere: dA / |p|³.
                let omega =
                    (2.0 * a / CELLS as f32) * (2.0 * b / CELLS as f32) / p.length().powi(3);
                out.push((p.normalize(), omega));
            }
        }
        out
    }

    fn polygon(&self) -> Vec<Vec3> {
        match self.disc {
            true => disc_polygon(self.centre, self.half.0),
            false => rect_polygon(self.centre, self.axis, self.half.0, self.half.1).to_vec(),
        }
    }
}

fn material(roughness: f32, metal: bool) -> ShadeMaterial {
    ShadeMaterial {
        f0: if metal {
            Vec3::new(1.0, 0.78, 0.34)
        } else {
            Vec3::splat(0.04)
        },
        metallic: if metal { 1.0 } else { 0.0 },
        albedo: Vec3::splat(0.8),
        roughness,
        lod: 0.0,
        bend: 0.0,
        stretch: 0.0,
    }
}

/// The relative difference of the LTC's light from brute force, in luminance-like sum
/// of channels, for one light, view and material (None where the light sends nothing):
/// the preview's exact form (`shade_polygon`) and, for a rectangle, the viewer's real-time
/// form (`LtcPoint::shade_quad`).
fn difference(
    table: &LtcTable,
    light: &Light,
    n_dot_v: f32,
    m: &ShadeMaterial,
) -> Option<(f32, Option<f32>)> {
    let n = Vec3::Z;
    let v = Vec3::new((1.0 - n_dot_v * n_dot_v).sqrt(), 0.0, n_dot_v);
    let alpha = m.roughness * m.roughness;
    let mut truth = Vec3::ZERO;
    for (l, omega) in light.cells() {
        let (s, d) = directional_light(
            n,
            v,
            n_dot_v,
            alpha,
            m.f0,
            m.metallic,
            l,
            Vec3::splat(omega),
            LightBrdf::GENERIC,
        );
        truth += s + d * m.albedo;
    }
    let t = truth.x + truth.y + truth.z;
    let off = |(s, d): (Vec3, Vec3)| {
        let ltc = s + d * m.albedo;
        ((ltc.x + ltc.y + ltc.z) - t).abs() / t
    };
    let exact = off(shade_polygon(
        table,
        n,
        v,
        n_dot_v,
        m,
        &light.polygon(),
        Vec3::ONE,
    ));
    let quad = (!light.disc).then(|| {
        let corners = rect_polygon(light.centre, light.axis, light.half.0, light.half.1);
        let point = LtcPoint::new(table, n, v, n_dot_v, m);
        off(point.shade_quad(n, v, n_dot_v, m, &QuadLight::new(corners), Vec3::ONE))
    });
    (t > 1e-6).then_some((exact, quad))
}

/// The mean relative difference over the cases per roughness is within twice what was
/// measured (2.5 / 1.2 / 0.38 / 0.20 % at r = 0.25 / 0.5 / 0.75 / 1 with a 32² table;
/// the worst case, a wide light at n·v = 0.3 on R at r = 0.25 … 0.5, 44 / 21 %: the LTC's
/// fit error at grazing views where the light is wide against the lobe). The viewer's
/// real-time form of the rectangles (the edges' rational fit, the horizon as a clipped
/// sphere) is within the same bars, and its mean within 0.5 percentage points of the
/// exact form's over the same rectangles.
#[test]
fn area_lights_from_the_fitted_table_against_brute_force() {
    let table = LtcTable::fit(LightBrdf::GENERIC, 32);
    let bars = [
        (0.25f32, 0.03f32),
        (0.5, 0.024),
        (0.75, 0.008),
        (1.0, 0.004),
    ];
    let n_dot_vs = [0.3f32, 0.6, 0.9, 1.0];
    for &(r, bar) in &bars {
        let mut worst = 0.0f32;
        let mut sum = 0.0f32;
        let mut count = 0;
        // Over the rectangles: the exact form's sum, the real-time form's, their count.
        let mut rects = (0.0f32, 0.0f32, 0);
        for &nv in &n_dot_vs {
            let reflect = Vec3::new(-(1.0 - nv * nv).sqrt(), 0.0, nv);
            // On R, beside it, and high above the normal; rectangles and a disc.
            for centre in [
                reflect,
                (reflect + Vec3::new(0.0, 0.3, 0.0)).normalize(),
                Vec3::new(0.3, 0.1, 1.0).normalize(),
            ] {
                let axis = centre.cross(Vec3::Y).normalize();
                for (half, disc) in [
                    ((0.09, 0.04), false),
                    ((0.2, 0.1), false),
                    ((0.05, 0.05), true),
                ] {
                    let light = Light {
                        centre,
                        axis,
                        half,
                        disc,
                    };
                    for metal in [true, false] {
                        if let Some((d, quad)) = difference(&table, &light, nv, &material(r, metal))
                        {
                            worst = worst.max(d);
                            sum += d;
                            count += 1;
                            if let Some(q) = quad {
                                rects.0 += d;
                                rects.1 += q;
                                rects.2 += 1;
                            }
                        }
                    }
                }
            }
        }
        let mean = sum / count as f32;
        eprintln!(
            "r = {r}: mean {:.2} %, worst {:.2} %",
            100.0 * mean,
            100.0 * worst
        );
        assert!(mean <= bar, "r = {r}: mean {mean} over {bar}");
        let (exact, quad) = (rects.0 / rects.2 as f32, rects.1 / rects.2 as f32);
        eprintln!(
            "r = {r}: rectangles, exact form {:.2} %, real-time form {:.2} %",
            100.0 * exact,
            100.0 * quad
        );
        assert!(
            quad <= bar && quad - exact <= 5e-3,
            "r = {r}: real-time {quad} exact {exact}"
        );
    }
}

/// A light far narrower than the lobe is shaded as the exact BRDF at its centre (the LTC
/// carries only its extent): a 0.2° square within 0.5 % of one directional light of its
/// energy, at every roughness from 0.25 and every view.
#[test]
fn a_small_light_is_the_brdf_at_its_centre() {
    let table = LtcTable::fit(LightBrdf::GENERIC, 16);
    for r in [0.25f32, 0.5, 1.0] {
        for nv in [0.2f32, 0.5, 1.0] {
            let n = Vec3::Z;
            let v = Vec3::new((1.0 - nv * nv).sqrt(), 0.0, nv);
            let centre = Vec3::new(-0.3, 0.2, 0.9).normalize();
            let polygon = rect_polygon(centre, centre.cross(Vec3::Y).normalize(), 0.0017, 0.0017);
            let omega = splitsum::math::ltc::polygon_solid_angle(&polygon);
            for metal in [true, false] {
                let m = material(r, metal);
                let (s, d) = shade_polygon(&table, n, v, nv, &m, &polygon, Vec3::ONE);
                let (ps, pd) = directional_light(
                    n,
                    v,
                    nv,
                    r * r,
                    m.f0,
                    m.metallic,
                    centre,
                    Vec3::splat(omega),
                    LightBrdf::GENERIC,
                );
                let (a, b) = ((s + d * m.albedo).x, (ps + pd * m.albedo).x);
                assert!(
                    (a / b - 1.0).abs() < 5e-3,
                    "r {r} n·v {nv} metal {metal}: {a} vs {b}"
                );
            }
        }
    }
}

/// A mirror (r = 0) shows the light's image: F(n·v) L where R falls inside the light, 0
/// where it does not.
#[test]
fn a_mirror_shows_the_light() {
    let table = LtcTable::fit(LightBrdf::GENERIC, 16);
    for nv in [0.3f32, 0.7, 1.0] {
        let n = Vec3::Z;
        let v = Vec3::new((1.0 - nv * nv).sqrt(), 0.0, nv);
        let reflect = Vec3::new(-v.x, 0.0, v.z);
        let m = material(0.0, true);
        for (centre, inside) in [
            (reflect, true),
            ((reflect + Vec3::new(0.0, 0.5, 0.0)).normalize(), false),
        ] {
            let axis = centre.cross(Vec3::Y).normalize();
            let polygon = rect_polygon(centre, axis, 0.1, 0.1);
            let (s, _) = shade_polygon(&table, n, v, nv, &m, &polygon, Vec3::ONE);
            let want = if inside {
                m.f0.x + (1.0 - m.f0.x) * (1.0 - nv).powi(5)
            } else {
                0.0
            };
            eprintln!("n·v {nv} inside {inside}: {} vs {want}", s.x);
            assert!(
                (s.x - want).abs() < 0.02,
                "n·v {nv} inside {inside}: {} vs {want}",
                s.x
            );
        }
    }
}

/// The studios with `--sun split`, their lamps and soft boxes shaded as area lights from
/// the LTC table: every sphere at r ≥ 0.25 within 5 % of the truth (32-pixel cells, 1024
/// truth points, as `examples/area_study.rs`: studio_small_03's metals measure 3.4 / 3.9 /
/// 2.6 / 1.7 % at r = 0.25 / 0.5 / 0.75 / 1, Blender's studio 3.0 / 2.6 / 2.1 / 2.3 %;
/// with the lamps in the chain 15.6 / 23.2 / 13.8 / 12.6 % and 21.1 / 19.7 / 12.4 / 11.0 %).
#[test]
fn studios_within_five_per_cent_with_their_lights_split() {
    use splitsum::backend::{Backend, CpuBackend};
    use splitsum::stages::preview::{render_preview, BakedLight, PreviewOptions};
    let backend = common::preferred_backend();
    let lut = CpuBackend.brdf_lut(512, 512).unwrap();
    for name in ["studio_small_03_1k.hdr", "blender_studiolight_studio.exr"] {
        let baked = common::bake_split(name);
        assert!(
            baked.split_lights().iter().any(|l| l.shape.is_some()),
            "{name}: no area light"
        );
        let preview = PreviewOptions {
            cell: 32,
            truth_samples: 1024,
            ..PreviewOptions::default()
        };
        let p = render_preview(&*backend, &BakedLight::of(name, &baked, &lut), &preview).unwrap();
        for s in p.stats.iter().filter(|s| s.roughness >= 0.25) {
            assert!(s.mean_relative <= 0.05, "{name}: {s:?}");
        }
    }
}

/// Heitz's published GGX fit (selfshadow/ltc_code's `fitLTC` output, as three.js r187 ships
/// it in `RectAreaLightTexturesLib`: `LTC_MAT_1` then `LTC_MAT_2`, 64 × 64 RGBA f32 each,
/// tests/data/README.md) for the height-correlated Smith GGX it was fitted to.
fn heitz_table() -> LtcTable {
    const SIZE: usize = 64;
    let bytes = std::fs::read("tests/data/ltc_ggx_heitz_three_r187.f32").unwrap();
    let f: Vec<f32> = bytes
        .chunks_exact(4)
        .map(|b| f32::from_le_bytes([b[0], b[1], b[2], b[3]]))
        .collect();
    assert_eq!(f.len(), 2 * 4 * SIZE * SIZE);
    let (one, two) = f.split_at(4 * SIZE * SIZE);
    let cells = (0..SIZE * SIZE)
        .map(|k| splitsum::plan::ltc::LtcCell {
            inverse: [one[4 * k], one[4 * k + 1], one[4 * k + 2], one[4 * k + 3]],
            norm: two[4 * k],
            fresnel: two[4 * k + 1],
        })
        .collect();
    LtcTable {
        size: SIZE as u32,
        brdf: HEITZ_BRDF,
        cells,
    }
}

/// The BRDF of Heitz's fit (`brdf_ggx.h`): GGX with the height-correlated Smith G2.
const HEITZ_BRDF: LightBrdf = LightBrdf {
    masking: splitsum::plan::shading::Masking::SmithCorrelated,
    diffuse: splitsum::plan::shading::DiffuseLobe::FresnelWeighted,
    compensated: false,
};

/// The LTC alone (no control variate) of one cell over a polygon, against `brdf` summed
/// over it, F = 1: (LTC, brute force).
fn lobe_over(
    cell: &splitsum::plan::ltc::LtcCell,
    light: &Light,
    n_dot_v: f32,
    alpha: f32,
    brdf: LightBrdf,
) -> (f32, f32) {
    let v = Vec3::new((1.0 - n_dot_v * n_dot_v).max(0.0).sqrt(), 0.0, n_dot_v);
    let ltc = splitsum::math::ltc::Ltc::from_inverse(cell.inverse_matrix());
    let fitted = cell.norm * ltc.integrate_polygon(&light.polygon());
    let brute: f32 = light
        .cells()
        .into_iter()
        .map(|(l, omega)| {
            let (s, _) = directional_light(
                Vec3::Z,
                v,
                n_dot_v,
                alpha,
                Vec3::ONE,
                1.0,
                l,
                Vec3::splat(omega),
                brdf,
            );
            s.x
        })
        .sum();
    (fitted, brute)
}

/// splitsum's fit (`LtcTable::fit`, 64², for the BRDF Heitz fitted) against Heitz's
/// published table, cell by cell at the table's own (r, θ) (every third cell from r = 0.1),
/// each LTC alone over rectangles of 5° to 34° on R, beside it and near the horizon against
/// the BRDF summed over them: per band of roughness the energy-weighted error of either
/// table, Σ |LTC − brute| / Σ brute, and their difference, Σ |ours − Heitz's| / Σ brute.
/// Measured, r in [0.1, 0.35) / [0.35, 0.65) / [0.65, 1]: ours 3.19 / 7.83 / 9.40 % from
/// brute force, Heitz's 2.81 / 8.00 / 9.57 %; the two 0.43 / 0.60 / 0.29 % apart; their
/// magnitudes (A + B, B) equal to 1e-4. Tolerances: ours no worse than 1.25 × Heitz's +
/// 0.2 pp (1.14 × in the first band, where the fits' floors differ: Heitz's α ≥ 1e-5, ours
/// 1e-3, `plan::ltc::MIN_ALPHA`), the tables within 1.5 % of each other and their
/// magnitudes within 0.01 (Nelder-Mead may settle in another local minimum elsewhere).
/// The LTC alone is what an engine's RectAreaLight shades; splitsum's preview and
/// js/splitsum-three.js correct it at the light's centre (`area_lights_from_the_fitted_table_against_brute_force`).
/// Per band of roughness ([lo, hi)), two tables of one size and BRDF cell by cell at the
/// table's own (r, θ) (every third cell from r = 0.1), each LTC alone over rectangles of 5°
/// to 34° on R, beside it and near the horizon, against the BRDF summed over them:
/// (Σ |`a` − brute| / Σ brute, Σ |`b` − brute| / Σ brute, Σ |`a` − `b`| / Σ brute), and
/// the largest difference of their magnitudes (A + B, B).
fn tables_against_brute_force(
    a_table: &LtcTable,
    b_table: &LtcTable,
    bands: &[(f32, f32)],
) -> (Vec<(f64, f64, f64)>, f32) {
    let size = a_table.size;
    assert_eq!(size, b_table.size);
    let last = (size - 1) as f32;
    let mut magnitude = 0.0f32;
    let mut out = Vec::new();
    for &(lo, hi) in bands {
        let (mut e_a, mut e_b, mut between, mut total) = (0.0f64, 0.0f64, 0.0f64, 0.0f64);
        for j in (0..size).step_by(3) {
            let x = j as f32 / last;
            let theta = (1.0 - x * x).acos().min(1.57);
            let n_dot_v = theta.cos();
            for i in (0..size).step_by(3) {
                let r = i as f32 / last;
                if r < lo || r >= hi {
                    continue;
                }
                let alpha = (r * r).max(splitsum::plan::ltc::MIN_ALPHA);
                let k = (j * size + i) as usize;
                let (a, b) = (&a_table.cells[k], &b_table.cells[k]);
                magnitude = magnitude
                    .max((a.norm - b.norm).abs())
                    .max((a.fresnel - b.fresnel).abs());
                let reflect = Vec3::new(-theta.sin(), 0.0, n_dot_v);
                for centre in [
                    reflect,
                    (reflect + Vec3::new(0.0, 0.4, 0.0)).normalize(),
                    Vec3::new(0.5, 0.2, 0.25).normalize(),
                ] {
                    let axis = centre.cross(Vec3::Y).normalize();
                    for half in [(0.09f32, 0.04f32), (0.3, 0.15)] {
                        let light = Light {
                            centre,
                            axis,
                            half,
                            disc: false,
                        };
                        let (got, brute) = lobe_over(a, &light, n_dot_v, alpha, a_table.brdf);
                        let (want, _) = lobe_over(b, &light, n_dot_v, alpha, b_table.brdf);
                        e_a += f64::from((got - brute).abs());
                        e_b += f64::from((want - brute).abs());
                        between += f64::from((got - want).abs());
                        total += f64::from(brute);
                    }
                }
            }
        }
        out.push((e_a / total, e_b / total, between / total));
    }
    (out, magnitude)
}

/// splitsum's fit (`LtcTable::fit`, 64², for the BRDF Heitz fitted) against Heitz's
/// published table (`tables_against_brute_force`).
/// Measured, r in [0.1, 0.35) / [0.35, 0.65) / [0.65, 1]: ours 3.19 / 7.83 / 9.40 % from
/// brute force, Heitz's 2.81 / 8.00 / 9.57 %; the two 0.43 / 0.60 / 0.29 % apart; their
/// magnitudes (A + B, B) equal to 1e-4. Tolerances: ours no worse than 1.25 × Heitz's +
/// 0.2 pp (1.14 × in the first band, where the fits' floors differ: Heitz's α ≥ 1e-5, ours
/// 1e-3, `plan::ltc::MIN_ALPHA`), the tables within 1.5 % of each other and their
/// magnitudes within 0.01 (Nelder-Mead may settle in another local minimum elsewhere).
/// The LTC alone is what an engine's RectAreaLight shades; splitsum's preview and
/// js/splitsum-three.js correct it at the light's centre (`area_lights_from_the_fitted_table_against_brute_force`).
#[test]
fn the_fit_against_heitz_published_table() {
    let heitz = heitz_table();
    let ours = LtcTable::fit(HEITZ_BRDF, heitz.size);
    let bands = [(0.1f32, 0.35f32), (0.35, 0.65), (0.65, 1.01)];
    let (errors, magnitude) = tables_against_brute_force(&ours, &heitz, &bands);
    for (&(lo, hi), &(e_ours, e_heitz, between)) in bands.iter().zip(&errors) {
        eprintln!(
            "r in [{lo}, {hi}): against brute force ours {:.2} %, Heitz's {:.2} %; ours against Heitz's {:.2} %",
            100.0 * e_ours,
            100.0 * e_heitz,
            100.0 * between
        );
        assert!(
            e_ours <= 1.1 * e_heitz + 0.002,
            "r in [{lo}, {hi}): {e_ours} vs {e_heitz}"
        );
        assert!(
            between <= 0.015,
            "r in [{lo}, {hi}): the tables {between} apart"
        );
    }
    eprintln!("magnitudes (A + B, B) within {magnitude:.4}");
    assert!(magnitude <= 0.01, "magnitudes {magnitude} apart");
}

/// The GPU's fit (`gpu::ltc_fit`, shaders/ltc_fit.wgsl) against its CPU twin
/// (`LtcTable::fit`), 16² for the generic light BRDF (Schlick-GGX): the same Nelder-Mead
/// on quadratures summed in f32 by a workgroup rather than in f64, so a simplex may take
/// another step where two points' errors are within rounding and stop elsewhere in the
/// fit's flat minimum. Measured on lavapipe, r in [0.1, 0.35) / [0.35, 0.65) / [0.65, 1]:
/// GPU 6.469 / 9.547 / 7.446 % from brute force, CPU 6.466 / 9.540 / 7.447 %, the two
/// 0.005 / 0.017 / 0.011 % apart, the magnitudes within 6.6e-7. Tolerances: the GPU's
/// table no further from brute force than the CPU's + 0.1 pp, the two within 0.2 % of
/// each other (the 64² fit's distance from Heitz's is 0.3–0.6 %), the magnitudes within
/// 1e-5 (1024 terms summed in f32: a relative 1e-6 each way).
#[test]
fn gpu_fit_against_the_cpu_fit() {
    let Some(ctx) = common::gpu() else { return };
    let brdf = LightBrdf::GENERIC;
    let start = std::time::Instant::now();
    let gpu = splitsum::gpu::ltc_fit::fit_ltc(&ctx.device, &ctx.queue, brdf, 16).unwrap();
    let gpu_s = start.elapsed().as_secs_f64();
    let start = std::time::Instant::now();
    let cpu = LtcTable::fit(brdf, 16);
    let cpu_s = start.elapsed().as_secs_f64();
    eprintln!("16² fit: GPU {gpu_s:.2} s, CPU {cpu_s:.2} s (wall)");
    let bands = [(0.1f32, 0.35f32), (0.35, 0.65), (0.65, 1.01)];
    let (errors, magnitude) = tables_against_brute_force(&gpu, &cpu, &bands);
    for (&(lo, hi), &(e_gpu, e_cpu, between)) in bands.iter().zip(&errors) {
        eprintln!(
            "r in [{lo}, {hi}): against brute force GPU {:.3} %, CPU {:.3} %; apart {:.3} %",
            100.0 * e_gpu,
            100.0 * e_cpu,
            100.0 * between
        );
        assert!(
            e_gpu <= e_cpu + 0.001,
            "r in [{lo}, {hi}): {e_gpu} vs {e_cpu}"
        );
        assert!(between <= 0.002, "r in [{lo}, {hi}): {between} apart");
    }
    eprintln!("magnitudes (A + B, B) within {magnitude:.2e}");
    assert!(magnitude <= 1e-5, "magnitudes {magnitude} apart");
}
