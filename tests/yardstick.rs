//! The yardstick: the preview's ground truth is the environment as read, whatever the sun
//! mode, and no input the readers accept gives a figure that is not a number.
//!
//! - a deliberately wrong extraction (the light moved 2°, its energy halved) raises the
//!   preview's error, since the truth does not read the extraction;
//! - keep and split report the same per-sphere truth on quarry_01 and studio_small_03;
//! - a one-texel lamp on black: a light of its texel's size with its exact energy, every
//!   sphere at r ≥ 0.25 within 5 % with it split, the exposure that of `--sun keep`;
//! - degenerate environments generated here (all black; one texel lit; a lamp at a pole;
//!   across the seam; exactly on the horizon; two equal lamps; a tiny lamp beside a
//!   bright sky) through `inspect`, `bake --sun split` for every target, `preview` in both
//!   modes (split with the stretched lookup too) and `view --screenshot`: finite figures, a
//!   sane exposure, valid light files.

mod common;

use std::path::{Path, PathBuf};

use common::{angle_deg, direction, output_dir, run_ok, splitsum};
use splitsum::backend::CpuBackend;
use splitsum::bake::{bake_environment, BakeOptions};
use splitsum::stages::preview::{render_preview, BakedLight, SphereStats};
use splitsum::{BrdfLut, Environment, Equirect, LutModel, PreviewOptions, Sun, SunMode};

/// Width of the generated equirects: texels of 0.70°, so a one-texel lamp is far
/// narrower than the lobe of any sphere at r ≥ 0.25.
const WIDTH: u32 = 512;
const HEIGHT: u32 = WIDTH / 2;
/// The radiance of a generated lamp (a bright bulb's order against a sky of about 1).
const LAMP: f32 = 20000.0;

/// The unit direction of equirect texel (x, y) (docs/conventions.md: azimuth φ =
/// 2π (u − 0.5) from +X toward +Z, row 0 at the zenith).
fn texel_direction(x: u32, y: u32) -> [f64; 3] {
    let phi = 2.0 * std::f64::consts::PI * ((x as f64 + 0.5) / WIDTH as f64 - 0.5);
    let theta = std::f64::consts::PI * (y as f64 + 0.5) / HEIGHT as f64;
    [
        theta.sin() * phi.cos(),
        theta.cos(),
        theta.sin() * phi.sin(),
    ]
}

/// An equirect of `sky(direction)` with `lamps` (centre, radius in degrees) of [`LAMP`]
/// added.
fn generated(sky: impl Fn([f64; 3]) -> f32, lamps: &[([f64; 3], f64)]) -> Equirect {
    let mut data = Vec::with_capacity((WIDTH * HEIGHT) as usize);
    for y in 0..HEIGHT {
        for x in 0..WIDTH {
            let d = texel_direction(x, y);
            let lit = lamps.iter().any(|&(c, r)| angle_deg(d, c) <= r);
            let l = sky(d) + if lit { LAMP } else { 0.0 };
            data.push([l, l, l]);
        }
    }
    Equirect {
        width: WIDTH,
        height: HEIGHT,
        data,
    }
}

/// Black, one texel lit at (x, y).
fn one_texel(x: u32, y: u32) -> Equirect {
    let mut e = generated(|_| 0.0, &[]);
    e.data[(y * WIDTH + x) as usize] = [LAMP; 3];
    e
}

