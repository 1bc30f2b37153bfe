//! The BRDF LUT against a converged reference integral computed independently in f64.
mod common;

use splitsum::cpu::brdf_lut::brdf_lut_texel;
use splitsum::plan::lut::{LutModel, LutQuadrature};

/// The LUT's accuracy bar (docs/accuracy.md): max |error| ≤ 1e-4 over the grid, grazing column included.
const LUT_TOLERANCE: f64 = 1e-4;

#[test]
fn cpu_lut_matches_converged_integral() {
    for model in LutModel::singles() {
        for (w, h) in [(128u32, 128u32), (512, 512)] {
            check_both_paths(model, w, h, &common::check_texels(w, h), "spread");
        }
    }
}

/// A denser scan (every 8th texel of the 512² table, plus all edge texels); slow, so run on
/// demand: `cargo test --release --test lut_accuracy -- --ignored --nocapture`
/// (`SPLITSUM_LUT_MODELS=name,name` for some models only).
#[test]
#[ignore]
fn dense_scan_512() {
    let (w, h) = (512u32, 512u32);
    let texels = dense_texels(w, h);
    for model in LutModel::singles().filter(wanted_models) {
        check_both_paths(model, w, h, &texels, "dense");
    }
}

/// Every 8th texel is a coarse node of the CPU backend's interpolated table (steps 4 and
/// 8), so [`dense_scan_512`] sees that path only where it integrates; this scans it at the
/// same texels offset by (1, 3), which it interpolates (edges included). On demand:
/// `cargo test --release --test lut_accuracy dense_scan_512_interpolated -- --ignored
/// --nocapture` (`SPLITSUM_LUT_MODELS` as above).
#[test]
#[ignore]
fn dense_scan_512_interpolated() {
    let (w, h) = (512u32, 512u32);
    let offset: Vec<(u32, u32)> = dense_texels(w, h)
        .iter()
        .map(|&(i, j)| ((i + 1).min(w - 1), (j + 3).min(h - 1)))
        .collect();
    for model in LutModel::singles().filter(wanted_models) {
        check_interpolated(model, w, h, &offset, "dense, offset (1, 3)");
    }
}

/// Every 8th texel of a w×h table plus every edge texel.
fn dense_texels(w: u32, h: u32) -> Vec<(u32, u32)> {
    let mut texels: Vec<(u32, u32)> = (0..w)
        .step_by(8)
        .flat_map(|i| (0..h).step_by(8).map(move |j| (i, j)))
        .collect();
    for t in 0..w.min(h) {
        texels.extend([(0, t), (w - 1, t), (t, 0), (t, h - 1)]);
    }
    texels
}

/// The models `SPLITSUM_LUT_MODELS="charlie,sheen-albedo"` names (all when unset).
fn wanted_models(m: &LutModel) -> bool {
    std::env::var("SPLITSUM_LUT_MODELS")
        .ok()
        .is_none_or(|o| o.split(',').any(|n| n == m.name()))
}

/// The CPU backend's interpolated table alone against the converged reference.
fn check_interpolated(model: LutModel, w: u32, h: u32, texels: &[(u32, u32)], label: &str) {
    let quad = LutQuadrature::for_model(model);
    let table = splitsum::backend::cpu::lut_interpolation::brdf_lut(w, h, &quad, model);
    let (err, at) = common::worst_model_errors(w, h, texels, model, &[&|i, j| table.get(i, j)])[0];
    println!(
        "{} {label} {w}x{h} interpolated: worst |error| {err:.2e} at texel {at:?}",
        model.name()
    );
    assert!(
        err <= LUT_TOLERANCE,
        "{} {w}x{h}: {err:.2e} at {at:?}",
        model.name()
    );
}

