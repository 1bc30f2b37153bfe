//! The commands that bake and write: `bake`, `cubemap`, `lut`, `verify` and `view`
//! (`preview` and `inspect` have modules of their own). Each builds the library's options
//! from its arguments, calls the library, and says what happened (one summary line per
//! success on stderr, warnings, and with `bake --preview` the preview's table on stdout).

use std::path::{Path, PathBuf};
use std::time::Instant;

use anyhow::Context;
use splitsum::{
    check_cube_path, check_cube_size, check_lut_path, check_output_extension, input_stem,
    png_clip_warning, write_atomic, write_lut, BackendJob, BakeOptions, BakeReport, Container,
    CubeWriteOptions, LutWriteOptions, Stage, SunMode,
};

use super::args::{BakeArgs, CubemapArgs, LutArgs, VerifyArgs, ViewArgs};
use super::preview::{preview_options, print_preview};
use super::shared::{open_baker, progress_bar, sun_line, warn};
use super::{for_user, Usage};

/// `splitsum bake`.
pub fn bake(args: BakeArgs) -> anyhow::Result<()> {
    let target = args.target;
    let defaults = BakeOptions::for_target(target);
    let opts = BakeOptions {
        target,
        specular_size: args.specular_size,
        min_mip_size: args.min_mip_size.unwrap_or(defaults.min_mip_size),
        irradiance_size: args.irradiance_size,
        container: args.container.into(),
        pixel_format: args.pixel_format,
        zstd: args.zstd.level(target),
        bc6h_quality: args.blocks.bc6h_quality,
        astc_quality: args.blocks.astc_quality,
        samples: args.samples,
        rotate_degrees: args.input_opts.rotate,
        exposure_ev: args.input_opts.exposure,
        sh: (defaults.sh || args.sh) && !args.no_sh,
        luts: (defaults.luts || args.lut) && !args.no_lut,
        preview: args
            .preview
            .then(|| preview_options(&args.preview_render, args.preview_exposure, target)),
        sun: args.sun.sun,
        ..defaults
    };
    let job = if opts.preview.is_some() {
        BackendJob::Preview
    } else {
        BackendJob::Bake
    };
    let mut baker = open_baker("bake", opts, &args.common, job)?;
    let mut failed = 0;
    for input in &args.inputs {
        let bar = progress_bar(
            !args.quiet,
            Stage::ALL.len() as u64,
            "{prefix} [{bar:24}] {msg}",
        );
        bar.set_prefix(input.display().to_string());
        let mut progress = |stage: Stage| {
            bar.set_message(stage.name());
            bar.set_position(Stage::ALL.iter().position(|s| *s == stage).unwrap_or(0) as u64);
        };
        let start = Instant::now();
        let result = baker.bake_with_progress(input, &args.output, &mut progress);
        bar.finish_and_clear();
        match result {
            Ok(report) => {
                warn(report.warnings.iter().cloned());
                if let Some(p) = &report.preview {
                    print_preview(&report.out_dir.join("preview.png"), p, args.common.verbose);
                }
                if !args.quiet {
                    eprintln!("{}", summary(input, &report, start.elapsed().as_secs_f64()));
                    let line = sun_line(input, &report.lights, args.sun.sun, "sun.json");
                    eprint!("{}", line.map(|l| l + "\n").unwrap_or_default());
                }
                if args.common.verbose {
                    let stages: Vec<String> = report
                        .timings
                        .iter()
                        .map(|(s, t)| format!("{} {t:.2}s", s.name()))
                        .collect();
                    eprintln!("  stages: {}", stages.join(", "));
                }
            }
            Err(e) => {
                failed += 1;
                eprintln!("error: {}", for_user("bake", e));
            }
        }
    }
    if failed > 0 {
        anyhow::bail!("{failed} of {} inputs failed", args.inputs.len());
    }
    Ok(())
}

/// `baked sky.hdr -> out/sky/ (5 files, 4.4 MB, 2.1 s)`.
fn summary(input: &Path, report: &BakeReport, seconds: f64) -> String {
    let bytes: usize = report.outputs.iter().map(|o| o.bytes).sum();
    let size = if bytes >= 1_000_000 {
        format!("{:.1} MB", bytes as f64 / 1e6)
    } else {
        format!("{:.0} kB", (bytes as f64 / 1e3).max(1.0))
    };
    format!(
        "baked {} -> {}/ ({} files, {size}, {seconds:.1} s)",
        input.display(),
        report.out_dir.display(),
        report.outputs.len()
    )
}

