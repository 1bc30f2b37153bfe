//! GPU faults in the middle of a job. A lost device must come back as
//! `Error::Gpu` naming the loss, never a panic or a hang; `bake --backend auto` then
//! finishes on the CPU with a warning and `--backend gpu` fails cleanly. The loss is real:
//! the device is destroyed (directly, or by the `SPLITSUM_LOSE_DEVICE_AT` hook in the
//! binary) and wgpu's device-lost callback and error scopes report it.
mod common;

use splitsum::environment::IrradianceSource;
use splitsum::plan::chain::SpecularChain;

use std::path::Path;
use std::process::Command;

use splitsum::backend::{Backend, GpuBackend};
use splitsum::gpu::context::LOSE_DEVICE_ENV;
use splitsum::{Cubemap, Error};

/// A grey 8² cube with its full mip chain.
fn grey_cube() -> Cubemap {
    let mut cube = Cubemap {
        size: 8,
        levels: vec![vec![[0.5, 0.5, 0.5, 1.0]; Cubemap::level_len(8)]],
    };
    splitsum::environment::mips::build_mips(&mut cube, 4);
    cube
}

/// Runs one kernel of the backend on a cube.
type KernelRun = fn(&GpuBackend, &Cubemap) -> splitsum::Result<()>;

#[test]
fn every_kernel_reports_a_lost_device() {
    let env = grey_cube();
    let kernels: [(&str, KernelRun); 3] = [
        ("brdf_lut", |b, _| b.brdf_lut(16, 16).map(drop)),
        ("prefilter_specular", |b, e| {
            b.prefilter_specular(e, None, SpecularChain::linear(e.levels.len() as u32), 16)
                .map(drop)
        }),
        ("irradiance", |b, e| {
            b.irradiance(&IrradianceSource::from_cube(e), 4).map(drop)
        }),
    ];
    for (name, run) in kernels {
        let Some(ctx) = common::gpu() else { return };
        let backend = GpuBackend { ctx };
        run(&backend, &env).unwrap();
        backend.ctx.device.destroy();
        match run(&backend, &env) {
            Err(Error::Gpu { stage, message }) => {
                assert_eq!(stage, name);
                assert!(message.contains("GPU device was lost"), "{name}: {message}");
            }
            other => panic!("{name}: expected a GPU error, got {other:?}"),
        }
    }
}

fn bake(out: &Path, backend: &str, lose_at: Option<&str>) -> std::process::Output {
    let mut cmd = Command::new(env!("CARGO_BIN_EXE_splitsum"));
    cmd.args([
        "bake",
        "--specular-size",
        "16",
        "--irradiance-size",
        "8",
        "--backend",
        backend,
        "-o",
    ])
    .arg(out)
    .arg("tests/data/venice_sunset_1k.hdr");
    if let Some(kernel) = lose_at {
        cmd.env(LOSE_DEVICE_ENV, kernel);
    }
    cmd.output().unwrap()
}