/// The degenerate environments, by name.
fn degenerate() -> Vec<(&'static str, Equirect)> {
    let sky = |d: [f64; 3]| if d[1] > 0.0 { 2.0 } else { 0.3 };
    let mut tiny = generated(sky, &[]);
    tiny.data[(HEIGHT / 4 * WIDTH + WIDTH / 3) as usize] = [LAMP * 5.0; 3];
    vec![
        ("all_black", generated(|_| 0.0, &[])),
        ("one_texel", one_texel(WIDTH / 3, HEIGHT / 3)),
        ("pole", generated(|_| 0.05, &[([0.0, 1.0, 0.0], 2.0)])),
        // Azimuth 180°: the seam, u = 0 and u = 1.
        (
            "seam",
            generated(|_| 0.05, &[(direction(180.0, 20.0), 1.5)]),
        ),
        (
            "horizon",
            generated(|_| 0.05, &[(direction(30.0, 0.0), 1.0)]),
        ),
        (
            "two_lamps",
            generated(
                |_| 0.05,
                &[(direction(60.0, 30.0), 1.0), (direction(-60.0, 30.0), 1.0)],
            ),
        ),
        ("tiny_beside_sky", tiny),
    ]
}

fn write_hdr(dir: &Path, name: &str, e: &Equirect) -> PathBuf {
    let path = dir.join(format!("{name}.hdr"));
    std::fs::write(&path, splitsum::io::hdr::encode(e.width, e.height, &e.data)).unwrap();
    path
}

fn json(bytes: &[u8]) -> serde_json::Value {
    serde_json::from_slice(bytes)
        .unwrap_or_else(|e| panic!("{e}: {}", String::from_utf8_lossy(bytes)))
}

fn read_json(path: &Path) -> serde_json::Value {
    json(&std::fs::read(path).unwrap_or_else(|e| panic!("{}: {e}", path.display())))
}

/// Every number of `v` is finite and no value is null (JSON writes NaN and infinity as
/// null), except the keys in `optional` (a sun that is absent); every solid angle and
/// angular radius of a light is positive.
fn check_figures(what: &str, v: &serde_json::Value, optional: &[&str]) {
    fn walk(what: &str, key: &str, v: &serde_json::Value, optional: &[&str]) {
        match v {
            serde_json::Value::Null => {
                assert!(optional.contains(&key), "{what}: {key} is null");
            }
            serde_json::Value::Number(n) => {
                let x = n.as_f64().unwrap();
                assert!(x.is_finite(), "{what}: {key} = {x}");
                if ["solid_angle_sr", "angular_radius_deg"].contains(&key) {
                    assert!(x > 0.0, "{what}: {key} = {x}");
                }
            }
            serde_json::Value::Array(a) => a.iter().for_each(|x| walk(what, key, x, optional)),
            serde_json::Value::Object(o) => o.iter().for_each(|(k, x)| walk(what, k, x, optional)),
            _ => {}
        }
    }
    walk(what, "", v, optional);
}

/// A bake of `env` in memory with `sun`, keeping the truth's environment, on the CPU.
fn bake(env: Equirect, sun: SunMode, specular_size: u32) -> splitsum::BakedEnvironment {
    let opts = BakeOptions {
        specular_size,
        sun,
        ground_truth: true,
        ..BakeOptions::default()
    };
    bake_environment(
        &CpuBackend,
        Environment::Equirect(env),
        &opts,
        &mut |_| {},
        &mut Vec::new(),
    )
    .unwrap()
}

/// The default model's LUT, 128² (the preview reads it bilinearly).
fn lut() -> BrdfLut {
    use splitsum::backend::Backend;
    CpuBackend
        .brdf_lut_model(128, 128, LutModel::default())
        .unwrap()
}

/// The preview options of the library tests: 32-pixel cells, 512 truth points.
fn preview_opts() -> PreviewOptions {
    PreviewOptions {
        cell: 32,
        truth_samples: 512,
        ..PreviewOptions::default()
    }
}

/// The metals' spheres at r ≥ 0.25 (the split-sum's own error is below 5 % there).
fn metals(stats: &[SphereStats]) -> Vec<&SphereStats> {
    stats
        .iter()
        .filter(|s| s.material != "dielectric" && s.roughness >= 0.25)
        .collect()
}

