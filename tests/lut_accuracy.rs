//! The BRDF LUT against a converged reference integral computed independently in f64.
mod common;

use splitsum::cpu::brdf_lut::brdf_lut_texel;
use splitsum::lut::{LutModel, LutQuadrature};

/// Quality bar from DESIGN.md: max |error| ≤ 1e-4 over the grid, grazing column included.
const LUT_TOLERANCE: f64 = 1e-4;

#[test]
fn cpu_lut_matches_converged_integral() {
    let quad = LutQuadrature::default();
    for model in LutModel::ALL {
        for (w, h) in [(128u32, 128u32), (512, 512)] {
            let texels = common::check_texels(w, h);
            let worst = common::worst_model_error(w, h, &texels, model, |nv, r| {
                brdf_lut_texel(nv, r, &quad, model)
            });
            println!(
                "{} {w}x{h}: worst |error| {:.2e} at texel {:?}",
                model.name(),
                worst.0,
                worst.1
            );
            assert!(
                worst.0 <= LUT_TOLERANCE,
                "{} {w}x{h}: {:?}",
                model.name(),
                worst
            );
        }
    }
}

/// A denser scan (every 8th texel of the 512² table, plus all edge texels); slow, so run on
/// demand: `cargo test --release --test lut_accuracy -- --ignored --nocapture`.
#[test]
#[ignore]
fn dense_scan_512() {
    let quad = LutQuadrature::default();
    let (w, h) = (512u32, 512u32);
    let mut texels: Vec<(u32, u32)> = (0..w)
        .step_by(8)
        .flat_map(|i| (0..h).step_by(8).map(move |j| (i, j)))
        .collect();
    for t in 0..w {
        texels.extend([(0, t), (w - 1, t), (t, 0), (t, h - 1)]);
    }
    for model in LutModel::ALL {
        let worst = common::worst_model_error(w, h, &texels, model, |nv, r| {
            brdf_lut_texel(nv, r, &quad, model)
        });
        println!(
            "{} dense 512: worst |error| {:.2e} at texel {:?}",
            model.name(),
            worst.0,
            worst.1
        );
        assert!(worst.0 <= LUT_TOLERANCE, "{}", model.name());
    }
}

/// Accuracy against cost of smaller rules (run on demand:
/// `cargo test --release --test lut_accuracy quadrature_scan -- --ignored --nocapture`):
/// worst |error| over the check texels of 512² and the CPU time of a 512² table.
#[test]
#[ignore]
fn quadrature_scan() {
    let (w, h) = (512u32, 512u32);
    for (full, partial, phi, growth) in [
        (12, 8, 6, 2.5f32),
        (12, 6, 5, 2.5),
        (10, 6, 5, 2.5),
        (10, 6, 5, 3.0),
        (12, 6, 5, 3.0),
        (10, 6, 6, 3.0),
        (10, 5, 5, 3.0),
    ] {
        let quad = LutQuadrature::with_rules(full, partial, phi, growth);
        let worst = common::worst_lut_error(w, h, &common::check_texels(w, h), |nv, r| {
            brdf_lut_texel(nv, r, &quad, LutModel::SchlickGgx)
        });
        let t = std::time::Instant::now();
        splitsum::cpu::brdf_lut::brdf_lut(w, h, &quad, LutModel::SchlickGgx);
        println!(
            "full {full:2} partial {partial} phi {phi} growth {growth}: worst {:.2e} at {:?}, 512² in {:.3} s",
            worst.0,
            worst.1,
            t.elapsed().as_secs_f64()
        );
    }
}

/// Furnace-style identities, every model: A + B = ∫ V' (the directional albedo with F = 1)
/// never exceeds 1 (single scattering loses energy, never gains it), and for a mirror
/// (row 0, r = 1/1024) h = n, so A = 1 − (1 − n·v)⁵ and B = (1 − n·v)⁵ exactly
/// (1e-3: the row's r is not 0, and the lobe spreads by α = 1e-6 there).
#[test]
fn every_model_keeps_the_albedo_identities() {
    let quad = LutQuadrature::default();
    let (w, h) = (64u32, 512u32);
    for model in LutModel::ALL {
        let lut = splitsum::cpu::brdf_lut::brdf_lut(w, h, &quad, model);
        // Back to (A, B) whatever the layout.
        let ab = |i: u32, j: u32| {
            let v = lut.get(i, j);
            match model.layout() {
                splitsum::lut::LutLayout::ScaleBias => v,
                splitsum::lut::LutLayout::Multiscatter => [v[1] - v[0], v[0]],
            }
        };
        for j in (0..h).step_by(7) {
            for i in 0..w {
                let [a, b] = ab(i, j);
                assert!(
                    a + b <= 1.0 + 1e-5,
                    "{} ({i}, {j}): A + B = {}",
                    model.name(),
                    a + b
                );
                assert!(a >= 0.0 && b >= 0.0);
            }
        }
        for i in (w / 16)..w {
            let nv = (i as f32 + 0.5) / w as f32;
            let [a, b] = ab(i, 0);
            let fc = (1.0 - nv).powi(5);
            assert!(
                (a - (1.0 - fc)).abs() < 1e-3,
                "{} n·v {nv}: A {a}",
                model.name()
            );
            assert!((b - fc).abs() < 1e-3, "{} n·v {nv}: B {b}", model.name());
        }
    }
}
