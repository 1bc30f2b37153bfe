//! The diffuse light a target gets, against the brute-force irradiance of the whole
//! environment at its full resolution: with the sun split, the residual's SH9 and its
//! irradiance cube plus the lights' exact irradiance; in both modes, SH that never goes
//! negative; ZH3 against linear SH.

mod common;

use std::collections::HashMap;
use std::sync::{Arc, Mutex, OnceLock};

use splitsum::environment::Environment;
use splitsum::math::sh::{sh_eval, zh3_eval};
use splitsum::{BackendChoice, BakeOptions, BakedEnvironment, Baker, Equirect, SunMode};

use common::{brute_force_irradiance, light_irradiance, test_equirect, uniform_directions};

/// The bakes made so far, by HDRI name and sun mode.
type Bakes = HashMap<(String, &'static str), Arc<BakedEnvironment>>;

/// The default CPU bake of the bundled HDRI `name` with `sun`, made once for all the tests
/// of this file (they ask for 26 bakes of 14 kinds).
fn bake(name: &str, e: &Equirect, sun: SunMode) -> Arc<BakedEnvironment> {
    static BAKES: OnceLock<Mutex<Bakes>> = OnceLock::new();
    let key = (name.to_string(), sun.name());
    let bakes = BAKES.get_or_init(Default::default);
    if let Some(done) = bakes.lock().unwrap().get(&key) {
        return done.clone();
    }
    let mut baker = Baker::new(BakeOptions {
        backend: BackendChoice::Cpu,
        sun,
        ..BakeOptions::default()
    })
    .unwrap();
    let baked = Arc::new(
        baker
            .bake_environment(Environment::Equirect(e.clone()))
            .unwrap(),
    );
    bakes.lock().unwrap().insert(key, baked.clone());
    baked
}

fn luminance(c: [f64; 3]) -> f64 {
    common::luminance(c)
}

/// π × E/π of 9 coefficients at d.
fn sh_irradiance(c: &[[f32; 3]; 9], d: [f64; 3]) -> [f64; 3] {
    sh_eval(c, d.map(|v| v as f32)).map(|v| std::f64::consts::PI * f64::from(v))
}

/// RMS of the luminance difference over the mean luminance of `truth`.
fn rms_relative(got: &[[f64; 3]], truth: &[[f64; 3]]) -> f64 {
    let mean = truth.iter().map(|t| luminance(*t)).sum::<f64>() / truth.len() as f64;
    let sq = got
        .iter()
        .zip(truth)
        .map(|(g, t)| (luminance(*g) - luminance(*t)).powi(2))
        .sum::<f64>()
        / truth.len() as f64;
    sq.sqrt() / mean
}

#[test]
fn split_sh_plus_the_lights_match_the_brute_force_irradiance() {
    // With the sun (and the brightest lamps) split, π × the residual's SH9 irradiance plus
    // the lights' exact irradiance at 1000 directions is within 2 % RMS (relative to the
    // mean) of the brute-force irradiance: the residual is smooth enough for nine
    // coefficients. The SH9 of the whole environment is printed beside it.
    let normals = uniform_directions(1000, 5);
    for name in ["quarry_01_1k.hdr", "royal_esplanade_1k.hdr"] {
        let e = test_equirect(name);
        let truth = brute_force_irradiance(&e, &normals);
        let whole = bake(name, &e, SunMode::Keep);
        let split = bake(name, &e, SunMode::Split);
        assert!(!split.lights.is_empty(), "{name}: no sun");
        let (sh_keep, sh_split) = (whole.sh.clone().unwrap(), split.sh.clone().unwrap());
        let keep: Vec<[f64; 3]> = normals
            .iter()
            .map(|&n| sh_irradiance(&sh_keep.exact_irradiance, n))
            .collect();
        let with_lights: Vec<[f64; 3]> = normals
            .iter()
            .map(|&n| {
                let mut e = sh_irradiance(&sh_split.irradiance, n);
                for light in &split.lights {
                    let l = light_irradiance(light, n);
                    (0..3).for_each(|c| e[c] += l[c]);
                }
                e
            })
            .collect();
        let (rms_keep, rms_split) = (
            rms_relative(&keep, &truth),
            rms_relative(&with_lights, &truth),
        );
        eprintln!(
            "{name}: SH9 of the whole environment {:.2} % RMS, residual SH9 + lights {:.2} %",
            100.0 * rms_keep,
            100.0 * rms_split
        );
        assert!(rms_split <= 0.02, "{name}: {:.2} % RMS", 100.0 * rms_split);
    }
}

#[test]
fn the_split_irradiance_cube_plus_the_lights_is_the_whole_irradiance() {
    // π × the residual's baked irradiance cube plus the lights' exact irradiance, at every
    // third of the cube's 6 × 32² texel centres (2048 normals, each a brute-force sum over
    // the 524 288 source texels), equals the brute-force irradiance of the whole
    // environment within 0.5 % (the irradiance kernel's own accuracy is 0.2 %,
    // docs/accuracy.md).
    for name in [
        "quarry_01_1k.hdr",
        "royal_esplanade_1k.hdr",
        "blender_studiolight_interior.exr",
    ] {
        let e = test_equirect(name);
        let split = bake(name, &e, SunMode::Split);
        let cube = &split.irradiance;
        let n = cube.size;
        let mut normals = Vec::new();
        let mut baked = Vec::new();
        for (face, i, j, d) in splitsum::environment::walk::texel_centres(n).step_by(3) {
            normals.push(d.map(f64::from));
            let t = cube.texel(0, face, i, j);
            baked.push([t[0], t[1], t[2]].map(|v| std::f64::consts::PI * f64::from(v)));
        }
        let truth = brute_force_irradiance(&e, &normals);
        let mut worst: f64 = 0.0;
        for (k, n) in normals.iter().enumerate() {
            let mut got = baked[k];
            for light in &split.lights {
                let l = light_irradiance(light, *n);
                (0..3).for_each(|c| got[c] += l[c]);
            }
            for c in 0..3 {
                worst = worst.max((got[c] / truth[k][c] - 1.0).abs());
            }
        }
        eprintln!(
            "{name}: worst {:.3} % at {} normals",
            100.0 * worst,
            normals.len()
        );
        assert!(worst <= 0.005, "{name}: {:.3} %", 100.0 * worst);
    }
}

#[test]
fn the_sh_a_target_uses_is_never_negative() {
    // At 10 000 directions (not the deringing search's own), in both modes, on every
    // bundled HDRI: E/π ≥ −1e-4 × its mean in every channel, and the window keeps the
    // mean (band 0).
    let dirs = uniform_directions(10_000, 11);
    for name in common::BUNDLED_HDRIS {
        let e = test_equirect(name);
        for mode in [SunMode::Keep, SunMode::Split] {
            let sh = bake(name, &e, mode).sh.clone().unwrap();
            assert_eq!(sh.irradiance[0], sh.exact_irradiance[0], "{name}");
            for c in 0..3 {
                let mean =
                    f64::from(sh.irradiance[0][c]) * 0.5 * (1.0 / std::f64::consts::PI).sqrt();
                let low = dirs
                    .iter()
                    .map(|&d| f64::from(sh_eval(&sh.irradiance, d.map(|v| v as f32))[c]))
                    .fold(f64::INFINITY, f64::min);
                assert!(
                    low >= -1e-4 * mean,
                    "{name} {}: channel {c} down to {:.3e} of its mean (window {:?})",
                    mode.name(),
                    low / mean,
                    sh.window_cutoff
                );
            }
        }
    }
}

#[test]
fn zh3_is_at_least_as_good_as_linear_sh() {
    // ZH3's irradiance against brute force, RMS over 1000 directions, on every bundled HDRI
    // with its sun kept: at most linear SH's (bands 0 and 1 of the same projection).
    let normals = uniform_directions(1000, 3);
    for name in common::BUNDLED_HDRIS {
        let e = test_equirect(name);
        let truth = brute_force_irradiance(&e, &normals);
        let sh = bake(name, &e, SunMode::Keep).sh.clone().unwrap();
        let mut linear = sh.exact_irradiance;
        linear[4..].iter_mut().for_each(|c| *c = [0.0; 3]);
        let zh3: Vec<[f64; 3]> = normals
            .iter()
            .map(|&n| {
                zh3_eval(&sh.zh3_irradiance, n.map(|v| v as f32))
                    .map(|v| std::f64::consts::PI * f64::from(v))
            })
            .collect();
        let l1: Vec<[f64; 3]> = normals.iter().map(|&n| sh_irradiance(&linear, n)).collect();
        let sh9: Vec<[f64; 3]> = normals
            .iter()
            .map(|&n| sh_irradiance(&sh.exact_irradiance, n))
            .collect();
        let (z, l, s) = (
            rms_relative(&zh3, &truth),
            rms_relative(&l1, &truth),
            rms_relative(&sh9, &truth),
        );
        eprintln!(
            "{name}: RMS linear SH {:.2} %, ZH3 {:.2} %, SH9 {:.2} %",
            100.0 * l,
            100.0 * z,
            100.0 * s
        );
        assert!(
            z <= l,
            "{name}: ZH3 {:.3} % > linear {:.3} %",
            100.0 * z,
            100.0 * l
        );
    }
}