/// Both ways a LUT is made, against the converged reference at `texels`: every texel
/// integrated (what the GPU kernel computes, [`brdf_lut_texel`]) and the CPU backend's
/// interpolated table (`cpu::lut_interpolation`).
fn check_both_paths(model: LutModel, w: u32, h: u32, texels: &[(u32, u32)], label: &str) {
    let quad = LutQuadrature::for_model(model);
    let table = splitsum::backend::cpu::lut_interpolation::brdf_lut(w, h, &quad, model);
    let integrated = |i, j| {
        let (nv, r) = splitsum::plan::lut::lut_texel_coords(i, j, w, h);
        brdf_lut_texel(nv, r, &quad, model)
    };
    let interpolated = |i, j| table.get(i, j);
    let worst = common::worst_model_errors(w, h, texels, model, &[&integrated, &interpolated]);
    for (path, (err, at)) in ["integrated", "interpolated"].iter().zip(&worst) {
        println!(
            "{} {label} {w}x{h} {path}: worst |error| {err:.2e} at texel {at:?}",
            model.name()
        );
        assert!(
            *err <= LUT_TOLERANCE,
            "{} {w}x{h} {path}: {err:.2e} at {at:?}",
            model.name()
        );
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
        splitsum::backend::cpu::lut_interpolation::brdf_lut(w, h, &quad, LutModel::SchlickGgx);
        println!(
            "full {full:2} partial {partial} phi {phi} growth {growth}: worst {:.2e} at {:?}, 512² in {:.3} s",
            worst.0,
            worst.1,
            t.elapsed().as_secs_f64()
        );
    }
}

