//! `splitsum bake` end to end: outputs, manifest, determinism, batches with failures.
mod common;

use std::path::Path;
use std::process::Command;

use common::splitsum;

use common::sha256_hex;

/// `splitsum bake` of `inputs` into `out` with small sizes, no LUT and `extra` options.
fn bake_command(inputs: &[&Path], out: &Path, extra: &[&str]) -> Command {
    let mut cmd = splitsum();
    cmd.arg("bake")
        .args(inputs)
        .arg("-o")
        .arg(out)
        .args([
            "--specular-size",
            "32",
            "--irradiance-size",
            "8",
            "--no-lut",
        ])
        .args(extra);
    cmd
}

fn bake(inputs: &[&Path], out: &Path, extra: &[&str]) -> (Option<i32>, String) {
    let o = bake_command(inputs, out, extra).output().unwrap();
    (
        o.status.code(),
        String::from_utf8_lossy(&o.stderr).into_owned(),
    )
}

#[test]
fn bake_writes_every_output_with_a_manifest() {
    let dir = common::output_dir("bake-outputs");
    let input = Path::new("tests/data/venice_sunset_1k.hdr");
    let o = splitsum()
        .args([
            "bake",
            "--specular-size",
            "64",
            "--irradiance-size",
            "16",
            "--zstd",
            "-o",
        ])
        .arg(&dir)
        .arg(input)
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let out = dir.join("venice_sunset_1k");
    let manifest = std::fs::read_to_string(out.join("manifest.json")).unwrap();
    for file in [
        "specular.ktx2",
        "irradiance.ktx2",
        "sh.json",
        "brdf_lut.png",
    ] {
        let bytes = std::fs::read(out.join(file)).unwrap();
        assert!(
            manifest.contains(&format!("\"file\": \"{file}\"")),
            "{file} missing from the manifest"
        );
        assert!(
            manifest.contains(&sha256_hex(&bytes)),
            "{file}: hash not in the manifest"
        );
        assert!(manifest.contains(&format!("\"bytes\": {}", bytes.len())));
    }
    let spec = std::fs::read(out.join("specular.ktx2")).unwrap();
    let r = ktx2::Reader::new(&spec[..]).unwrap();
    assert_eq!(
        (
            r.header().face_count,
            r.header().level_count,
            r.header().pixel_width
        ),
        // 64² down to the generic target's smallest mip, 1²: seven levels.
        (6, 7, 64)
    );
    assert_eq!(
        r.header().supercompression_scheme,
        Some(ktx2::SupercompressionScheme::Zstandard)
    );
    let sh = std::fs::read_to_string(out.join("sh.json")).unwrap();
    assert!(sh.contains("\"order\": \"l0m0,l1m-1,l1m0,l1m1,l2m-2,l2m-1,l2m0,l2m1,l2m2\""));
    let sh: serde_json::Value = serde_json::from_str(&sh).unwrap();
    for key in [
        "radiance_sh9",
        "irradiance_sh9",
        "exact_radiance_sh9",
        "exact_irradiance_sh9",
    ] {
        let list = sh[key].as_array().unwrap();
        assert!(
            list.len() == 9 && list.iter().all(|t| t.as_array().unwrap().len() == 3),
            "{key}: nine RGB triples: {sh}"
        );
    }
    assert_eq!(sh["zh3_irradiance"]["linear"].as_array().unwrap().len(), 4);
    // Nothing else (no temporaries) in the folder.
    let mut names: Vec<String> = std::fs::read_dir(&out)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    names.sort();
    assert_eq!(
        names,
        [
            "brdf_lut.png",
            "irradiance.ktx2",
            "manifest.json",
            "sh.json",
            "specular.ktx2"
        ]
    );
}

