//! The `splitsum` binary end to end: outputs checked against the converged reference,
//! errors, exit codes.
mod common;

use std::path::Path;

/// The LUT's accuracy bar in float32 (and 16-bit PNG) output (docs/accuracy.md).
const LUT_TOLERANCE: f64 = 1e-4;

use common::splitsum;

/// Max |error| of a decoded LUT (row-major [A, B]) against the reference at check texels.
fn max_error(width: u32, height: u32, data: &[[f32; 2]]) -> f64 {
    common::check_texels(width, height)
        .into_iter()
        .map(|(i, j)| {
            let (nv, r) = splitsum::plan::lut::lut_texel_coords(i, j, width, height);
            let (ra, rb) = common::reference_lut(nv as f64, r as f64);
            let got = data[(j * width + i) as usize];
            (got[0] as f64 - ra).abs().max((got[1] as f64 - rb).abs())
        })
        .fold(0.0, f64::max)
}

fn read_exr_rg(path: &Path) -> (u32, u32, Vec<[f32; 2]>) {
    use exr::prelude::*;
    let image = read_first_flat_layer_from_file(path).unwrap();
    let layer = image.layer_data;
    let channel = |name: &str| -> Vec<f32> {
        let c = layer
            .channel_data
            .list
            .iter()
            .find(|c| c.name.to_string() == name)
            .unwrap();
        match &c.sample_data {
            FlatSamples::F32(v) => v.clone(),
            _ => panic!("not f32"),
        }
    };
    let (r, g) = (channel("R"), channel("G"));
    let data = r.iter().zip(&g).map(|(a, b)| [*a, *b]).collect();
    (layer.size.0 as u32, layer.size.1 as u32, data)
}

#[test]
fn lut_128_exr_meets_the_quality_bar() {
    let dir = common::output_dir("cli-exr");
    let out = dir.join("x.exr");
    let status = splitsum()
        .args(["lut", "--size", "128", "-o"])
        .arg(&out)
        .status()
        .unwrap();
    assert!(status.success());
    let (w, h, data) = read_exr_rg(&out);
    assert_eq!((w, h), (128, 128));
    let err = max_error(w, h, &data);
    println!("128 exr: max |error| {err:.2e}");
    assert!(err <= LUT_TOLERANCE, "{err}");
}

#[test]
fn default_lut_png_meets_the_quality_bar() {
    let dir = common::output_dir("cli-png");
    // Run in `dir` so the default output path out/brdf_lut.png lands there.
    let status = splitsum().arg("lut").current_dir(&dir).status().unwrap();
    assert!(status.success());
    let img = image::open(dir.join("out/brdf_lut.png"))
        .unwrap()
        .into_rgb16();
    assert_eq!(img.dimensions(), (512, 512));
    let data: Vec<[f32; 2]> = img
        .pixels()
        .map(|p| [p.0[0] as f32 / 65535.0, p.0[1] as f32 / 65535.0])
        .collect();
    let err = max_error(512, 512, &data);
    println!("512 png: max |error| {err:.2e}");
    assert!(err <= LUT_TOLERANCE, "{err}");
}

#[test]
fn lut_512_exr_cpu_backend_meets_the_quality_bar() {
    let dir = common::output_dir("cli-exr-cpu");
    let out = dir.join("lut.exr");
    let status = splitsum()
        .args(["lut", "--backend", "cpu", "-o"])
        .arg(&out)
        .status()
        .unwrap();
    assert!(status.success());
    let (w, h, data) = read_exr_rg(&out);
    let err = max_error(w, h, &data);
    println!("512 exr cpu: max |error| {err:.2e}");
    assert!(err <= LUT_TOLERANCE, "{err}");
}

#[test]
fn ktx2_f32_output_loads() {
    let dir = common::output_dir("cli-ktx2");
    let out = dir.join("lut.ktx2");
    let status = splitsum()
        .args(["lut", "--size", "64", "--f32", "-o"])
        .arg(&out)
        .status()
        .unwrap();
    assert!(status.success());
    let bytes = std::fs::read(&out).unwrap();
    let reader = ktx2::Reader::new(&bytes[..]).unwrap();
    assert_eq!(reader.header().format, Some(ktx2::Format::R32G32_SFLOAT));
    let level = reader.levels().next().unwrap();
    let data: Vec<[f32; 2]> = level
        .data
        .chunks_exact(8)
        .map(|c| {
            [
                f32::from_le_bytes(c[0..4].try_into().unwrap()),
                f32::from_le_bytes(c[4..8].try_into().unwrap()),
            ]
        })
        .collect();
    assert!(max_error(64, 64, &data) <= LUT_TOLERANCE);
}

