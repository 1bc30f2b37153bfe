//! `splitsum preview` (and the table `bake --preview` prints): the seed materials under a
//! bake, split-sum against the ground truth, as a picture, a table and `--json`.

use std::path::{Path, PathBuf};

use splitsum::{
    check_output_extension, input_stem, read_bake_dir, write_atomic, BackendJob, BakeOptions,
    Preview, PreviewOptions, PREVIEW_ROUGHNESS,
};

use splitsum::{Shading, Target};

use super::args::{PreviewArgs, PreviewRenderArgs};
use super::shared::{open_baker, progress_bar, sun_line, warn};
use super::{for_user, Usage};

/// The preview's options for a bake for `target`: its engine's shading, its lookup
/// replaced by `--lookup`.
pub(super) fn preview_options(
    render: &PreviewRenderArgs,
    exposure_ev: Option<f32>,
    target: &Target,
) -> PreviewOptions {
    let shading = target.shading;
    PreviewOptions {
        cell: render.preview_cell,
        exposure_ev,
        truth_samples: render.truth_samples,
        shading: render
            .lookup
            .map_or(shading, |lookup| shading.with_lookup(lookup)),
    }
}

/// Prints a preview's table: per material and roughness, mean / worst relative difference
/// of split-sum against truth; with `verbose`, what each render cost.
pub(super) fn print_preview(path: &Path, p: &Preview, verbose: bool) {
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
    if args.input.is_dir() && args.target.shading != Shading::GENERIC {
        return Err(Usage(format!(
            "invalid --target {}: {} is a bake folder, previewed as the generic target it was baked for; preview the HDRI itself with --target {}",
            args.target.name,
            args.input.display(),
            args.target.name
        ))
        .into());
    }
    let popts = preview_options(&args.render, args.exposure, args.target);
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
        ..BakeOptions::for_target(args.target)
    };
    let mut baker = open_baker("preview", opts, &args.common, BackendJob::Preview)?;
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
    eprint!("{}", line.map(|l| l + "\n").unwrap_or_default());
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
        truth_luminance: f32,
        split_sum_luminance: f32,
    }
    #[derive(serde::Serialize)]
    struct Out<'a> {
        input: String,
        sun_mode: &'static str,
        shading: &'static str,
        lookup: &'static str,
        sun: Option<splitsum::Sun>,
        additional_lights: &'a [splitsum::Sun],
        exposure: f32,
        definition: &'static str,
        spheres: Vec<Sphere>,
    }
    let out = Out {
        input: input.display().to_string(),
        sun_mode: baked.sun_mode.name(),
        shading: p.shading.name,
        lookup: p.shading.lookup.id(),
        sun: baked.sun().copied(),
        additional_lights: baked.lights.get(1..).unwrap_or_default(),
        exposure: p.exposure,
        definition: splitsum::RELATIVE_DIFFERENCE_DEFINITION,
        spheres: p
            .stats
            .iter()
            .map(|s| Sphere {
                material: s.material,
                roughness: s.roughness,
                mean: s.mean_relative,
                worst: s.worst_relative,
                truth_luminance: s.truth_luminance,
                split_sum_luminance: s.split_sum_luminance,
            })
            .collect(),
    };
    let mut text = serde_json::to_string_pretty(&out).unwrap_or_default();
    text.push('\n');
    text
}