/// A dim sky with a 1.5° sun at elevation 35°: the preview with the sun split as found,
/// moved by 2°, and with half its energy. The truth is the same in all three; the split-sum
/// shades each extraction, and the wrong ones are further from the truth on every metal
/// sphere whose lobe the move or the halving changes (r = 0.25 and 0.5), by over twice the
/// right one's error.
#[test]
fn a_wrong_extraction_raises_the_error() {
    let sun_dir = direction(20.0, 35.0);
    let env = generated(|d| 0.5 + 0.5 * d[1].max(0.0) as f32, &[(sun_dir, 1.5)]);
    let baked = bake(env, SunMode::Split, 64);
    assert_eq!(baked.lights.len(), 1, "{:?}", baked.lights);
    let lut = lut();
    let opts = preview_opts();
    let light = BakedLight::of("sun", &baked, &lut);
    let right = render_preview(&CpuBackend, &light, &opts).unwrap();

    let mut moved = baked.lights[0];
    let d = moved.direction.map(f64::from);
    // 2° up its meridian.
    let tilted = direction(
        d[2].atan2(d[0]).to_degrees(),
        d[1].asin().to_degrees() + 2.0,
    );
    assert!((angle_deg(tilted, d) - 2.0).abs() < 1e-3);
    moved.direction = tilted.map(|x| x as f32);
    let mut halved = baked.lights[0];
    halved.irradiance = halved.irradiance.map(|e| 0.5 * e);

    for (what, wrong) in [("moved 2°", moved), ("energy halved", halved)] {
        let lights = [wrong];
        let p = render_preview(
            &CpuBackend,
            &BakedLight {
                lights: &lights,
                ..light
            },
            &opts,
        )
        .unwrap();
        for (r, w) in metals(&right.stats).into_iter().zip(metals(&p.stats)) {
            assert_eq!(
                r.truth_luminance, w.truth_luminance,
                "the truth moved with the light"
            );
            if r.roughness <= 0.5 {
                eprintln!(
                    "{what}: {} r = {}: {:.2} % → {:.2} %",
                    r.material,
                    r.roughness,
                    100.0 * r.mean_relative,
                    100.0 * w.mean_relative
                );
                assert!(
                    w.mean_relative > 2.0 * r.mean_relative && w.mean_relative > 0.02,
                    "{what}: {r:?} → {w:?}"
                );
            }
        }
    }
}

/// Keep and split report the same truth per sphere: both read the environment as read
/// (split: its background, the same conversion as keep's level 0), so they agree to
/// rounding, far inside the truth's sampling noise.
#[test]
fn keep_and_split_measure_against_the_same_truth() {
    let lut = lut();
    for name in ["quarry_01_1k.hdr", "studio_small_03_1k.hdr"] {
        let env = common::test_equirect(name);
        let [keep, split] = [SunMode::Keep, SunMode::Split].map(|mode| {
            let baked = bake(env.clone(), mode, 64);
            render_preview(
                &CpuBackend,
                &BakedLight::of(name, &baked, &lut),
                &preview_opts(),
            )
            .unwrap()
        });
        for (k, s) in keep.stats.iter().zip(&split.stats) {
            let d = (k.truth_luminance - s.truth_luminance).abs() / k.truth_luminance;
            assert!(d <= 1e-5, "{name}: {k:?} against {s:?}");
        }
        assert_eq!(keep.exposure, split.exposure, "{name}");
    }
}

