//! The `splitsum` binary: parse, call the library, print errors with their chain, map
//! them to exit codes (0 ok, 1 a job failed, 2 usage error; clap exits 2 by itself).

mod cli;

use std::process::ExitCode;
use std::time::Instant;

use anyhow::Context;
use clap::Parser;

use cli::{Cli, Command, CommonArgs, CubemapArgs, LutArgs};
use splitsum::io::lut::{check_lut_path, write_lut, LutWriteOptions};

fn main() -> ExitCode {
    let cli = Cli::parse();
    quiet_vulkan_loader();
    let result = match cli.command {
        Command::Lut(args) => run_lut(args),
        Command::Cubemap(args) => run_cubemap(args),
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("error: {e:#}");
            ExitCode::from(1)
        }
    }
}

/// The Vulkan loader prints "error: XDG_RUNTIME_DIR is invalid or not set" on headless
/// machines; it is harmless but reads like a splitsum failure. Point the variable at a
/// private folder when it is missing (before any thread starts).
fn quiet_vulkan_loader() {
    #[cfg(unix)]
    if std::env::var_os("XDG_RUNTIME_DIR").is_none() {
        use std::os::unix::fs::{DirBuilderExt, MetadataExt, PermissionsExt};
        let Ok(uid) = std::fs::metadata("/proc/self").map(|m| m.uid()) else {
            return;
        };
        let dir = std::env::temp_dir().join(format!("splitsum-runtime-{uid}"));
        let _ = std::fs::DirBuilder::new().mode(0o700).create(&dir);
        // Use it only if it is ours and private.
        if let Ok(m) = std::fs::symlink_metadata(&dir) {
            if m.is_dir() && m.uid() == uid && m.permissions().mode() & 0o777 == 0o700 {
                std::env::set_var("XDG_RUNTIME_DIR", &dir);
            }
        }
    }
}

/// Opens the backend the user chose, printing the fallback note and, with -v, which one.
fn open_backend(common: &CommonArgs) -> anyhow::Result<Box<dyn splitsum::Backend>> {
    let (backend, note) = splitsum::create_backend(common.backend.into())?;
    if let Some(note) = note {
        eprintln!("note: {note}");
    }
    if common.verbose {
        eprintln!("backend: {}", backend.description());
    }
    Ok(backend)
}

fn run_cubemap(args: CubemapArgs) -> anyhow::Result<()> {
    use splitsum::io::cubemap::{check_cube_path, write_cubemap, CubeWriteOptions};
    use splitsum::io::input::{load_environment, load_faces, InputOptions};
    let first_input = args
        .input
        .clone()
        .or_else(|| args.faces.first().cloned())
        .unwrap_or_default();
    let output = args.output.clone().unwrap_or_else(|| {
        let stem = first_input
            .to_string_lossy()
            .replace(splitsum::io::input::FACE_PLACEHOLDER, "")
            .parse::<std::path::PathBuf>()
            .unwrap_or_default()
            .file_stem()
            .map(|s| {
                s.to_string_lossy()
                    .trim_end_matches(['_', '-', '.'])
                    .to_owned()
            })
            .unwrap_or_default();
        std::path::PathBuf::from("out").join(format!("{stem}_cubemap.ktx2"))
    });
    check_cube_path(&output)?;
    if let Some(size) = args.size {
        splitsum::convert::validate_cube_size(size)?;
    }
    let opts = InputOptions {
        exposure_ev: args.input_opts.exposure,
    };
    let start = Instant::now();
    let loaded = match &args.input {
        Some(path) => match splitsum::io::input::expand_face_pattern(path) {
            Some(faces) => load_faces(&faces, &opts)?,
            None => load_environment(path, &opts)?,
        },
        None => load_faces(&args.faces, &opts)?,
    };
    for w in &loaded.warnings {
        eprintln!("warning: {w}");
    }
    if args.common.verbose {
        eprintln!(
            "read {}: {:.3} s",
            first_input.display(),
            start.elapsed().as_secs_f64()
        );
    }
    let size = args
        .size
        .unwrap_or_else(|| splitsum::convert::default_cube_size(&loaded.env));
    let backend = open_backend(&args.common)?;
    let start = Instant::now();
    let cube = splitsum::convert::environment_to_cube(
        backend.as_ref(),
        &loaded.env,
        size,
        args.mips,
        args.input_opts.rotate,
    )
    .context("converting to a cubemap")?;
    if args.common.verbose {
        eprintln!(
            "cubemap {size}, {} levels: {:.3} s",
            cube.levels.len(),
            start.elapsed().as_secs_f64()
        );
    }
    let written = write_cubemap(
        &output,
        &cube,
        &CubeWriteOptions {
            format: args.pixel_format.into(),
            zstd: args.zstd,
            layout: args.layout.into(),
        },
    )?;
    if args.common.verbose {
        for p in written {
            eprintln!("wrote {}", p.display());
        }
    }
    Ok(())
}

fn run_lut(args: LutArgs) -> anyhow::Result<()> {
    check_lut_path(&args.output)?;
    splitsum::lut::validate_lut_size(args.size, args.size)?;
    let backend = open_backend(&args.common)?;
    let start = Instant::now();
    let lut = backend
        .brdf_lut(args.size, args.size)
        .context("computing the BRDF LUT")?;
    if args.common.verbose {
        eprintln!(
            "brdf lut {0}x{0}: {1:.3} s",
            args.size,
            start.elapsed().as_secs_f64()
        );
    }
    write_lut(&args.output, &lut, LutWriteOptions { f32: args.f32 })?;
    if args.common.verbose {
        eprintln!("wrote {}", args.output.display());
    }
    Ok(())
}
