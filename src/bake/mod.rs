//! The whole bake of one environment: load it, bake its light in memory
//! ([`crate::stages::light`]), render the preview when asked, stage the target's file set
//! and LUTs and a manifest, and rename them into place together, so a failed bake leaves
//! earlier outputs untouched and no partial files. [`Baker`] is the front door: it owns
//! the backend (with the fallback policy) and the LUTs, and bakes any number of inputs.

mod baker;
pub mod manifest;
pub mod options;

use std::path::{Path, PathBuf};
use std::time::Instant;

pub use baker::{Baker, LoadedInput};
pub use manifest::{read_bake_dir, Manifest};
pub use options::BakeOptions;

use crate::backend::Backend;
use crate::environment::sun::Sun;
use crate::environment::Environment;
use crate::io::atomic::write_all_atomic;
use crate::io::cubemap::{clip_warning, BlockEncoder, CubeEncoding};
use crate::io::input::{input_stem, load_input, LoadedEnvironment};
use crate::io::staging::{OutputRecord, Staging};
use crate::plan::lut::BrdfLut;
use crate::stages::light::{bake_light, timed_stage, BakedEnvironment, Stage, Timings};
use crate::stages::preview::{is_shading_lut, preview_baked, Preview};
use crate::targets::{write_luts, FileContext};
use crate::Result;

/// What a bake produced.
#[derive(Clone, Debug)]
pub struct BakeReport {
    /// The folder the outputs are in.
    pub out_dir: PathBuf,
    /// Every file written (the manifest last).
    pub outputs: Vec<OutputRecord>,
    /// Wall seconds per stage.
    pub timings: Timings,
    /// Warnings for the user: from loading the input, about the target and pixel format,
    /// about values a format clips, and a GPU failure that was redone on the CPU.
    pub warnings: Vec<String>,
    /// The preview, when asked for.
    pub preview: Option<Preview>,
    /// The backend that computed the outputs (as the manifest records it).
    pub backend: String,
    /// The compact lights found in the input, the sun first (generic frame, rotation
    /// applied), whichever the mode.
    pub lights: Vec<Sun>,
}

/// The line saying that `sun` (found in `input`) looks clipped, when it does.
pub fn clipped_sun_warning(input: &Path, sun: &Sun) -> Option<String> {
    sun.clipped.then(|| {
        format!(
            "{}: the sun looks clipped (its core is a plateau at one value: the camera saturated), so its irradiance {:.4} is a lower bound of the real sun's",
            input.display(),
            sun.illuminance()
        )
    })
}

/// The output folder of `input` under `out_root`: `<out_root>/<stem>`.
pub fn output_dir(out_root: &Path, input: &Path) -> PathBuf {
    out_root.join(input_stem(input))
}

/// Bakes a loaded environment in memory as `opts` say (validated first).
pub fn bake_environment(
    backend: &dyn Backend,
    env: Environment,
    opts: &BakeOptions,
    progress: &mut dyn FnMut(Stage),
    timings: &mut Timings,
) -> Result<BakedEnvironment> {
    opts.validate()?;
    bake_light(backend, env, &opts.light_options(), progress, timings)
}

/// Loads `input` (timed as [`Stage::Load`]) and bakes it in memory: the baked light and
/// the load's warnings.
pub fn load_and_bake(
    backend: &dyn Backend,
    input: &Path,
    opts: &BakeOptions,
    progress: &mut dyn FnMut(Stage),
    timings: &mut Timings,
) -> Result<(BakedEnvironment, Vec<String>)> {
    opts.validate()?;
    let LoadedEnvironment { env, warnings } = timed_stage(Stage::Load, progress, timings, || {
        load_input(input, &opts.input_options())
    })?;
    Ok((
        bake_environment(backend, env, opts, progress, timings)?,
        warnings,
    ))
}

/// Bakes one input into `output_dir(out_root, input)` on `backend`, writing `luts` (the
/// tables of the target's LUT files, matched by model; empty for none). `progress` is
/// called as each stage starts.
pub fn bake(
    backend: &dyn Backend,
    input: &Path,
    out_root: &Path,
    opts: &BakeOptions,
    luts: &[BrdfLut],
    progress: &mut dyn FnMut(Stage),
) -> Result<BakeReport> {
    let mut timings = Vec::new();
    let (baked, mut warnings) = load_and_bake(backend, input, opts, progress, &mut timings)?;
    warnings.extend(baked.sun().and_then(|s| clipped_sun_warning(input, s)));
    let preview = match &opts.preview {
        None => None,
        Some(p) => Some(timed_stage(Stage::Preview, progress, &mut timings, || {
            // The preview shades with the table of its shading's LUT where the bake has it
            // (the target's file), computing it otherwise.
            let split_sum_lut = luts.iter().find(|l| is_shading_lut(&p.shading, l));
            let name = input.file_name().map(|n| n.to_string_lossy()).unwrap_or_default();
            preview_baked(backend, &name, &baked, split_sum_lut, p)
        })?),
    };

    progress(Stage::Write);
    let write_start = Instant::now();
    let target = opts.target;
    if opts.container.is_texture() {
        if let Some(w) = target.format_warning(opts.pixel_format()) {
            warnings.push(format!("target {}: {w}", target.name));
        }
    }
    if target.files.has_pixel_format {
        warnings.extend(clip_warning(&baked.specular, opts.pixel_format()));
    }
    let dir = output_dir(out_root, input);
    let stem = input_stem(input);
    let ctx = FileContext {
        dir: &dir,
        stem: &stem,
        target,
        encoding: CubeEncoding {
            container: opts.container,
            format: opts.pixel_format(),
            zstd: opts.zstd,
            layout: crate::io::cubemap::CubeLayout::Cross,
            every_level: true,
            blocks: BlockEncoder {
                backend,
                quality: opts.bc6h_quality,
                astc_quality: opts.astc_quality,
            },
        },
    };
    let mut out = Staging::default();
    let lights = baked.lights.clone();
    warnings.extend((target.files.write)(&ctx, baked, &mut out)?);
    if opts.luts {
        write_luts(&mut out, &dir, target, luts)?;
    }
    if let Some(p) = &preview {
        out.add(
            dir.join("preview.png"),
            p.png.clone(),
            ("preview", "png (8-bit sRGB)", p.width, 1),
        );
    }
    // The manifest lists every other file (it cannot hold its own hash).
    let identity = backend.identity();
    let mut manifest = Manifest::new(
        input,
        identity.clone(),
        &backend.bc6h_identity(),
        opts,
        luts.first().map(|l| l.width),
        preview.as_ref(),
        &out.records,
    );
    manifest.sun.lights = lights.clone();
    out.add(
        dir.join("manifest.json"),
        manifest.to_json().into_bytes(),
        ("manifest", "json", 0, 0),
    );
    write_all_atomic(&out.files)?;
    timings.push((Stage::Write, write_start.elapsed().as_secs_f64()));

    Ok(BakeReport {
        out_dir: dir,
        outputs: out.records,
        timings,
        warnings,
        preview,
        backend: identity,
        lights,
    })
}