/// A one-texel lamp is a light of its texel's size (a cap of its solid angle) with its
/// exact energy, at its texel's direction.
#[test]
fn a_one_texel_lamp_is_a_light_of_its_texel() {
    let (x, y) = (WIDTH / 3, HEIGHT / 3);
    let e = one_texel(x, y);
    let lights = splitsum::find_lights(&Environment::Equirect(e));
    assert_eq!(lights.len(), 1, "{lights:?}");
    let sun: Sun = lights[0];
    let theta = std::f64::consts::PI * (y as f64 + 0.5) / HEIGHT as f64;
    let (dphi, dtheta) = (
        2.0 * std::f64::consts::PI / WIDTH as f64,
        std::f64::consts::PI / HEIGHT as f64,
    );
    // The texel's exact solid angle: Δφ (cos θ0 − cos θ1).
    let omega = dphi * ((theta - dtheta / 2.0).cos() - (theta + dtheta / 2.0).cos());
    let want = LAMP as f64 * omega;
    assert!(
        ((sun.irradiance[1] as f64) - want).abs() <= 1e-4 * want,
        "{sun:?} {want}"
    );
    assert!(
        angle_deg(sun.direction.map(f64::from), texel_direction(x, y)) < 0.05,
        "{sun:?}"
    );
    let cap =
        2.0 * std::f64::consts::PI * (1.0 - (sun.angular_radius_deg as f64).to_radians().cos());
    assert!(sun.solid_angle_sr > 0.0 && (cap - sun.solid_angle_sr as f64).abs() <= 1e-3 * cap);
    assert!(
        (sun.solid_angle_sr as f64 - omega).abs() <= 1e-3 * omega,
        "{sun:?} {omega}"
    );
}

/// `preview --json` of `input` with `--sun mode` (16-pixel cells, 128 truth points: the
/// figures must be numbers, not converged).
fn preview_json(dir: &Path, input: &Path, mode: &str, extra: &[&str]) -> serde_json::Value {
    let out = dir.join(format!("preview_{mode}.json"));
    run_ok(
        splitsum()
            .arg("preview")
            .arg(input)
            .args(["--sun", mode, "--backend", "cpu", "-o"])
            .arg(dir.join(format!("preview_{mode}.png")))
            .arg("--json")
            .arg(&out)
            .args(extra),
    );
    read_json(&out)
}

/// `view INPUT --sun split --screenshot PNG` (96 × 64, on the CPU) and the share of its
/// pixels at white ([`white_share`]).
fn view_white_share(input: &Path, png: &Path) -> f64 {
    run_ok(
        splitsum()
            .arg("view")
            .arg(input)
            .args([
                "--sun",
                "split",
                "--backend",
                "cpu",
                "--size",
                "96x64",
                "--screenshot",
            ])
            .arg(png),
    );
    white_share(png)
}

/// The share of a PNG's pixels at white (every channel ≥ 250): what is blown out.
fn white_share(path: &Path) -> f64 {
    let img = image::open(path).unwrap().to_rgb8();
    let white = img
        .pixels()
        .filter(|p| p.0.iter().all(|&c| c >= 250))
        .count();
    white as f64 / (img.width() * img.height()) as f64
}

/// The done-when of the yardstick on a one-texel lamp on black (1024 × 512, as three.js's
/// spot1Lux.hdr is): with the lamp split, every sphere at r ≥ 0.25 within 5 % of the
/// truth (the residual is black; the lamp's texel is summed exactly by the truth and
/// shaded as a directional light by the split-sum), the figures finite in both modes, the
/// exposure that of `--sun keep` and the viewer's screenshot not blown out.
#[test]
fn a_one_texel_lamp_on_black_through_the_command_line() {
    let dir = output_dir("yardstick_one_texel");
    let mut e = Equirect {
        width: 1024,
        height: 512,
        data: vec![[0.0; 3]; 1024 * 512],
    };
    e.data[200 * 1024 + 300] = [26432.0; 3];
    let input = write_hdr(&dir, "lamp", &e);
    let extra = ["--preview-cell", "32", "--truth-samples", "256"];
    let split = preview_json(&dir, &input, "split", &extra);
    let keep = preview_json(&dir, &input, "keep", &extra);
    for (mode, p) in [("split", &split), ("keep", &keep)] {
        check_figures(mode, p, &[]);
    }
    let ev = |p: &serde_json::Value| p["exposure"].as_f64().unwrap().log2();
    assert!((ev(&split) - ev(&keep)).abs() <= 1.0, "{split} {keep}");
    for s in split["spheres"].as_array().unwrap() {
        if s["roughness"].as_f64().unwrap() >= 0.25 {
            assert!(s["mean"].as_f64().unwrap() <= 0.05, "{s}");
        }
    }
    let white = view_white_share(&input, &dir.join("view.png"));
    assert!(white < 0.1, "{white}: blown out");
}