/// Two bakes give byte-identical files, manifest included, also when the second runs on
/// one thread (as on a machine with another core count: rayon splits the work, never a
/// sum).
#[test]
fn two_bakes_are_byte_identical() {
    let input = Path::new("tests/data/venice_sunset_1k.hdr");
    for backend in ["cpu", "auto"] {
        let (a, b) = (
            common::output_dir(&format!("bake-det-a-{backend}")),
            common::output_dir(&format!("bake-det-b-{backend}")),
        );
        assert_eq!(bake(&[input], &a, &["--backend", backend]).0, Some(0));
        let one_thread = bake_command(&[input], &b, &["--backend", backend])
            .env("RAYON_NUM_THREADS", "1")
            .status()
            .unwrap();
        assert!(one_thread.success());
        for file in [
            "specular.ktx2",
            "irradiance.ktx2",
            "sh.json",
            "manifest.json",
        ] {
            let x = std::fs::read(a.join("venice_sunset_1k").join(file)).unwrap();
            let y = std::fs::read(b.join("venice_sunset_1k").join(file)).unwrap();
            assert!(x == y, "{backend}: {file} differs between two bakes");
        }
    }
}

#[test]
fn a_batch_bakes_the_good_inputs_and_exits_1() {
    let dir = common::output_dir("bake-batch");
    let bad = dir.join("broken.hdr");
    std::fs::write(&bad, b"#?RADIANCE\n\n-Y 512 +X 1024\n").unwrap();
    let good = Path::new("tests/data/venice_sunset_1k.hdr");
    let (code, err) = bake(&[&bad, good], &dir.join("out"), &[]);
    assert_eq!(code, Some(1), "{err}");
    assert!(
        err.contains("broken.hdr") && err.contains("truncated"),
        "{err}"
    );
    assert!(
        dir.join("out/venice_sunset_1k/manifest.json").exists(),
        "the good input is baked"
    );
    assert!(
        !dir.join("out/broken").exists(),
        "nothing written for the bad input"
    );
}

#[test]
fn a_failed_bake_keeps_earlier_outputs() {
    let dir = common::output_dir("bake-keep");
    let input = dir.join("env.hdr");
    std::fs::copy("tests/data/venice_sunset_1k.hdr", &input).unwrap();
    assert_eq!(bake(&[&input], &dir.join("out"), &[]).0, Some(0));
    let before = std::fs::read(dir.join("out/env/specular.ktx2")).unwrap();
    // The same input name, now truncated: the bake fails and the old outputs stay.
    let bytes = std::fs::read(&input).unwrap();
    std::fs::write(&input, &bytes[..bytes.len() / 3]).unwrap();
    let (code, _) = bake(&[&input], &dir.join("out"), &[]);
    assert_eq!(code, Some(1));
    assert_eq!(
        std::fs::read(dir.join("out/env/specular.ktx2")).unwrap(),
        before
    );
    let names: Vec<String> = std::fs::read_dir(dir.join("out/env"))
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    assert!(names.iter().all(|n| !n.ends_with(".tmp")), "{names:?}");
}

/// Without an adapter (forced by SPLITSUM_NO_GPU), `auto` bakes on the CPU and says so;
/// `--backend gpu` fails cleanly before writing anything.
#[test]
fn gpu_less_fallback() {
    let dir = common::output_dir("bake-no-gpu");
    let input = Path::new("tests/data/venice_sunset_1k.hdr");
    let run = |backend: &str| {
        splitsum()
            .args([
                "bake",
                "-v",
                "--specular-size",
                "16",
                "--irradiance-size",
                "8",
                "--no-lut",
                "--backend",
                backend,
                "-o",
            ])
            .arg(dir.join(backend))
            .arg(input)
            .env(splitsum::gpu::context::HIDE_GPU_ENV, "1")
            .output()
            .unwrap()
    };
    let o = run("auto");
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(o.status.success(), "{err}");
    assert!(
        err.contains("using the CPU backend") && err.contains("backend: cpu"),
        "{err}"
    );
    assert!(dir.join("auto/venice_sunset_1k/manifest.json").exists());
    let o = run("gpu");
    assert_eq!(o.status.code(), Some(1));
    assert!(String::from_utf8_lossy(&o.stderr).contains("no GPU adapter"));
    assert!(!dir.join("gpu").exists());
}

