//! The BRDF LUT against a converged reference integral computed independently in f64.
mod common;

use splitsum::cpu::brdf_lut::brdf_lut_texel;
use splitsum::lut::LutQuadrature;

/// Quality bar from DESIGN.md: max |error| ≤ 1e-4 over the grid, grazing column included.
const LUT_TOLERANCE: f64 = 1e-4;

#[test]
fn cpu_lut_matches_converged_integral() {
    let quad = LutQuadrature::default();
    for (w, h) in [(128u32, 128u32), (512, 512)] {
        let worst = common::worst_lut_error(w, h, &common::check_texels(w, h), |nv, r| {
            brdf_lut_texel(nv, r, &quad)
        });
        println!(
            "{w}x{h}: worst |error| {:.2e} at texel {:?}",
            worst.0, worst.1
        );
        assert!(worst.0 <= LUT_TOLERANCE, "{w}x{h}: {:?}", worst);
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
    let worst = common::worst_lut_error(w, h, &texels, |nv, r| brdf_lut_texel(nv, r, &quad));
    println!(
        "dense 512: worst |error| {:.2e} at texel {:?}",
        worst.0, worst.1
    );
    assert!(worst.0 <= LUT_TOLERANCE);
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
            brdf_lut_texel(nv, r, &quad)
        });
        let t = std::time::Instant::now();
        splitsum::cpu::brdf_lut::brdf_lut(w, h, &quad);
        println!(
            "full {full:2} partial {partial} phi {phi} growth {growth}: worst {:.2e} at {:?}, 512² in {:.3} s",
            worst.0,
            worst.1,
            t.elapsed().as_secs_f64()
        );
    }
}
