//! The `splitsum` binary: parse, call the library, print errors with their chain, map
//! them to exit codes (0 ok, 1 a job failed, 2 usage error, clap exits 2 by itself;
//! 130 interrupted).

mod cli;

use std::process::ExitCode;
use std::time::Instant;

use anyhow::Context;
use clap::Parser;

use cli::{
    BakeArgs, Cli, Command, CommonArgs, CubemapArgs, LutArgs, PreviewArgs, PreviewRenderArgs,
    VerifyArgs,
};
use splitsum::io::lut::{check_lut_path, write_lut, LutWriteOptions};

/// Exit code after Ctrl-C or SIGTERM (128 + SIGINT, the shell convention).
const INTERRUPTED: i32 = 130;

fn main() -> ExitCode {
    let cli = Cli::parse();
    quiet_vulkan_loader();
    // Interrupted mid-write: remove the temporaries being written (the destinations keep
    // their previous contents) and exit.
    let _ = ctrlc::set_handler(|| {
        splitsum::io::atomic::remove_in_flight_temporaries();
        eprintln!("interrupted");
        std::process::exit(INTERRUPTED);
    });
    let result = match cli.command {
        Command::Lut(args) => run_lut(args),
        Command::Cubemap(args) => run_cubemap(args),
        Command::Bake(args) => run_bake(args),
        Command::Preview(args) => run_preview(args),
        Command::Verify(args) => run_verify(args),
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
    use splitsum::io::input::{load_faces, load_input, InputOptions};
    let first_input = args
        .input
        .clone()
        .or_else(|| args.faces.first().cloned())
        .unwrap_or_default();
    let target: &'static splitsum::target::Target = args.target.into();
    let output = args.output.clone().unwrap_or_else(|| {
        let stem = splitsum::io::input::input_stem(&first_input);
        std::path::PathBuf::from("out")
            .join(format!("{stem}_cubemap.{}", target.files.cube_extension()))
    });
    check_cube_path(&output)?;
    if let Some(size) = args.size {
        splitsum::convert::validate_cube_size(size)?;
    }
    let format = args.pixel_format.map_or(target.pixel_format, Into::into);
    let is_texture = matches!(
        splitsum::io::extension_of(&output).as_str(),
        "ktx2" | "dds" | "ktx"
    );
    if target.orientation.texel_map() != splitsum::math::cubemap::AxisMap::IDENTITY
        && !is_texture
        && matches!(args.layout, cli::LayoutArg::Equirect)
    {
        return Err(splitsum::Error::InvalidParameter {
            name: "--target",
            message: format!(
                "an equirect is not a cube: --target {} re-orients cube faces, so it applies to .ktx2, .dds, .ktx and the faces or cross layouts",
                target.name
            ),
        }
        .into());
    }
    if let Some(w) = target.format_warning(format).filter(|_| is_texture) {
        eprintln!("warning: --target {}: {w}", target.name);
    }
    let opts = InputOptions {
        exposure_ev: args.input_opts.exposure,
        cube_size: args.size,
    };
    let start = Instant::now();
    let loaded = match &args.input {
        Some(path) => load_input(path, &opts)?,
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
    // By value: the input's finest level becomes the pyramid's without a copy.
    let cube = splitsum::convert::environment_into_cube(
        backend.as_ref(),
        loaded.env,
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
    let cube = target.orientation.apply(cube);
    let written = write_cubemap(
        &output,
        &cube,
        &CubeWriteOptions {
            format,
            zstd: args.zstd.level(target),
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

fn run_bake(args: BakeArgs) -> anyhow::Result<()> {
    use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
    use splitsum::bake::{bake, BakeOptions, Stage};
    use std::io::IsTerminal;
    let target: &'static splitsum::target::Target = args.target.into();
    if args.pixel_format.is_some() && !target.files.has_pixel_format() {
        return Err(splitsum::Error::InvalidParameter {
            name: "--pixel-format",
            message: format!(
                "--target {} writes RGBD PNGs into a .env, whatever the pixel format",
                target.name
            ),
        }
        .into());
    }
    let defaults = BakeOptions::for_target(target);
    let opts = BakeOptions {
        specular_size: args.specular_size,
        min_mip_size: args.min_mip_size.unwrap_or(defaults.min_mip_size),
        irradiance_size: args.irradiance_size,
        container: args.container.into(),
        pixel_format: args.pixel_format.map_or(defaults.pixel_format, Into::into),
        zstd: args.zstd.level(target),
        samples: args.samples,
        rotate_degrees: args.input_opts.rotate,
        exposure_ev: args.input_opts.exposure,
        sh: (defaults.sh || args.sh) && !args.no_sh,
        preview: args
            .preview
            .then(|| preview_options(&args.preview_render, args.preview_exposure)),
        target,
    };
    let write_lut = (target.lut || args.lut) && !args.no_lut;
    splitsum::convert::validate_cube_size(opts.specular_size)?;
    let mut backend = open_backend(&args.common)?;
    // With --backend auto a GPU failure (device lost, out of memory, a driver error)
    // switches this and every later job to the CPU backend, with a warning.
    let auto = matches!(args.common.backend, cli::BackendArg::Auto);
    let fall_back = |e: &splitsum::Error, backend: &mut Box<dyn splitsum::Backend>| -> bool {
        if auto && matches!(e, splitsum::Error::Gpu { .. }) {
            eprintln!("warning: {e}; continuing on the CPU backend");
            *backend = Box::new(splitsum::CpuBackend);
            true
        } else {
            false
        }
    };
    // One table per LUT file of the target, computed once for every input.
    let lut_size = splitsum::lut::DEFAULT_LUT_SIZE;
    let compute_luts =
        |backend: &dyn splitsum::Backend| -> splitsum::Result<Vec<splitsum::BrdfLut>> {
            if !write_lut {
                return Ok(Vec::new());
            }
            target
                .luts
                .iter()
                .map(|spec| backend.brdf_lut_model(lut_size, lut_size, spec.model))
                .collect()
        };
    let mut luts = match compute_luts(backend.as_ref()) {
        Err(e) if fall_back(&e, &mut backend) => compute_luts(backend.as_ref()),
        r => r,
    }
    .context("computing the BRDF LUT")?;
    let show = !args.quiet && std::io::stderr().is_terminal();
    let mut failed = 0;
    for input in &args.inputs {
        let bar = ProgressBar::new(Stage::ALL.len() as u64);
        bar.set_draw_target(if show {
            ProgressDrawTarget::stderr()
        } else {
            ProgressDrawTarget::hidden()
        });
        if let Ok(style) = ProgressStyle::with_template("{prefix} [{bar:24}] {msg}") {
            bar.set_style(style.progress_chars("=> "));
        }
        bar.set_prefix(input.display().to_string());
        let mut progress = |stage: Stage| {
            bar.set_message(stage.name());
            bar.set_position(Stage::ALL.iter().position(|s| *s == stage).unwrap_or(0) as u64);
        };
        let mut run = |backend: &dyn splitsum::Backend, luts: &[splitsum::BrdfLut]| {
            bake(backend, input, &args.output, &opts, luts, &mut progress)
        };
        let result = match run(backend.as_ref(), &luts) {
            Err(e) if fall_back(&e, &mut backend) => {
                // Redo everything on the CPU, the LUTs included, so the outputs are
                // exactly a CPU bake's, as the manifest says.
                compute_luts(backend.as_ref()).and_then(|l| {
                    luts = l;
                    run(backend.as_ref(), &luts)
                })
            }
            r => r,
        };
        bar.finish_and_clear();
        match result {
            Ok(report) => {
                for w in &report.warnings {
                    eprintln!("warning: {w}");
                }
                if let Some(p) = &report.preview {
                    print_preview(&report.out_dir.join("preview.png"), p, args.common.verbose);
                }
                if args.common.verbose {
                    let stages: Vec<String> = report
                        .timings
                        .iter()
                        .map(|(s, t)| format!("{} {t:.2}s", s.name()))
                        .collect();
                    eprintln!(
                        "baked {} -> {} ({})",
                        input.display(),
                        report.out_dir.display(),
                        stages.join(", ")
                    );
                }
            }
            Err(e) => {
                failed += 1;
                eprintln!("error: {e}");
            }
        }
    }
    if failed > 0 {
        anyhow::bail!("{failed} of {} inputs failed", args.inputs.len());
    }
    Ok(())
}

fn preview_options(
    render: &PreviewRenderArgs,
    exposure_ev: Option<f32>,
) -> splitsum::preview::PreviewOptions {
    splitsum::preview::PreviewOptions {
        cell: render.preview_cell,
        exposure_ev,
        truth_samples: render.truth_samples,
    }
}

/// Prints a preview's table: per material and roughness, mean / worst relative difference
/// of split-sum against truth; with `verbose`, what each render cost.
fn print_preview(path: &std::path::Path, p: &splitsum::preview::Preview, verbose: bool) {
    use splitsum::preview::scene::ROUGHNESS;
    if p.stats.is_empty() {
        println!("{}: split-sum only (--truth-samples 0)", path.display());
        return;
    }
    println!(
        "{}: split-sum against ground truth per sphere, luminance: Σ|ΔY| / ΣY and worst pixel |ΔY| / Y, %",
        path.display()
    );
    let header: Vec<String> = ROUGHNESS
        .iter()
        .map(|r| format!("{:>13}", format!("r = {r}")))
        .collect();
    println!("{:<11}{}", "", header.join(""));
    for row in p.stats.chunks(ROUGHNESS.len()) {
        let cells: Vec<String> = row
            .iter()
            .map(|s| {
                let cell = format!(
                    "{:.2} / {:.1}",
                    100.0 * s.mean_relative,
                    100.0 * s.worst_relative
                );
                format!("{cell:>15}")
            })
            .collect();
        println!("{:<11}{}", row[0].material, cells.join(""));
    }
    if verbose {
        eprintln!(
            "preview: split-sum {:.3} s, truth {:.3} s, exposure ×{:.3}",
            p.split_sum_seconds, p.truth_seconds, p.exposure
        );
    }
}

fn run_preview(args: PreviewArgs) -> anyhow::Result<()> {
    use splitsum::bake::{load_and_bake, preview_baked, read_bake_dir, BakeOptions};
    let popts = preview_options(&args.render, args.exposure);
    splitsum::preview::validate_options(&popts)?;
    let output = args.output.clone().unwrap_or_else(|| {
        if args.input.is_dir() {
            args.input.join("preview.png")
        } else {
            let stem = splitsum::io::input::input_stem(&args.input);
            std::path::PathBuf::from("out").join(format!("{stem}_preview.png"))
        }
    });
    splitsum::io::check_output_extension(&output, "a preview", &["png"])?;
    let backend = open_backend(&args.common)?;
    let (baked, lut) = if args.input.is_dir() {
        read_bake_dir(&args.input)?
    } else {
        let opts = BakeOptions {
            specular_size: args.specular_size,
            ..BakeOptions::default()
        };
        let (baked, warnings) = load_and_bake(
            backend.as_ref(),
            &args.input,
            &opts,
            &mut |_| {},
            &mut Vec::new(),
        )?;
        for w in &warnings {
            eprintln!("warning: {w}");
        }
        (baked, None)
    };
    let preview = preview_baked(backend.as_ref(), &baked, lut.as_ref(), &popts)?;
    splitsum::io::atomic::write_atomic(&output, &preview.png)?;
    print_preview(&output, &preview, args.common.verbose);
    Ok(())
}

fn run_verify(args: VerifyArgs) -> anyhow::Result<()> {
    use splitsum::io::input::{load_environment, InputOptions};
    let loaded = load_environment(&args.input, &InputOptions::default())?;
    let gpu = splitsum::GpuBackend::new()?;
    eprintln!("GPU: {}", gpu.ctx.adapter_description());
    let rows = splitsum::verify::verify(&gpu, &loaded.env)?;
    println!(
        "{:<22} {:>12} {:>12} {:>12}  result",
        "kernel", "max abs", "max rel", "tolerance"
    );
    let mut ok = true;
    for r in &rows {
        println!(
            "{:<22} {:>12.3e} {:>12.3e} {:>12.1e}  {}",
            r.kernel,
            r.max_abs,
            r.max_rel,
            r.tolerance,
            if r.pass { "pass" } else { "FAIL" }
        );
        ok &= r.pass;
    }
    if !ok {
        anyhow::bail!("GPU results differ from the CPU reference beyond tolerance");
    }
    Ok(())
}

fn run_lut(args: LutArgs) -> anyhow::Result<()> {
    check_lut_path(&args.output)?;
    splitsum::lut::validate_lut_size(args.size, args.size)?;
    let backend = open_backend(&args.common)?;
    let start = Instant::now();
    let lut = backend
        .brdf_lut_model(args.size, args.size, args.model.into())
        .context("computing the BRDF LUT")?;
    if args.common.verbose {
        eprintln!(
            "brdf lut {0}x{0}: {1:.3} s",
            args.size,
            start.elapsed().as_secs_f64()
        );
    }
    if splitsum::io::extension_of(&args.output) == "png" {
        let (clipped, largest) = lut
            .values()
            .filter(|&v| v > 1.0)
            .fold((0usize, 0.0f32), |(n, m), v| (n + 1, m.max(v)));
        if clipped > 0 {
            eprintln!(
                "warning: {}: {clipped} values above 1 (the {} model's largest is {largest:.2}) are clipped in a PNG; write .exr or .ktx2 to keep them",
                args.output.display(),
                splitsum::lut::LutModel::from(args.model).name(),
            );
        }
    }
    write_lut(&args.output, &lut, LutWriteOptions { f32: args.f32 })?;
    if args.common.verbose {
        eprintln!("wrote {}", args.output.display());
    }
    Ok(())
}