/// `splitsum cubemap`.
pub fn cubemap(args: CubemapArgs) -> anyhow::Result<()> {
    let target = args.target;
    let first_input = args
        .input
        .clone()
        .or_else(|| args.faces.first().cloned())
        .unwrap_or_default();
    let output = args.output.clone().unwrap_or_else(|| {
        PathBuf::from("out").join(format!(
            "{}_cubemap.{}",
            input_stem(&first_input),
            target.files.cube_container.extension()
        ))
    });
    check_cube_path(&output).map_err(|e| for_user("cubemap", e))?;
    if let Some(size) = args.size {
        check_cube_size(size).map_err(|e| for_user("cubemap", e))?;
    }
    let container = Container::of_path(&output).unwrap_or(Container::Ktx2);
    if !target.orientation.is_generic()
        && !container.is_texture()
        && matches!(args.layout, super::args::LayoutArg::Equirect)
    {
        return Err(Usage(format!(
            "invalid --target: an equirect is not a cube: --target {} re-orients cube faces, so it applies to .ktx2, .dds, .ktx and the faces or cross layouts",
            target.name
        ))
        .into());
    }
    let format = args.pixel_format.unwrap_or(target.pixel_format);
    target
        .check_format(format)
        .and_then(|()| container.check_format(format))
        .map_err(|e| for_user("cubemap", e))?;
    if let Some(w) = target
        .format_warning(format)
        .filter(|_| container.is_texture())
    {
        eprintln!("warning: --target {}: {w}", target.name);
    }
    let opts = BakeOptions {
        rotate_degrees: args.input_opts.rotate,
        exposure_ev: args.input_opts.exposure,
        ..BakeOptions::for_target(target)
    };
    let mut baker = open_baker("cubemap", opts, &args.common, BackendJob::Bake)?;
    let start = Instant::now();
    let mut loaded = match &args.input {
        Some(path) => baker.load(path, args.size)?,
        None => baker.load_faces(&args.faces, args.size)?,
    };
    warn(loaded.warnings.drain(..));
    let sun_path = output.with_file_name(format!("{}_sun.json", input_stem(&output)));
    let lights: Vec<splitsum::Sun> = match args.sun.sun {
        SunMode::Keep => splitsum::find_lights(&loaded.env),
        SunMode::Split => splitsum::split_lights(&mut loaded.env),
    }
    .into_iter()
    .map(|s| s.rotated(args.input_opts.rotate))
    .collect();
    if let Some(w) = lights
        .first()
        .and_then(|s| splitsum::clipped_sun_warning(&first_input, s))
    {
        warn([w]);
    }
    let line = sun_line(
        &first_input,
        &lights,
        args.sun.sun,
        &sun_path.display().to_string(),
    );
    eprint!("{}", line.map(|l| l + "\n").unwrap_or_default());
    if args.common.verbose {
        eprintln!(
            "read {}: {:.3} s",
            first_input.display(),
            start.elapsed().as_secs_f64()
        );
    }
    let start = Instant::now();
    let cube = baker
        .cubemap(loaded.env, args.size, args.mips)
        .map_err(|e| for_user("cubemap", e))
        .context("converting to a cubemap")?;
    warn(baker.take_warnings());
    if args.common.verbose {
        eprintln!(
            "cubemap {}, {} levels: {:.3} s",
            cube.size,
            cube.levels.len(),
            start.elapsed().as_secs_f64()
        );
    }
    let written = baker
        .write_cubemap(
            &output,
            &cube,
            &CubeWriteOptions {
                format,
                zstd: args.zstd.level(target),
                layout: args.layout.into(),
                bc6h_quality: args.blocks.bc6h_quality,
                astc_quality: args.blocks.astc_quality,
            },
        )
        .map_err(|e| for_user("cubemap", e))?;
    warn(baker.take_warnings());
    if let Some(json) =
        splitsum::sun_json(&lights, target).filter(|_| args.sun.sun == SunMode::Split)
    {
        write_atomic(&sun_path, json.as_bytes())?;
    }
    let shown: Vec<String> = written.iter().map(|p| p.display().to_string()).collect();
    eprintln!(
        "wrote {} ({}×{}, {} levels)",
        shown.join(", "),
        cube.size,
        cube.size,
        if container.is_texture() {
            cube.levels.len()
        } else {
            1
        }
    );
    Ok(())
}