/// Six face files given as a pattern (`sky_{face}.hdr`) bake like any other input, into
/// `<out>/sky/`, and give the same outputs as the same cube in a KTX2 container.
#[test]
fn a_face_pattern_bakes() {
    use splitsum::io::cubemap::{write_cubemap, CubeLayout, CubeWriteOptions};
    let dir = common::output_dir("bake-faces");
    // A 32² cube whose faces differ, written as faces (RGBE) and as an rgba32f KTX2.
    let mut cube = splitsum::Cubemap {
        size: 32,
        levels: vec![(0..splitsum::Cubemap::level_len(32))
            .map(|k| {
                let face = k / (32 * 32);
                [1.0 + face as f32, 0.5, 0.25 * (k % 7) as f32, 1.0]
            })
            .collect()],
    };
    splitsum::environment::mips::build_mips(&mut cube, 1);
    let faces = CubeWriteOptions {
        layout: CubeLayout::Faces,
        ..Default::default()
    };
    write_cubemap(&dir.join("sky.hdr"), &cube, &faces).unwrap();
    let pattern = dir.join("sky_{face}.hdr");
    let (code, err) = bake(&[&pattern], &dir.join("out"), &["--backend", "cpu"]);
    assert_eq!(code, Some(0), "{err}");
    let out = dir.join("out/sky");
    for file in [
        "specular.ktx2",
        "irradiance.ktx2",
        "sh.json",
        "manifest.json",
    ] {
        assert!(out.join(file).exists(), "{file}");
    }
    let manifest = std::fs::read_to_string(out.join("manifest.json")).unwrap();
    assert!(manifest.contains("sky_{face}.hdr"), "{manifest}");
    // The same cube from one file: identical SH (the faces are RGBE, so re-read them).
    let loaded = splitsum::io::input::load_input(&pattern, &Default::default()).unwrap();
    let splitsum::Environment::Cube(read_back) = loaded.env else {
        panic!("faces load as a cube");
    };
    let ktx = dir.join("same.ktx2");
    write_cubemap(
        &ktx,
        &read_back,
        &CubeWriteOptions {
            format: splitsum::io::PixelFormat::Rgba32f,
            ..Default::default()
        },
    )
    .unwrap();
    let (code, err) = bake(&[&ktx], &dir.join("out"), &["--backend", "cpu"]);
    assert_eq!(code, Some(0), "{err}");
    assert_eq!(
        std::fs::read(out.join("sh.json")).unwrap(),
        std::fs::read(dir.join("out/same/sh.json")).unwrap()
    );
}

/// Ctrl-C (SIGINT) in the middle of a bake: exit code 130, and nothing half-written in the
/// output folder (the handler removes the temporaries of a write in progress; an input
/// not yet written leaves nothing).
#[cfg(unix)]
#[test]
fn an_interrupted_bake_exits_130_and_leaves_no_partial_files() {
    let dir = common::output_dir("bake-interrupt");
    let mut child = splitsum()
        .args(["bake", "--backend", "cpu", "--specular-size", "1024", "-o"])
        .arg(&dir)
        .arg("tests/data/venice_sunset_1k.hdr")
        .stderr(std::process::Stdio::piped())
        .spawn()
        .unwrap();
    std::thread::sleep(std::time::Duration::from_millis(700));
    let killed = Command::new("kill")
        .args(["-INT", &child.id().to_string()])
        .status()
        .unwrap();
    assert!(killed.success());
    let status = child.wait().unwrap();
    assert_eq!(status.code(), Some(130), "{status}");
    let leftovers: Vec<_> = std::fs::read_dir(&dir)
        .unwrap()
        .flatten()
        .flat_map(|e| std::fs::read_dir(e.path()).into_iter().flatten().flatten())
        .map(|e| e.file_name())
        .collect();
    assert!(leftovers.is_empty(), "{leftovers:?}");
}