#[test]
fn bad_extension_fails_cleanly() {
    let dir = common::output_dir("cli-bad-ext");
    let out = dir.join("lut.txt");
    let o = splitsum().args(["lut", "-o"]).arg(&out).output().unwrap();
    // A usage error: the output path names no format.
    assert_eq!(o.status.code(), Some(2));
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(err.contains("lut.txt") && err.contains("'.txt'"), "{err}");
    assert_eq!(err.lines().count(), 1, "{err}");
    assert!(!out.exists());
    assert_eq!(
        std::fs::read_dir(&dir).unwrap().count(),
        0,
        "no stray files"
    );
}

#[test]
fn usage_errors_exit_2() {
    for args in [
        &["lut", "--size", "0"][..],
        &["lut", "--bogus"],
        &["frobnicate"],
    ] {
        let o = splitsum().args(args).output().unwrap();
        assert_eq!(o.status.code(), Some(2), "{args:?}");
    }
}

#[test]
fn version_and_help() {
    let o = splitsum().arg("--version").output().unwrap();
    assert!(o.status.success());
    assert!(String::from_utf8_lossy(&o.stdout).contains(env!("CARGO_PKG_VERSION")));
    let o = splitsum().args(["lut", "--help"]).output().unwrap();
    let help = String::from_utf8_lossy(&o.stdout);
    assert!(help.contains("n·v") && help.contains("--backend"), "{help}");
}

#[test]
fn backend_gpu_without_adapter_fails_and_auto_falls_back() {
    let dir = common::output_dir("cli-no-gpu");
    let out = dir.join("lut.exr");
    let o = splitsum()
        .args(["lut", "--size", "16", "--backend", "gpu", "-o"])
        .arg(&out)
        .env(splitsum::gpu::context::HIDE_GPU_ENV, "1")
        .output()
        .unwrap();
    assert_eq!(o.status.code(), Some(1));
    assert!(String::from_utf8_lossy(&o.stderr).contains("no GPU adapter"));
    assert!(!out.exists());
    let o = splitsum()
        .args(["lut", "--size", "16", "-v", "-o"])
        .arg(&out)
        .env(splitsum::gpu::context::HIDE_GPU_ENV, "1")
        .output()
        .unwrap();
    assert!(o.status.success());
    assert!(String::from_utf8_lossy(&o.stderr).contains("backend: cpu"));
    assert!(out.exists());
}

/// `-v` names where the job's kernels run: on a software adapter `auto` bakes a LUT on the
/// CPU but fits the LTC table on the adapter (`SoftwareAdapterBackend`), and says so.
#[test]
fn verbose_names_where_each_job_runs() {
    let Some(ctx) = common::gpu() else { return };
    let adapter = ctx.adapter_info.name.clone();
    let software = ctx.adapter_info.device_type == wgpu::DeviceType::Cpu;
    drop(ctx);
    let dir = common::output_dir("cli-verbose-backend");
    let backend_line = |args: &[&str], out: &str| -> String {
        let o = splitsum()
            .args(args)
            .args(["-v", "-o"])
            .arg(dir.join(out))
            .output()
            .unwrap();
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
        let err = String::from_utf8_lossy(&o.stderr).into_owned();
        err.lines()
            .find(|l| l.starts_with("backend: "))
            .unwrap_or_else(|| panic!("no backend line in {err}"))
            .to_owned()
    };
    let lut = backend_line(&["lut", "--size", "16"], "lut.png");
    let ltc = backend_line(&["lut", "--ltc", "--size", "4"], "ltc.json");
    assert!(ltc.contains(&adapter), "{ltc}");
    if software {
        assert!(lut.starts_with("backend: cpu"), "{lut}");
    } else {
        assert!(lut.contains(&adapter), "{lut}");
    }
}

#[test]
fn cubemap_from_a_face_pattern_and_back_to_faces() {
    use splitsum::io::cubemap::{write_cubemap, CubeLayout, CubeWriteOptions};
    let dir = common::output_dir("cli-faces");
    let mut cube = splitsum::Cubemap {
        size: 8,
        levels: vec![(0..6 * 64)
            .map(|k| [1.0 + (k / 64) as f32, 0.5, 0.25, 1.0])
            .collect()],
    };
    splitsum::environment::mips::build_mips(&mut cube, 1);
    let opts = CubeWriteOptions {
        layout: CubeLayout::Faces,
        ..Default::default()
    };
    write_cubemap(&dir.join("sky.hdr"), &cube, &opts).unwrap();
    // Default output name from the pattern's stem, in out/ under the working folder.
    let status = splitsum()
        .args([
            "cubemap",
            "sky_{face}.hdr",
            "--mips",
            "--pixel-format",
            "rgb9e5",
        ])
        .current_dir(&dir)
        .status()
        .unwrap();
    assert!(status.success());
    let bytes = std::fs::read(dir.join("out/sky_cubemap.ktx2")).unwrap();
    let reader = ktx2::Reader::new(&bytes[..]).unwrap();
    assert_eq!(reader.header().face_count, 6);
    assert_eq!(reader.header().level_count, 4);
    // Each face keeps its own radiance (1 + face index in R).
    let level0 = splitsum::io::PixelFormat::Rgb9e5.decode(reader.levels().next().unwrap().data);
    for face in 0..6 {
        let r = level0[face * 64][0];
        assert!((r - (1.0 + face as f32)).abs() < 0.05, "face {face}: {r}");
    }
}