/// Every degenerate environment through inspect, bake (every target, `--sun split`),
/// preview in both modes and the viewer.
#[test]
fn degenerate_environments_through_every_command() {
    let dir = output_dir("yardstick_degenerate");
    for (name, env) in degenerate() {
        let input = write_hdr(&dir, name, &env);
        let at = dir.join(name);
        std::fs::create_dir_all(&at).unwrap();

        let o = run_ok(splitsum().arg("inspect").arg(&input).arg("--json"));
        let inspect = json(&o.stdout);
        check_figures(&format!("{name}: inspect"), &inspect, &["sun"]);
        let found = inspect["sun"].is_object() as usize
            + inspect["additional_lights"]
                .as_array()
                .map_or(0, |a| a.len());
        let want = match name {
            "all_black" => 0,
            "two_lamps" => 2,
            _ => 1,
        };
        assert_eq!(found, want, "{name}: {inspect}");

        for target in ["generic", "bevy", "three", "filament", "babylon", "gltf"] {
            let out = at.join(target);
            run_ok(
                splitsum()
                    .arg("bake")
                    .arg(&input)
                    .args(["--target", target, "--sun", "split", "--backend", "cpu"])
                    .args(["--specular-size", "32", "--irradiance-size", "8", "-o"])
                    .arg(&out),
            );
            let mut lights = 0;
            for f in walk(&out) {
                if f.extension().is_some_and(|x| x == "json") {
                    let v = read_json(&f);
                    // Documented nulls: no deringing window was needed, no supercompression.
                    check_figures(
                        &format!("{name}: {}", f.display()),
                        &v,
                        &["cutoff", "zstd", "lut_size", "preview"],
                    );
                    if f.file_name().is_some_and(|n| n == "sun.json") {
                        lights += 1 + v["additional_lights"].as_array().map_or(0, |a| a.len());
                    }
                }
            }
            assert_eq!(lights, found, "{name}: {target}'s sun.json against inspect");
        }

        let extra = [
            "--preview-cell",
            "16",
            "--truth-samples",
            "128",
            "--specular-size",
            "32",
        ];
        let split = preview_json(&at, &input, "split", &extra);
        let keep = preview_json(&at, &input, "keep", &extra);
        check_figures(&format!("{name}: preview split"), &split, &["sun"]);
        check_figures(&format!("{name}: preview keep"), &keep, &["sun"]);
        // The stretched lookup's figures too (the recipe without its grazing taps).
        let stretched_dir = at.join("stretched");
        std::fs::create_dir_all(&stretched_dir).unwrap();
        let stretched = [&extra[..], &["--lookup", "stretched"]].concat();
        let stretched = preview_json(&stretched_dir, &input, "split", &stretched);
        check_figures(
            &format!("{name}: preview split --lookup stretched"),
            &stretched,
            &["sun"],
        );
        let ev = |p: &serde_json::Value| p["exposure"].as_f64().unwrap().log2();
        assert!(
            (ev(&split) - ev(&keep)).abs() <= 1.0,
            "{name}: {split} {keep}"
        );
        for p in [&split, &keep] {
            assert!(ev(p).abs() <= 40.0, "{name}: exposure {p}");
        }

        let white = view_white_share(&input, &at.join("view.png"));
        assert!(white < 0.1, "{name}: {white} of the view blown out");
    }
}

/// The files under `dir`, recursively.
fn walk(dir: &Path) -> Vec<PathBuf> {
    let mut out = Vec::new();
    for entry in std::fs::read_dir(dir).unwrap() {
        let p = entry.unwrap().path();
        if p.is_dir() {
            out.extend(walk(&p));
        } else {
            out.push(p);
        }
    }
    out
}
