//! The commands: each builds the library's options from its arguments, calls the library,
//! and says what happened (one summary line per success on stderr, warnings, and the
//! preview's table on stdout).

use std::io::IsTerminal;
use std::path::{Path, PathBuf};
use std::time::Instant;

use anyhow::Context;
use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use splitsum::{
    check_cube_path, check_cube_size, check_lut_path, check_output_extension, input_stem,
    png_clip_warning, read_bake_dir, write_atomic, write_lut, BakeOptions, BakeReport, Baker,
    Container, CubeWriteOptions, LutWriteOptions, Preview, PreviewOptions, Stage, SunMode,
    MIN_SUN_SHARE, PREVIEW_ROUGHNESS,
};

use super::args::{
    BakeArgs, CommonArgs, CubemapArgs, InspectArgs, LutArgs, PreviewArgs, PreviewRenderArgs,
    VerifyArgs, ViewArgs,
};
use super::{for_user, Usage};

/// A baker for `command` with `opts`, its backend note printed and, with -v, what runs
/// where.
fn open_baker(command: &str, mut opts: BakeOptions, common: &CommonArgs) -> anyhow::Result<Baker> {
    opts.backend = common.backend.into();
    let baker = Baker::new(opts).map_err(|e| for_user(command, e))?;
    if let Some(note) = baker.backend_note() {
        eprintln!("note: {note}");
    }
    if common.verbose {
        eprintln!("backend: {}", baker.backend_description());
    }
    Ok(baker)
}

/// Prints warnings, one line each.
fn warn(warnings: impl IntoIterator<Item = String>) {
    for w in warnings {
        eprintln!("warning: {w}");
    }
}

/// A progress bar on stderr when it is a terminal and `show` (hidden otherwise).
fn progress_bar(show: bool, len: u64, template: &str) -> ProgressBar {
    let bar = ProgressBar::new(len);
    bar.set_draw_target(if show && std::io::stderr().is_terminal() {
        ProgressDrawTarget::stderr()
    } else {
        ProgressDrawTarget::hidden()
    });
    if let Ok(style) = ProgressStyle::with_template(template) {
        bar.set_style(style.progress_chars("=> "));
    }
    bar
}

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
        bc6h_quality: args.bc6h.bc6h_quality,
        samples: args.samples,
        rotate_degrees: args.input_opts.rotate,
        exposure_ev: args.input_opts.exposure,
        sh: (defaults.sh || args.sh) && !args.no_sh,
        luts: (defaults.luts || args.lut) && !args.no_lut,
        preview: args
            .preview
            .then(|| preview_options(&args.preview_render, args.preview_exposure)),
        sun: args.sun.sun,
        ..defaults
    };
    let mut baker = open_baker("bake", opts, &args.common)?;
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

