//! The `splitsum` binary: parse, call the library, print errors with their chain, map
//! them to exit codes (0 ok, 1 a job failed, 2 usage error; clap exits 2 by itself).

mod cli;

use std::process::ExitCode;
use std::time::Instant;

use anyhow::Context;
use clap::Parser;

use cli::{Cli, Command, LutArgs};
use splitsum::io::lut::{check_lut_path, write_lut, LutWriteOptions};

fn main() -> ExitCode {
    let cli = Cli::parse();
    quiet_vulkan_loader();
    let result = match cli.command {
        Command::Lut(args) => run_lut(args),
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

fn run_lut(args: LutArgs) -> anyhow::Result<()> {
    check_lut_path(&args.output)?;
    splitsum::lut::validate_lut_size(args.size, args.size)?;
    let (backend, note) = splitsum::create_backend(args.common.backend.into())?;
    if let Some(note) = note {
        eprintln!("note: {note}");
    }
    if args.common.verbose {
        eprintln!("backend: {}", backend.description());
    }
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