/// The device is lost before the LUT (the first GPU kernel) or before the prefilter (in
/// the middle of the bake): `auto` warns, redoes the work on the CPU and writes exactly
/// what a CPU bake writes; `gpu` exits 1 with the reason and leaves no files. On a
/// software adapter `auto` runs no bake kernel on it (only the preview's truth, see
/// `SoftwareAdapterBackend`), so there `auto` must write a CPU bake's bytes without a
/// warning, and the loss is checked with `--backend gpu` and, for `auto`, with a loss
/// before the preview's truth.
#[test]
fn bake_falls_back_to_the_cpu_when_the_device_is_lost() {
    let Some(ctx) = common::gpu() else { return };
    let software = ctx.adapter_info.device_type == wgpu::DeviceType::Cpu;
    drop(ctx);
    let dir = common::output_dir("gpu-fault-bake");
    let o = bake(&dir.join("cpu"), "cpu", None);
    assert!(o.status.success());
    let reference = dir.join("cpu/venice_sunset_1k");
    for kernel in ["brdf_lut", "prefilter_specular"] {
        let auto_runs_it_on_the_gpu = !software;
        let out = dir.join(format!("auto-{kernel}"));
        let o = bake(&out, "auto", Some(kernel));
        let err = String::from_utf8_lossy(&o.stderr);
        assert!(o.status.success(), "{kernel}: {err}");
        if auto_runs_it_on_the_gpu {
            assert!(
                err.contains("GPU device was lost")
                    && err.contains("continuing on the CPU backend"),
                "{kernel}: {err}"
            );
        }
        let files = [
            "specular.ktx2",
            "irradiance.ktx2",
            "sh.json",
            "brdf_lut.png",
        ];
        for file in &files {
            let got = std::fs::read(out.join("venice_sunset_1k").join(file)).unwrap();
            let want = std::fs::read(reference.join(file)).unwrap();
            assert!(got == want, "{kernel}: {file} differs from the CPU bake");
        }
        let manifest = std::fs::read_to_string(out.join("venice_sunset_1k/manifest.json")).unwrap();
        if auto_runs_it_on_the_gpu {
            assert!(manifest.contains("\"backend\": \"cpu"), "{manifest}");
        }

        let out = dir.join(format!("gpu-{kernel}"));
        let o = bake(&out, "gpu", Some(kernel));
        let err = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(1), "{kernel}: {err}");
        assert!(err.contains("GPU device was lost"), "{kernel}: {err}");
        assert!(!err.contains("panicked"), "{err}");
        assert!(
            !out.join("venice_sunset_1k").exists(),
            "{kernel}: partial output"
        );
    }
    if software {
        let out = dir.join("auto-preview_truth");
        let o = Command::new(env!("CARGO_BIN_EXE_splitsum"))
            .args([
                "bake",
                "--specular-size",
                "16",
                "--irradiance-size",
                "8",
                "--preview",
            ])
            .args(["--truth-samples", "16", "--preview-cell", "8", "-o"])
            .arg(&out)
            .arg("tests/data/venice_sunset_1k.hdr")
            .env(LOSE_DEVICE_ENV, "preview_truth")
            .output()
            .unwrap();
        let err = String::from_utf8_lossy(&o.stderr);
        assert!(o.status.success(), "preview_truth: {err}");
        assert!(
            err.contains("GPU device was lost") && err.contains("continuing on the CPU backend"),
            "preview_truth: {err}"
        );
        assert!(out.join("venice_sunset_1k/preview.png").is_file());
    }
}

/// On a machine whose only adapter is OpenGL (wgpu's GL backend, asked for alone with
/// `WGPU_BACKEND=gl`; Mesa's llvmpipe through EGL here), `--backend gpu` and `verify`
/// refuse the cube kernels in one line naming the adapter and what fails there, instead
/// of a raw wgpu error or wrong numbers, and `--backend auto` bakes on the CPU. Skipped
/// where no GL adapter can be opened.
#[test]
fn an_opengl_adapter_is_refused_clearly_for_the_cube_kernels() {
    let run = |args: &[&str], out: &Path| {
        Command::new(env!("CARGO_BIN_EXE_splitsum"))
            .args(args)
            .arg("-o")
            .arg(out)
            .arg("tests/data/venice_sunset_1k.hdr")
            .env("WGPU_BACKEND", "gl")
            .output()
            .unwrap()
    };
    let dir = common::output_dir("gpu-gl");
    let probe = Command::new(env!("CARGO_BIN_EXE_splitsum"))
        .args(["lut", "--size", "16", "--backend", "gpu", "-v", "-o"])
        .arg(dir.join("probe.png"))
        .env("WGPU_BACKEND", "gl")
        .output()
        .unwrap();
    let said = String::from_utf8_lossy(&probe.stderr).to_string()
        + &String::from_utf8_lossy(&probe.stdout);
    if !probe.status.success() || !said.contains("Gl,") {
        eprintln!("skipping: no OpenGL adapter ({said})");
        return;
    }
    let gpu = run(
        &[
            "bake",
            "--specular-size",
            "16",
            "--backend",
            "gpu",
            "--quiet",
        ],
        &dir.join("gpu"),
    );
    let err = String::from_utf8_lossy(&gpu.stderr);
    assert_eq!(gpu.status.code(), Some(1), "{err}");
    assert!(
        err.contains("the OpenGL adapter") && err.contains("equirect_to_cube"),
        "{err}"
    );
    assert!(
        !err.contains("ComputePipeline") && !err.contains("panicked"),
        "{err}"
    );
    assert!(!dir.join("gpu/venice_sunset_1k").exists(), "partial output");

    let verify = Command::new(env!("CARGO_BIN_EXE_splitsum"))
        .args(["verify", "tests/data/venice_sunset_1k.hdr"])
        .env("WGPU_BACKEND", "gl")
        .output()
        .unwrap();
    let err = String::from_utf8_lossy(&verify.stderr);
    assert_eq!(verify.status.code(), Some(1), "{err}");
    assert!(err.contains("the OpenGL adapter"), "{err}");

    let auto = run(
        &["bake", "--specular-size", "16", "--quiet"],
        &dir.join("auto"),
    );
    let err = String::from_utf8_lossy(&auto.stderr);
    assert!(auto.status.success(), "{err}");
    assert!(dir.join("auto/venice_sunset_1k/specular.ktx2").exists());
}