/// What became of the sun (and further compact lights) of `input` in `mode`, in one line
/// (`light` names the file the lights went to); none for an environment without a sun
/// baked as it is.
fn sun_line(input: &Path, lights: &[splitsum::Sun], mode: SunMode, light: &str) -> Option<String> {
    let input = input.display();
    let more = match lights.len() {
        0 | 1 => String::new(),
        n => format!(
            " and {} more compact light{} ({:.1} % of the light)",
            n - 1,
            if n > 2 { "s" } else { "" },
            100.0 * lights[1..].iter().map(|l| l.share).sum::<f32>()
        ),
    };
    Some(match (lights.first(), mode) {
        (Some(sun), SunMode::Keep) => format!(
            "{input}: sun at {sun}{more}; baked into the IBL (--sun split writes them as lights, the sun with shadows)"
        ),
        (Some(sun), SunMode::Split) => {
            format!("{input}: sun at {sun}{more}; taken out of the IBL, written as {light}")
        }
        (None, SunMode::Keep) => return None,
        (None, SunMode::Split) => format!(
            "{input}: no sun (no compact source holds {:.0} % of the light): nothing taken out, no light written",
            100.0 * MIN_SUN_SHARE
        ),
    })
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

fn preview_options(render: &PreviewRenderArgs, exposure_ev: Option<f32>) -> PreviewOptions {
    PreviewOptions {
        cell: render.preview_cell,
        exposure_ev,
        truth_samples: render.truth_samples,
    }
}

/// Prints a preview's table: per material and roughness, mean / worst relative difference
/// of split-sum against truth; with `verbose`, what each render cost.
fn print_preview(path: &Path, p: &Preview, verbose: bool) {
    if p.stats.is_empty() {
        println!("{}: split-sum only (--truth-samples 0)", path.display());
        return;
    }
    println!(
        "{}: split-sum against ground truth per sphere, luminance: Σ|ΔY| / ΣY and worst pixel |ΔY| / Y, %",
        path.display()
    );
    let header: Vec<String> = PREVIEW_ROUGHNESS
        .iter()
        .map(|r| format!("{:>13}", format!("r = {r}")))
        .collect();
    println!("{:<11}{}", "", header.join(""));
    for row in p.stats.chunks(PREVIEW_ROUGHNESS.len()) {
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

/// `splitsum preview`.
pub fn preview(args: PreviewArgs) -> anyhow::Result<()> {
    let popts = preview_options(&args.render, args.exposure);
    let output = args.output.clone().unwrap_or_else(|| {
        if args.input.is_dir() {
            args.input.join("preview.png")
        } else {
            PathBuf::from("out").join(format!("{}_preview.png", input_stem(&args.input)))
        }
    });
    check_output_extension(&output, "a preview", &["png"]).map_err(|e| for_user("preview", e))?;
    if let Some(json) = &args.json {
        check_output_extension(json, "the preview's figures", &["json"])
            .map_err(|e| for_user("preview", e))?;
    }
    let opts = BakeOptions {
        specular_size: args.specular_size,
        preview: Some(popts),
        sun: args.sun.unwrap_or_default(),
        ..BakeOptions::default()
    };
    let mut baker = open_baker("preview", opts, &args.common)?;
    let spinner = progress_bar(true, 0, "{spinner} {msg} ({elapsed})");
    spinner.enable_steady_tick(std::time::Duration::from_millis(120));
    let (baked, lut) = if args.input.is_dir() {
        spinner.set_message(format!("reading {}", args.input.display()));
        let (baked, lut) = read_bake_dir(&args.input)?;
        if let Some(mode) = args.sun.filter(|m| *m != baked.sun_mode) {
            return Err(Usage(format!(
                "invalid --sun: {} was baked with --sun {}; bake it again with --sun {}, or preview the HDRI itself",
                args.input.display(),
                baked.sun_mode.name(),
                mode.name()
            ))
            .into());
        }
        (baked, lut)
    } else {
        spinner.set_message(format!("baking {}", args.input.display()));
        let loaded = baker.load(&args.input, Some(args.specular_size))?;
        warn(loaded.warnings);
        (baker.bake_environment(loaded.env)?, None)
    };
    spinner.set_message(if popts.truth_samples > 0 {
        format!(
            "rendering split-sum and ground truth ({} samples per pixel and lobe)",
            popts.truth_samples
        )
    } else {
        "rendering split-sum".to_string()
    });
    // The caption names the environment: a bake folder's input as its manifest records it.
    let source = match args.input.is_dir() {
        true => splitsum::Manifest::read(&args.input)
            .map(|m| PathBuf::from(m.input))
            .unwrap_or_else(|_| args.input.clone()),
        false => args.input.clone(),
    };
    let name = source.file_name().map_or_else(
        || source.display().to_string(),
        |n| n.to_string_lossy().into_owned(),
    );
    let preview = baker.preview(&name, &baked, lut.as_ref(), &popts)?;
    spinner.finish_and_clear();
    warn(baker.take_warnings());
    let line = sun_line(&source, &baked.lights, baked.sun_mode, "lights");
    eprint!(
        "{}",
        line.map(|l| l + "
")
            .unwrap_or_default()
    );
    write_atomic(&output, &preview.png)?;
    if let Some(json) = &args.json {
        write_atomic(json, preview_json(&source, &baked, &preview).as_bytes())?;
    }
    print_preview(&output, &preview, args.common.verbose);
    Ok(())
}

/// `preview --json`: the mode, the sun, and per sphere the split-sum's relative
/// difference from the truth.
fn preview_json(input: &Path, baked: &splitsum::BakedEnvironment, p: &Preview) -> String {
    #[derive(serde::Serialize)]
    struct Sphere {
        material: &'static str,
        roughness: f32,
        mean: f32,
        worst: f32,
    }
    #[derive(serde::Serialize)]
    struct Out<'a> {
        input: String,
        sun_mode: &'static str,
        sun: Option<splitsum::Sun>,
        additional_lights: &'a [splitsum::Sun],
        exposure: f32,
        definition: &'static str,
        spheres: Vec<Sphere>,
    }
    let out = Out {
        input: input.display().to_string(),
        sun_mode: baked.sun_mode.name(),
        sun: baked.sun().copied(),
        additional_lights: baked.lights.get(1..).unwrap_or_default(),
        exposure: p.exposure,
        definition: "per sphere, on each pixel's luminance Y: mean = sum |Y_split_sum - Y_truth| / sum Y_truth, worst = the largest |Y_split_sum - Y_truth| / Y_truth of one pixel",
        spheres: p
            .stats
            .iter()
            .map(|s| Sphere {
                material: s.material,
                roughness: s.roughness,
                mean: s.mean_relative,
                worst: s.worst_relative,
            })
            .collect(),
    };
    let mut text = serde_json::to_string_pretty(&out).unwrap_or_default();
    text.push('\n');
    text
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
    let mut baker = open_baker("cubemap", opts, &args.common)?;
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
                bc6h_quality: args.bc6h.bc6h_quality,
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

/// `splitsum inspect`.
pub fn inspect(args: InspectArgs) -> anyhow::Result<()> {
    let opts = BakeOptions {
        rotate_degrees: args.input_opts.rotate,
        exposure_ev: args.input_opts.exposure,
        backend: splitsum::BackendChoice::Cpu,
        ..BakeOptions::default()
    };
    let baker = Baker::new(opts).map_err(|e| for_user("inspect", e))?;
    let loaded = baker.load(&args.input, None)?;
    let inventory = splitsum::inventory(&loaded.env);
    let lights: Vec<splitsum::Sun> = splitsum::find_lights(&loaded.env)
        .into_iter()
        .map(|s| s.rotated(args.input_opts.rotate))
        .collect();
    let light_out = |sun: &splitsum::Sun| LightOut {
        sun: *sun,
        illuminance: sun.illuminance(),
        azimuth_deg: sun.azimuth_deg(),
        elevation_deg: sun.elevation_deg(),
    };
    if args.json {
        #[derive(serde::Serialize)]
        struct Out<'a> {
            input: String,
            #[serde(flatten)]
            inventory: &'a splitsum::Inventory,
            sun: Option<LightOut>,
            additional_lights: Vec<LightOut>,
            warnings: &'a [String],
        }
        let out = Out {
            input: args.input.display().to_string(),
            inventory: &inventory,
            sun: lights.first().map(light_out),
            additional_lights: lights.iter().skip(1).map(light_out).collect(),
            warnings: &loaded.warnings,
        };
        println!("{}", serde_json::to_string_pretty(&out)?);
        return Ok(());
    }
    warn(loaded.warnings);
    let i = &inventory;
    println!("{}", args.input.display());
    match i.layout {
        "cube" => println!("  size          cube, 6 × {0}×{0} texels", i.width),
        _ => println!("  size          {}×{} {}", i.width, i.height, i.layout),
    }
    println!(
        "  mean          {:.4} (R {:.4}, G {:.4}, B {:.4}); peak {:.4}; dynamic range {:.3e}",
        i.mean_luminance, i.mean[0], i.mean[1], i.mean[2], i.peak_luminance, i.dynamic_range
    );
    if i.non_finite + i.negative > 0 {
        println!(
            "  bad texels    {} non-finite, {} negative",
            i.non_finite, i.negative
        );
    }
    if lights.is_empty() {
        println!(
            "  sun           none (no compact source holds {:.0} % of the light)",
            100.0 * MIN_SUN_SHARE
        );
    }
    for (k, s) in lights.iter().enumerate() {
        let label = if k == 0 {
            "sun".to_string()
        } else {
            format!("light {}", k + 1)
        };
        println!(
            "  {label:<14}azimuth {:.2}°, elevation {:.2}°, direction ({:.5}, {:.5}, {:.5})",
            s.azimuth_deg(),
            s.elevation_deg(),
            s.direction[0],
            s.direction[1],
            s.direction[2]
        );
        println!(
            "                irradiance E (facing it) {:.4} (R {:.4}, G {:.4}, B {:.4}), {:.1} % of the light",
            s.illuminance(),
            s.irradiance[0],
            s.irradiance[1],
            s.irradiance[2],
            100.0 * s.share
        );
        println!(
            "                angular radius {:.3}°, solid angle {:.3e} sr, {} texels{}",
            s.angular_radius_deg,
            s.solid_angle_sr,
            s.texels,
            if s.clipped {
                "; clipped (its core is a plateau: the camera saturated, so E is a lower bound)"
            } else {
                ""
            }
        );
    }
    Ok(())
}

/// A light as `inspect --json` writes it: its figures with its illuminance, azimuth and
/// elevation.
#[derive(serde::Serialize)]
struct LightOut {
    #[serde(flatten)]
    sun: splitsum::Sun,
    illuminance: f32,
    azimuth_deg: f32,
    elevation_deg: f32,
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
    check_lut_path(&args.output).map_err(|e| for_user("lut", e))?;
    let mut baker = open_baker("lut", BakeOptions::default(), &args.common)?;
    let start = Instant::now();
    let lut = baker
        .lut(args.model, args.size)
        .map_err(|e| for_user("lut", e))?;
    warn(baker.take_warnings());
    if args.common.verbose {
        eprintln!(
            "brdf lut {0}x{0}: {1:.3} s",
            args.size,
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
        args.size,
        args.size,
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