#[test]
fn output_path_problems_are_clean_errors() {
    let dir = common::output_dir("cli-output-paths");
    // The output names an existing folder.
    std::fs::create_dir_all(dir.join("taken.png")).unwrap();
    let o = splitsum()
        .args(["lut", "--size", "8", "-o"])
        .arg(dir.join("taken.png"))
        .output()
        .unwrap();
    assert_eq!(o.status.code(), Some(1));
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(err.contains("taken.png") && err.contains("folder"), "{err}");
    // A parent of the output is a file.
    std::fs::write(dir.join("file"), b"x").unwrap();
    let o = splitsum()
        .args(["lut", "--size", "8", "-o"])
        .arg(dir.join("file/lut.png"))
        .output()
        .unwrap();
    assert_eq!(o.status.code(), Some(1));
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(err.contains("file") && !err.contains("panicked"), "{err}");
    assert_eq!(err.trim_end().lines().count(), 1, "{err}");
}

/// A Charlie LUT holds values above 1 near grazing: a PNG clips them, with a warning; so
/// does Filament's DFG, whose third channel is that albedo.
#[test]
fn a_png_that_clips_the_lut_says_so() {
    let dir = common::output_dir("cli-charlie-png");
    for model in ["charlie", "filament-dfg"] {
        let lut_to = |file: &str| {
            splitsum()
                .args([
                    "lut",
                    "--model",
                    model,
                    "--size",
                    "32",
                    "--backend",
                    "cpu",
                    "-o",
                ])
                .arg(dir.join(file))
                .output()
                .unwrap()
        };
        let o = lut_to(&format!("{model}.png"));
        assert!(o.status.success());
        let err = String::from_utf8_lossy(&o.stderr);
        assert!(
            err.contains("are stored as 1 in a 16-bit PNG; write .exr or .ktx2 to keep them"),
            "{err}"
        );
        let o = lut_to(&format!("{model}.exr"));
        let err = String::from_utf8_lossy(&o.stderr);
        assert!(o.status.success() && !err.contains("warning"), "{err}");
    }
}

/// `lut --ltc` writes the LTC table as `io::ltc` reads it back, for the model's masking;
/// a sheen model, a size out of range and a format other than JSON are usage errors that
/// write nothing.
#[test]
fn lut_ltc_writes_the_table() {
    let dir = common::output_dir("cli-ltc");
    let out = dir.join("ltc.json");
    common::run_ok(
        splitsum()
            .args([
                "lut",
                "--ltc",
                "--size",
                "8",
                "--model",
                "smith-correlated",
                "-o",
            ])
            .arg(&out),
    );
    let table = splitsum::read_ltc(&out).unwrap();
    assert_eq!(table.size, 8);
    assert_eq!(
        table.brdf.masking,
        splitsum::plan::shading::Masking::SmithCorrelated
    );
    // Normal incidence (row 0): an isotropic lobe, (1, 0, 0, w), w growing with r, and
    // a magnitude A + B with F = 1 falling with r (Heitz's table: 0.307 at r = 1).
    let row: Vec<_> = table.cells[..8].to_vec();
    assert!(
        row.iter()
            .all(|c| c.inverse[0] == 1.0 && c.inverse[1].abs() < 1e-3 && c.inverse[2].abs() < 1e-3),
        "{row:?}"
    );
    assert!(
        row.windows(2)
            .all(|w| w[1].inverse[3] > w[0].inverse[3] && w[1].norm <= w[0].norm + 1e-4),
        "{row:?}"
    );
    assert!((row[7].norm - 0.307).abs() < 0.01, "{:?}", row[7]);
    for (args, what) in [
        (&["--model", "charlie"][..], "sheen"),
        (&["--size", "1"], "2 to"),
        (&["--size", "1000"], "2 to"),
    ] {
        let bad = dir.join("bad.json");
        let o = splitsum()
            .args(["lut", "--ltc"])
            .args(args)
            .arg("-o")
            .arg(&bad)
            .output()
            .unwrap();
        assert_eq!(o.status.code(), Some(2), "{args:?}");
        assert!(
            String::from_utf8_lossy(&o.stderr).contains(what),
            "{args:?}: {}",
            String::from_utf8_lossy(&o.stderr)
        );
        assert!(!bad.exists());
    }
    let o = splitsum()
        .args(["lut", "--ltc", "-o"])
        .arg(dir.join("ltc.png"))
        .output()
        .unwrap();
    assert_eq!(o.status.code(), Some(2));
    assert!(!dir.join("ltc.png").exists());
}