/// Furnace-style identities, every GGX model (the Charlie sheen: 0 ≤ E ≤ 1, E → 0 at r → 0): A + B = ∫ V' (the directional albedo with F = 1)
/// never exceeds 1 (single scattering loses energy, never gains it), and for a mirror
/// (row 0, r = 1/1024) h = n, so A = 1 − (1 − n·v)⁵ and B = (1 − n·v)⁵ exactly
/// (1e-3: the row's r is not 0, and the lobe spreads by α = 1e-6 there).
#[test]
fn every_model_keeps_the_albedo_identities() {
    let (w, h) = (64u32, 512u32);
    for model in LutModel::singles() {
        let quad = LutQuadrature::for_model(model);
        let lut = splitsum::backend::cpu::lut_interpolation::brdf_lut(w, h, &quad, model);
        if model.distribution() == splitsum::plan::lut::LutDistribution::Charlie {
            // Sheen: E ≥ 0 and finite (not ≤ 1: the Ashikhmin visibility is not derived
            // from the Charlie distribution, and E reaches 22 at grazing n·v and small r),
            // and a mirror's Charlie D lies flat at θh = π/2, where every reflection is
            // below the horizon unless the view grazes: E → 0 at r → 0 for n·v ≥ ¼.
            for (i, j) in (0..w).flat_map(|i| (0..h).step_by(7).map(move |j| (i, j))) {
                let e = lut.get(i, j)[0];
                assert!(e.is_finite() && e >= 0.0, "charlie ({i}, {j}): {e}");
            }
            assert!(
                (w / 4..w).all(|i| lut.get(i, 0)[0] < 1e-3),
                "{}",
                model.name()
            );
            continue;
        }
        // Back to (A, B) whatever the layout.
        let ab = |i: u32, j: u32| {
            let v = lut.get(i, j);
            match model.layout() {
                splitsum::plan::lut::LutLayout::ScaleBias => v,
                splitsum::plan::lut::LutLayout::Multiscatter => [v[1] - v[0], v[0]],
                splitsum::plan::lut::LutLayout::Albedo => unreachable!("only the Charlie models"),
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
                assert!(a >= 0.0 && b >= 0.0, "{} ({i}, {j}): {a} {b}", model.name());
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

/// Filament's DFG as cmgen writes it (`--ibl-dfg`, 1024 Hammersley samples per texel),
/// against splitsum's model of the same definition and against the converged reference:
/// single scattering (R, G), multiple scattering (R, G) and, with `--ibl-dfg-cloth`, the
/// three-channel file whose B is the cloth albedo (`filament-dfg`'s B, the `charlie`
/// model). cmgen (Debian `libfilament-tools`) is not a dependency, so this runs on demand
/// where it is installed: `cargo test --release --test lut_accuracy filament_dfg --
/// --ignored --nocapture`. cmgen's row y of an h-row table holds roughness
/// min(1, (h − y + ½)/h) (CubemapIBL.cpp `DFG`), n·v = (x + ½)/w, and α = roughness².
#[test]
#[ignore]
fn filament_dfg_against_cmgen() {
    use exr::prelude::*;
    let Ok(cmgen) = common::which_cmgen() else {
        common::skip_peer("cmgen not found");
        return;
    };
    let dir = common::output_dir("lut-cmgen");
    let n = 128usize;
    // (file, cmgen flags, which channels against which model)
    type Run<'a> = (&'a str, &'a [&'a str], &'a [(LutModel, [usize; 2])]);
    let runs: [Run; 3] = [
        ("single", &[], &[(LutModel::SmithCorrelated, [0, 1])]),
        (
            "multiscatter",
            &["--ibl-dfg-multiscatter"],
            &[(LutModel::MultiscatterSmithCorrelated, [0, 1])],
        ),
        (
            "filament-dfg",
            &["--ibl-dfg-multiscatter", "--ibl-dfg-cloth"],
            &[
                (LutModel::MultiscatterSmithCorrelated, [0, 1]),
                (LutModel::Charlie, [2, 3]),
            ],
        ),
    ];
    for (name, flags, checks) in runs {
        let path = dir.join(format!("{name}.exr"));
        let mut cmd = std::process::Command::new(&cmgen);
        cmd.arg(format!("--ibl-dfg={}", path.display()))
            .arg(format!("--size={n}"))
            .args(flags);
        assert!(cmd.output().unwrap().status.success());
        // R, G, B and a 0 that stands for the Charlie model's empty second channel.
        let image = read_first_rgba_layer_from_file(
            &path,
            |res, _| vec![[0f32; 4]; res.width() * res.height()],
            move |px: &mut Vec<[f32; 4]>, pos, (r, g, b, _a): (f32, f32, f32, f32)| {
                px[pos.y() * n + pos.x()] = [r, g, b, 0.0];
            },
        )
        .unwrap();
        let data = image.layer_data.channel_data.pixels;
        for &(model, [c0, c1]) in checks {
            let texels = (0..n).step_by(3).flat_map(|y| {
                let r = (((n - y) as f32 + 0.5) / n as f32).min(1.0);
                let data = &data;
                (0..n).step_by(3).map(move |x| {
                    let t = data[y * n + x];
                    ((x as f32 + 0.5) / n as f32, r, [t[c0], t[c1]])
                })
            });
            let (vs_ours, vs_ref, ours_vs_ref) = peer_errors(model, texels);
            println!(
                "cmgen {name}, channels {c0} {c1} as {}: cmgen vs splitsum max |Δ| {vs_ours:.2e}, cmgen vs converged {vs_ref:.2e}, splitsum vs converged {ours_vs_ref:.2e}",
                model.name()
            );
            // Matching the peer to its own accuracy: the two differ by no more than
            // cmgen's own error plus splitsum's.
            assert!(vs_ours <= vs_ref + ours_vs_ref + 1e-6);
        }
    }
}

/// Max |Δ| of a peer's LUT values (n·v, r, [x, y]) against splitsum's `model`, of the
/// peer against the converged reference, and of splitsum against it.
fn peer_errors(
    model: LutModel,
    texels: impl Iterator<Item = (f32, f32, [f32; 2])>,
) -> (f64, f64, f64) {
    let quad = LutQuadrature::for_model(model);
    let (mut vs_ours, mut vs_ref, mut ours_vs_ref) = (0.0f64, 0.0f64, 0.0f64);
    for (nv, r, theirs) in texels {
        let ours = brdf_lut_texel(nv, r, &quad, model);
        let (ra, rb) = common::reference_lut_model(nv as f64, r as f64, model);
        for c in 0..2 {
            let reference = [ra, rb][c];
            vs_ours = vs_ours.max((theirs[c] - ours[c]).abs() as f64);
            vs_ref = vs_ref.max((theirs[c] as f64 - reference).abs());
            ours_vs_ref = ours_vs_ref.max((ours[c] as f64 - reference).abs());
        }
    }
    (vs_ours, vs_ref, ours_vs_ref)
}

/// three.js r187's DFG (`src/renderers/shaders/DFGLUTData.js`: 16×16 RG16F, 4096 samples per
/// texel, sampled at uv = (roughness, n·v), so texel (i, j) holds r = (i + ½)/16 and
/// n·v = (j + ½)/16) against splitsum's `smith-correlated` model and the converged reference.
/// Runs where `engines/three` has its npm packages (`npm ci`): `cargo test --release --test
/// lut_accuracy three_dfg -- --ignored --nocapture`.
#[test]
#[ignore]
fn three_dfg_against_splitsum() {
    let path = "engines/three/node_modules/three/src/renderers/shaders/DFGLUTData.js";
    let Ok(js) = std::fs::read_to_string(path) else {
        common::skip_peer(&format!("{path} not found (npm ci in engines/three)"));
        return;
    };
    let start = js.find("new Uint16Array( [").expect("the DATA array");
    let end = start + js[start..].find("] )").unwrap();
    let halves: Vec<f32> = js[start..end]
        .split([',', '['])
        .filter_map(|t| t.trim().strip_prefix("0x"))
        .map(|h| half::f16::from_bits(u16::from_str_radix(h, 16).unwrap()).to_f32())
        .collect();
    assert_eq!(halves.len(), 16 * 16 * 2);
    let texels = (0..16).flat_map(|j| {
        let halves = &halves;
        (0..16).map(move |i| {
            let (r, nv) = ((i as f32 + 0.5) / 16.0, (j as f32 + 0.5) / 16.0);
            let k = 2 * (j * 16 + i);
            (nv, r, [halves[k], halves[k + 1]])
        })
    });
    let (vs_ours, vs_ref, ours_vs_ref) = peer_errors(LutModel::SmithCorrelated, texels);
    println!(
        "three.js DFG vs splitsum smith-correlated max |Δ| {vs_ours:.2e}, three vs converged {vs_ref:.2e}, splitsum vs converged {ours_vs_ref:.2e}"
    );
    assert!(vs_ours <= vs_ref + ours_vs_ref + 1e-6);
}

/// The CPU backend's interpolated LUT against integrating every texel, at every texel of
/// every model. Bound 2.5e-5 (relative to max(1, value)): the cells' check tolerance of
/// 1e-5, plus the quadrature's own texel-to-texel steps (its panel count changes with n·v,
/// by up to about 1e-5), which integrated texels show and an interpolant smooths over;
/// measured worst 1.8e-5. The total against the converged reference is checked by
/// `check_both_paths`. Sizes include odd ones whose last coarse gap is short.
#[test]
fn interpolated_lut_matches_every_texel_integrated() {
    for model in LutModel::singles() {
        let quad = LutQuadrature::for_model(model);
        for (w, h) in [(512u32, 512u32), (301, 203), (16, 16)] {
            let t = std::time::Instant::now();
            let fast =
                splitsum::backend::cpu::lut_interpolation::interpolated_lut(w, h, &quad, model);
            let fast_s = t.elapsed().as_secs_f64();
            let t = std::time::Instant::now();
            let exact = splitsum::cpu::brdf_lut::brdf_lut_exact(w, h, &quad, model);
            let exact_s = t.elapsed().as_secs_f64();
            let mut worst = (0.0f32, 0usize);
            for (k, (a, b)) in fast.lut.data.iter().zip(&exact.data).enumerate() {
                for c in 0..2 {
                    let e = (a[c] - b[c]).abs() / b[c].abs().max(1.0);
                    if e > worst.0 {
                        worst = (e, k);
                    }
                }
            }
            println!(
                "{} {w}x{h}: worst {:.2e} at texel ({}, {}); {:.1} % integrated; {fast_s:.3} s vs {exact_s:.3} s",
                model.name(),
                worst.0,
                worst.1 % w as usize,
                worst.1 / w as usize,
                100.0 * fast.integrated as f64 / (w * h) as f64
            );
            assert!(worst.0 <= 2.5e-5, "{} {w}x{h}: {worst:?}", model.name());
        }
    }
}

/// The glTF Sample Viewer's LUTs, as its own shader computes them (`engines/gltf/luts.mjs`
/// runs npm @khronosgroup/gltf-viewer 1.1.0's `ibl_filtering.frag`, its port of
/// glTF-IBL-Sampler's filter shader, in headless Chromium: 512 Hammersley samples a texel,
/// uv = (n·v, roughness), here at 128²). `lut_ggx` (R, G) is the height-correlated
/// (A, B), so it is held to splitsum's `smith-correlated` as the other peers are.
/// `lut_charlie` (B) is not an estimate of ∫ D V (n·l) dl: its samples are drawn from the
/// Charlie distribution with α = r² (sin θh = ξ^(α/(2α+1)), pdf D_α cos θh) but weighted
/// as if uniform over the hemisphere (8π V D (n·l)(v·h) / N, no division by the pdf), its D
/// takes α = r, and its Ashikhmin V is clamped to 1. So it is held to the expectation of
/// that estimator instead (a 1024 × 256 midpoint sum over the same sample square, f64),
/// and its distance from the Charlie albedo that `charlie` (Filament's cloth channel)
/// integrates is reported. Runs after `npm ci && node luts.mjs` in `engines/gltf`:
/// `cargo test --release --test lut_accuracy gltf_viewer -- --ignored --nocapture`.
#[test]
#[ignore]
fn gltf_viewer_luts_against_splitsum() {
    let dir = std::path::Path::new("target/engines/gltf");
    let read = |name: &str| -> Option<Vec<f32>> {
        let bytes = std::fs::read(dir.join(format!("{name}.f32"))).ok()?;
        Some(
            bytes
                .chunks_exact(4)
                .map(|c| f32::from_le_bytes(c.try_into().unwrap()))
                .collect(),
        )
    };
    let (Some(ggx), Some(charlie)) = (read("lut_ggx"), read("lut_charlie")) else {
        common::skip_peer(
            "target/engines/gltf/*.f32 not found (cd engines/gltf && npm ci && node luts.mjs)",
        );
        return;
    };
    let n = 128usize;
    assert_eq!(ggx.len(), n * n * 4);
    let at = |i: usize, j: usize| ((i as f32 + 0.5) / n as f32, (j as f32 + 0.5) / n as f32);
    let texels = (0..n).step_by(3).flat_map(|j| {
        let ggx = &ggx;
        (0..n).step_by(3).map(move |i| {
            let (nv, r) = at(i, j);
            let k = 4 * (j * n + i);
            (nv, r, [ggx[k], ggx[k + 1]])
        })
    });
    let (vs_ours, vs_ref, ours_vs_ref) = peer_errors(LutModel::SmithCorrelated, texels);
    println!(
        "glTF viewer lut_ggx vs splitsum smith-correlated max |Δ| {vs_ours:.2e}, viewer vs converged {vs_ref:.2e}, splitsum vs converged {ours_vs_ref:.2e}"
    );
    assert!(vs_ours <= vs_ref + ours_vs_ref + 1e-6);

    // lut_charlie against the expectation of its own estimator, and against the albedo.
    let quad = LutQuadrature::for_model(LutModel::Charlie);
    let (mut vs_expectation, mut vs_albedo, mut largest) = (0.0f64, 0.0f64, 0.0f64);
    // Row 0 (r = 1/256) is left out: there α = 1.5e-5 and the sampled sin θh = ξ^1.5e-5
    // rounds to 1 in f32, so the shader's value is decided by rounding (0.042 at
    // n·v = 0.074, where the estimator's expectation is 0).
    for j in (9..n).step_by(9) {
        for i in (0..n).step_by(9) {
            let (nv, r) = at(i, j);
            let viewer = charlie[4 * (j * n + i) + 2] as f64;
            let expect = viewer_charlie_expectation(nv as f64, r as f64);
            let albedo = brdf_lut_texel(nv, r, &quad, LutModel::Charlie)[0] as f64;
            vs_expectation = vs_expectation.max((viewer - expect).abs() / expect.abs().max(1.0));
            vs_albedo = vs_albedo.max((viewer - albedo).abs() / albedo.abs().max(1.0));
            largest = largest.max(viewer);
        }
    }
    println!(
        "glTF viewer lut_charlie (B, largest {largest:.3}): vs its estimator's expectation {vs_expectation:.2e}, vs the Charlie albedo (splitsum charlie) {vs_albedo:.2e} (relative to max(1, value))"
    );
    // 512 Hammersley points over a smooth integrand: a few 1e-3; the bar leaves room for
    // the midpoint sum's own error at the horizon kink.
    assert!(vs_expectation <= 2e-2, "{vs_expectation}");
}

/// The expectation of `ibl_filtering.frag`'s Charlie `LUT()` estimator at (n·v, r): the
/// mean over its sample square (ξ.x → φ = 2π ξ.x, ξ.y → sin θh = ξ.y^(α/(2α+1)), α = r²)
/// of 8π · V_Ashikhmin(n·l, n·v) (clamped to [0, 1]) · D_Charlie(r, n·h) · (n·l) · (v·h),
/// where its D_Charlie takes r itself as α; n·l, n·h, v·h saturated, n·l ≤ 0 adding 0.
fn viewer_charlie_expectation(n_dot_v: f64, r: f64) -> f64 {
    use std::f64::consts::PI;
    let alpha = r * r;
    let v = [(1.0 - n_dot_v * n_dot_v).max(0.0).sqrt(), 0.0, n_dot_v];
    let d_charlie = |rough: f64, n_dot_h: f64| {
        let rough = rough.max(1e-6);
        let inv = 1.0 / rough;
        let sin2 = 1.0 - n_dot_h * n_dot_h;
        (2.0 + inv) * sin2.max(0.0).powf(inv * 0.5) / (2.0 * PI)
    };
    let (nu, nphi) = (1024usize, 256usize);
    let mut sum = 0.0;
    for a in 0..nu {
        let xi_y = (a as f64 + 0.5) / nu as f64;
        let sin_t = xi_y.powf(alpha / (2.0 * alpha + 1.0));
        let cos_t = (1.0 - sin_t * sin_t).max(0.0).sqrt();
        for b in 0..nphi {
            let phi = 2.0 * PI * (b as f64 + 0.5) / nphi as f64;
            let h = [sin_t * phi.cos(), sin_t * phi.sin(), cos_t];
            let v_dot_h = v[0] * h[0] + v[2] * h[2];
            let l = [
                2.0 * v_dot_h * h[0] - v[0],
                2.0 * v_dot_h * h[1],
                2.0 * v_dot_h * h[2] - v[2],
            ];
            let n_dot_l = l[2].clamp(0.0, 1.0);
            if n_dot_l > 0.0 {
                let vis = (1.0 / (4.0 * (n_dot_l + n_dot_v - n_dot_l * n_dot_v))).clamp(0.0, 1.0);
                sum +=
                    vis * d_charlie(r, cos_t.clamp(0.0, 1.0)) * n_dot_l * v_dot_h.clamp(0.0, 1.0);
            }
        }
    }
    8.0 * PI * sum / (nu * nphi) as f64
}