/// `splitsum verify`.
pub fn verify(args: VerifyArgs) -> anyhow::Result<()> {
    let v = splitsum::verify_input(&args.input)?;
    eprintln!("GPU: {}", v.adapter);
    println!(
        "{:<22} {:>12} {:>12} {:>12}  result",
        "kernel", "max abs", "max rel", "tolerance"
    );
    for r in &v.rows {
        println!(
            "{:<22} {:>12.3e} {:>12.3e} {:>12.1e}  {}",
            r.kernel,
            r.max_abs,
            r.max_rel,
            r.tolerance,
            if r.pass { "pass" } else { "FAIL" }
        );
    }
    if !v.passed() {
        anyhow::bail!("GPU results differ from the CPU reference beyond tolerance");
    }
    Ok(())
}

/// `splitsum lut`.
pub fn lut(args: LutArgs) -> anyhow::Result<()> {
    if args.ltc {
        return ltc(args);
    }
    let size = args.size.unwrap_or(splitsum::DEFAULT_LUT_SIZE);
    check_lut_path(&args.output).map_err(|e| for_user("lut", e))?;
    let mut baker = open_baker(
        "lut",
        BakeOptions::default(),
        &args.common,
        BackendJob::Bake,
    )?;
    let start = Instant::now();
    let lut = baker
        .lut(args.model, size)
        .map_err(|e| for_user("lut", e))?;
    warn(baker.take_warnings());
    if args.common.verbose {
        eprintln!(
            "brdf lut {0}x{0}: {1:.3} s",
            size,
            start.elapsed().as_secs_f64()
        );
    }
    if let Some(w) = png_clip_warning(&args.output, &lut) {
        eprintln!("warning: {w}; write .exr or .ktx2 to keep them");
    }
    write_lut(&args.output, &lut, LutWriteOptions { f32: args.f32 })?;
    eprintln!(
        "wrote {} ({}×{} {})",
        args.output.display(),
        size,
        size,
        args.model.name()
    );
    Ok(())
}

/// Cells per side of `lut --ltc`'s table by default: three.js's and Heitz's 64.
const DEFAULT_LTC_SIZE: u32 = 64;

/// `splitsum lut --ltc`: the LTC table of `--model`'s masking.
fn ltc(args: LutArgs) -> anyhow::Result<()> {
    let size = args.size.unwrap_or(DEFAULT_LTC_SIZE);
    check_output_extension(&args.output, "an LTC table", &["json"])
        .map_err(|e| for_user("lut", e))?;
    let mut baker = open_baker(
        "lut",
        BakeOptions::default(),
        &args.common,
        BackendJob::LtcFit,
    )?;
    let start = Instant::now();
    let table = baker
        .ltc(args.model, size)
        .map_err(|e| for_user("lut", e))?;
    warn(baker.take_warnings());
    if args.common.verbose {
        eprintln!("ltc {0}x{0}: {1:.3} s", size, start.elapsed().as_secs_f64());
    }
    splitsum::write_ltc(&args.output, &table)?;
    eprintln!(
        "wrote {} ({}×{} LTC table, {} masking)",
        args.output.display(),
        size,
        size,
        args.model.name()
    );
    Ok(())
}

/// `splitsum view`.
pub fn view(args: ViewArgs) -> anyhow::Result<()> {
    let keys = match &args.keys {
        Some(k) => splitsum::parse_keys(k).map_err(|e| for_user("view", e))?,
        None => Vec::new(),
    };
    let opts = splitsum::ViewOptions {
        input: args.input,
        model: args.model,
        size: args.size,
        backend: args.common.backend.into(),
        screenshot: args.screenshot.clone(),
        keys,
        frames: args.frames,
        sun: args.sun,
    };
    opts.validate().map_err(|e| for_user("view", e))?;
    let Some(path) = args.screenshot else {
        return splitsum::run_view(opts, &mut |_| {}).map_err(|e| for_user("view", e));
    };
    check_output_extension(&path, "a screenshot", &["png"]).map_err(|e| for_user("view", e))?;
    let spinner = progress_bar(true, 0, "{spinner} {msg} ({elapsed})");
    spinner.enable_steady_tick(std::time::Duration::from_millis(120));
    let verbose = args.common.verbose;
    let result = splitsum::run_view(opts, &mut |line| {
        if let Some(w) = line.strip_prefix("warning: ") {
            spinner.suspend(|| eprintln!("warning: {w}"));
        } else if verbose {
            spinner.suspend(|| eprintln!("{line}"));
        }
        spinner.set_message(line);
    });
    spinner.finish_and_clear();
    result.map_err(|e| for_user("view", e))?;
    println!("wrote {} ({}x{})", path.display(), args.size.0, args.size.1);
    Ok(())
}
