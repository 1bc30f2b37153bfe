//! The whole bake of one environment: cubemap, prefiltered specular, irradiance, SH, LUT,
//! and a manifest. Every output of an input is staged and renamed into place together,
//! so a failed bake leaves earlier outputs untouched and no partial files.

use std::path::{Path, PathBuf};
use std::time::Instant;

use serde::Serialize;
use sha2::{Digest, Sha256};

use crate::convert::environment_into_cube_with_irradiance;
use crate::cpu::prefilter_specular::{chain_levels, SpecularChain};
use crate::cpu::roughest_level::fit_roughest_level;
use crate::cpu::sh_project::{sh_project, ShCoefficients};
use crate::environment::{Cubemap, Environment};
use crate::io::atomic::write_all_atomic;
use crate::io::cubemap::{encode_texture, to_cross};
use crate::io::input::{load_input, InputOptions, LoadedEnvironment};
use crate::io::lut::{encode_lut, LutWriteOptions};
use crate::io::{dds, env, exr, ktx1, ktx2, sh_text, PixelFormat};
use crate::lut::LutModel;
use crate::lut::{BrdfLut, DEFAULT_LUT_SIZE};
use crate::math::sh::{sh_prescaled, sh_rotated, SH_ORDER};
use crate::preview::{render_preview, BakedLight, Preview, PreviewOptions, SphereStats};
use crate::target::{FileSet, LutChannels, Target, GENERIC};
use crate::{Backend, Error, Result};

/// Container of the specular and irradiance outputs.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Container {
    /// KTX 2.0 cubemaps with every mip.
    Ktx2,
    /// DDS (DX10) cubemaps with every mip.
    Dds,
    /// OpenEXR horizontal crosses, one file per mip (`specular_m0.exr`, …).
    Exr,
}

impl Container {
    /// File extension.
    pub fn extension(self) -> &'static str {
        match self {
            Container::Ktx2 => "ktx2",
            Container::Dds => "dds",
            Container::Exr => "exr",
        }
    }
}

/// Everything a bake can be asked for.
#[derive(Clone, Debug)]
pub struct BakeOptions {
    /// The engine the files are for: orientation, chain layout and which files are
    /// written come from it (pixel format, zstd, minimum mip size and SH are its defaults
    /// in [`BakeOptions::for_target`], overridable here).
    pub target: &'static Target,
    /// Specular cube edge (a power of two).
    pub specular_size: u32,
    /// Edge of the smallest specular mip (a power of two; 1 gives the full chain): the
    /// chain has log2(specular_size / min_mip_size) + 1 levels (one when the specular size
    /// is not larger).
    pub min_mip_size: u32,
    /// Irradiance cube edge (a power of two).
    pub irradiance_size: u32,
    /// Output container.
    pub container: Container,
    /// Pixel format of KTX2/DDS outputs.
    pub pixel_format: PixelFormat,
    /// KTX2 Zstandard level.
    pub zstd: Option<i32>,
    /// GGX samples per texel for importance-sampled specular levels.
    pub samples: u32,
    /// Rotation about +Y in degrees.
    pub rotate_degrees: f32,
    /// Exposure in EV.
    pub exposure_ev: f32,
    /// Write sh.json.
    pub sh: bool,
    /// Render `preview.png` (split-sum against ground truth, see [`crate::preview`]).
    pub preview: Option<PreviewOptions>,
}

impl BakeOptions {
    /// The defaults of `target`: its pixel format, supercompression, minimum mip size and
    /// SH output; 256² specular, 32² irradiance, KTX2.
    pub fn for_target(target: &'static Target) -> Self {
        BakeOptions {
            target,
            specular_size: 256,
            min_mip_size: target.min_mip_size,
            irradiance_size: 32,
            container: Container::Ktx2,
            pixel_format: target.pixel_format,
            zstd: target.zstd,
            samples: crate::cpu::prefilter_specular::DEFAULT_SAMPLES,
            rotate_degrees: 0.0,
            exposure_ev: 0.0,
            sh: target.sh,
            preview: None,
        }
    }

    /// The container of the cubes, as manifests name it: the bake's for the standard file
    /// set, the engine's own otherwise.
    pub fn container_name(&self) -> &'static str {
        match self.target.files {
            FileSet::Standard => self.container.extension(),
            FileSet::FilamentKtx1 => "ktx (KTX 1)",
            FileSet::BabylonEnv => "env (Babylon.js)",
            FileSet::GltfSampleViewer => "ktx2 (glTF-IBL-Sampler's folders)",
        }
    }

    /// The specular chain's layout: levels down to the minimum mip, the target's roughness
    /// per mip.
    pub fn specular_chain(&self) -> SpecularChain {
        SpecularChain {
            levels: chain_levels(self.specular_size, self.min_mip_size),
            roughness: self.target.roughness,
        }
    }
}

impl Default for BakeOptions {
    /// The generic target's defaults.
    fn default() -> Self {
        BakeOptions::for_target(&GENERIC)
    }
}

/// A stage of a bake, reported to the progress callback before it starts.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Stage {
    /// Reading and validating the input.
    Load,
    /// Converting to the environment cubemap with mips.
    Cubemap,
    /// Prefiltering the specular chain.
    Specular,
    /// Convolving the irradiance cube.
    Irradiance,
    /// Prefiltering the Charlie sheen chain (targets that read one).
    Sheen,
    /// Projecting onto spherical harmonics.
    Sh,
    /// Rendering the preview.
    Preview,
    /// Encoding and writing the outputs.
    Write,
}

impl Stage {
    /// Lower-case name.
    pub fn name(self) -> &'static str {
        match self {
            Stage::Load => "load",
            Stage::Cubemap => "cubemap",
            Stage::Specular => "specular",
            Stage::Irradiance => "irradiance",
            Stage::Sheen => "sheen",
            Stage::Sh => "sh",
            Stage::Preview => "preview",
            Stage::Write => "write",
        }
    }

    /// All stages in order.
    pub const ALL: [Stage; 8] = [
        Stage::Load,
        Stage::Cubemap,
        Stage::Specular,
        Stage::Irradiance,
        Stage::Sheen,
        Stage::Sh,
        Stage::Preview,
        Stage::Write,
    ];
}

/// One file a bake wrote.
#[derive(Clone, Debug)]
pub struct OutputRecord {
    /// Path of the file.
    pub path: PathBuf,
    /// What it holds ("specular", "irradiance", "sh", "brdf_lut").
    pub kind: &'static str,
    /// Pixel format or file format.
    pub format: String,
    /// Edge in texels (0 for non-images).
    pub size: u32,
    /// Mip levels (0 for non-images).
    pub levels: u32,
    /// File size in bytes.
    pub bytes: usize,
    /// SHA-256 of the file's bytes, hex.
    pub sha256: String,
}

/// What a bake produced.
#[derive(Clone, Debug)]
pub struct BakeReport {
    /// The folder the outputs are in.
    pub out_dir: PathBuf,
    /// Every file written (the manifest last).
    pub outputs: Vec<OutputRecord>,
    /// Wall seconds per stage.
    pub timings: Vec<(Stage, f64)>,
    /// Warnings from loading the input.
    pub warnings: Vec<String>,
    /// The preview, when asked for.
    pub preview: Option<Preview>,
}

/// The light of one environment baked in memory, in the generic orientation (before a
/// target's): what `bake` writes and `preview` renders.
#[derive(Clone, Debug)]
pub struct BakedEnvironment {
    /// The prefiltered specular chain (level 0 is the environment cube).
    pub specular: Cubemap,
    /// Its layout.
    pub chain: SpecularChain,
    /// The irradiance cube (E/π).
    pub irradiance: Cubemap,
    /// The SH projection, when asked for.
    pub sh: Option<ShCoefficients>,
    /// The prefiltered Charlie sheen chain, in the specular chain's layout, for targets
    /// that read one ([`FileSet::has_sheen`]).
    pub sheen: Option<Cubemap>,
}

impl BakedEnvironment {
    /// What the preview reads of it, with `lut`.
    pub fn light<'a>(&'a self, lut: &'a BrdfLut) -> BakedLight<'a> {
        BakedLight {
            specular: &self.specular,
            chain: self.chain,
            irradiance: &self.irradiance,
            lut,
        }
    }
}

/// Runs `f` as `stage`: reports it to `progress` and records its wall time.
fn timed_stage<T>(
    stage: Stage,
    progress: &mut dyn FnMut(Stage),
    timings: &mut Vec<(Stage, f64)>,
    f: impl FnOnce() -> Result<T>,
) -> Result<T> {
    progress(stage);
    let t = Instant::now();
    let out = f()?;
    timings.push((stage, t.elapsed().as_secs_f64()));
    Ok(out)
}

/// Checks the sizes and counts of `opts` before any work.
pub fn validate_options(opts: &BakeOptions) -> Result<()> {
    crate::convert::validate_cube_size(opts.specular_size)?;
    crate::convert::validate_cube_size(opts.irradiance_size).map_err(|_| {
        Error::InvalidParameter {
            name: "--irradiance-size",
            message: format!(
                "{} must be a power of two in 1..=8192",
                opts.irradiance_size
            ),
        }
    })?;
    if !opts.min_mip_size.is_power_of_two() {
        return Err(Error::InvalidParameter {
            name: "--min-mip-size",
            message: format!("{} is not a power of two", opts.min_mip_size),
        });
    }
    if opts.samples == 0 || opts.samples > 65536 {
        return Err(Error::InvalidParameter {
            name: "--samples",
            message: format!("{} is outside 1..=65536", opts.samples),
        });
    }
    if let Some(p) = &opts.preview {
        crate::preview::validate_options(p)?;
    }
    let target = opts.target;
    if target.files != FileSet::Standard && opts.container != Container::Ktx2 {
        return Err(Error::InvalidParameter {
            name: "--container",
            message: format!(
                "--target {} writes the containers its engine loads ({}); --container applies to the generic, bevy and three targets",
                target.name,
                opts.container_name()
            ),
        });
    }
    if target.files.carries_sh() && !opts.sh {
        return Err(Error::InvalidParameter {
            name: "--no-sh",
            message: format!(
                "--target {} writes the irradiance SH into its file, where the engine reads them",
                target.name
            ),
        });
    }
    if target.files == FileSet::BabylonEnv && opts.min_mip_size != 1 {
        return Err(Error::InvalidParameter {
            name: "--min-mip-size",
            message: format!(
                "--target babylon writes the whole chain down to 1x1, the only one Babylon reads from a .env ({} asked for)",
                opts.min_mip_size
            ),
        });
    }
    Ok(())
}

/// Bakes a loaded environment in memory: cube conversion, specular chain (its last level
/// fitted for bilinear lookups), irradiance and SH. `progress` is called as each stage
/// starts, and each stage's wall time is pushed onto `timings`.
pub fn bake_environment(
    backend: &dyn Backend,
    source: Environment,
    opts: &BakeOptions,
    progress: &mut dyn FnMut(Stage),
    timings: &mut Vec<(Stage, f64)>,
) -> Result<BakedEnvironment> {
    validate_options(opts)?;
    let (env, irradiance_source) = timed_stage(Stage::Cubemap, progress, timings, || {
        environment_into_cube_with_irradiance(
            backend,
            source,
            opts.specular_size,
            true,
            opts.rotate_degrees,
        )
    })?;
    let chain = opts.specular_chain();
    let mut specular = timed_stage(Stage::Specular, progress, timings, || {
        backend.prefilter_specular(&env, Some(&irradiance_source), chain, opts.samples)
    })?;
    let irradiance = timed_stage(Stage::Irradiance, progress, timings, || {
        let irradiance = backend.irradiance(&irradiance_source, opts.irradiance_size)?;
        // The r = 1 level is E/π; its texels are fitted to the finer irradiance cube for
        // the bilinear lookup a shader makes (see `cpu::roughest_level`).
        fit_roughest_level(&mut specular, &irradiance);
        Ok(irradiance)
    })?;
    let sheen = match opts.target.files.has_sheen() {
        false => None,
        true => Some(timed_stage(Stage::Sheen, progress, timings, || {
            backend.prefilter_sheen(&env, Some(&irradiance_source), chain)
        })?),
    };
    let sh = timed_stage(Stage::Sh, progress, timings, || {
        Ok(opts.sh.then(|| sh_project(&irradiance_source)))
    })?;
    Ok(BakedEnvironment {
        specular,
        chain,
        irradiance,
        sh,
        sheen,
    })
}

/// Validates `opts`, loads `input` (timed as [`Stage::Load`]) and bakes it in memory with
/// [`bake_environment`]: the baked light and the load's warnings.
pub fn load_and_bake(
    backend: &dyn Backend,
    input: &Path,
    opts: &BakeOptions,
    progress: &mut dyn FnMut(Stage),
    timings: &mut Vec<(Stage, f64)>,
) -> Result<(BakedEnvironment, Vec<String>)> {
    validate_options(opts)?;
    let LoadedEnvironment { env, warnings } = timed_stage(Stage::Load, progress, timings, || {
        load_input(
            input,
            &InputOptions {
                exposure_ev: opts.exposure_ev,
                cube_size: Some(opts.specular_size),
            },
        )
    })?;
    Ok((
        bake_environment(backend, env, opts, progress, timings)?,
        warnings,
    ))
}

/// The preview of `baked` with `lut`, or without one with the default model's
/// [`DEFAULT_LUT_SIZE`]² LUT computed on `backend`.
pub fn preview_baked(
    backend: &dyn Backend,
    baked: &BakedEnvironment,
    lut: Option<&BrdfLut>,
    opts: &PreviewOptions,
) -> Result<Preview> {
    let own;
    let lut = match lut {
        Some(l) => l,
        None => {
            own = backend.brdf_lut(DEFAULT_LUT_SIZE, DEFAULT_LUT_SIZE)?;
            &own
        }
    };
    render_preview(backend, &baked.light(lut), opts)
}

/// `sh.json`: the coefficient order, the radiance projection and the E/π coefficients.
#[derive(Serialize)]
struct ShJson<'a> {
    order: &'a str,
    radiance_sh9: &'a [[f32; 3]; 9],
    irradiance_sh9: &'a [[f32; 3]; 9],
}

/// `sh.json` of `sh` (world space, generic orientation, whatever the target).
pub fn sh_json(sh: &ShCoefficients) -> String {
    to_json(&ShJson {
        order: SH_ORDER,
        radiance_sh9: &sh.radiance,
        irradiance_sh9: &sh.irradiance,
    })
}

/// Pretty JSON with a final newline. Serialising these plain structs cannot fail, and
/// non-finite floats (which sanitised inputs never give) become `null`.
fn to_json(value: &impl Serialize) -> String {
    let mut s = serde_json::to_string_pretty(value).unwrap_or_default();
    s.push('\n');
    s
}

fn sha256_hex(bytes: &[u8]) -> String {
    Sha256::digest(bytes)
        .iter()
        .map(|b| format!("{b:02x}"))
        .collect()
}

/// Encodes a cube for the container: one file, or (EXR) one cross per mip.
fn encode_cube(
    dir: &Path,
    name: &str,
    cube: &Cubemap,
    opts: &BakeOptions,
) -> Result<Vec<(PathBuf, Vec<u8>)>> {
    let enc_err = |path: &Path, format: &'static str, message: String| Error::Encode {
        path: path.to_path_buf(),
        format,
        message,
    };
    Ok(match opts.container {
        Container::Ktx2 => {
            let path = dir.join(format!("{name}.ktx2"));
            let bytes = ktx2::encode(&encode_texture(cube, opts.pixel_format), opts.zstd)
                .map_err(|e| enc_err(&path, "KTX2", e.to_string()))?;
            vec![(path, bytes)]
        }
        Container::Dds => vec![(
            dir.join(format!("{name}.dds")),
            dds::encode(&encode_texture(cube, opts.pixel_format)),
        )],
        Container::Exr => (0..cube.levels.len())
            .map(|m| {
                let level = Cubemap {
                    size: cube.level_size(m),
                    levels: vec![cube.levels[m].clone()],
                };
                let (w, h, data) = to_cross(&level);
                let path = dir.join(format!("{name}_m{m}.exr"));
                let bytes =
                    exr::encode_rgb32(w, h, &data).map_err(|e| enc_err(&path, "OpenEXR", e))?;
                Ok((path, bytes))
            })
            .collect::<Result<_>>()?,
    })
}

/// The files of one bake, staged in memory with their records until written together.
#[derive(Default)]
struct Staging {
    staged: Vec<(PathBuf, Vec<u8>)>,
    outputs: Vec<OutputRecord>,
}

impl Staging {
    /// Adds a file; `meta` is (kind, format, size, levels).
    fn add(&mut self, path: PathBuf, bytes: Vec<u8>, meta: (&'static str, &str, u32, u32)) {
        self.outputs.push(OutputRecord {
            path: path.clone(),
            kind: meta.0,
            format: meta.1.to_string(),
            size: meta.2,
            levels: meta.3,
            bytes: bytes.len(),
            sha256: sha256_hex(&bytes),
        });
        self.staged.push((path, bytes));
    }

    /// Adds the files of one cube (`encode_cube`'s: one, or six faces), of `kind` in
    /// `format`, with the cube's edge and level count.
    fn add_cube(
        &mut self,
        files: Vec<(PathBuf, Vec<u8>)>,
        kind: &'static str,
        format: &str,
        cube: &Cubemap,
    ) {
        for (path, bytes) in files {
            self.add(
                path,
                bytes,
                (kind, format, cube.size, cube.levels.len() as u32),
            );
        }
    }
}

/// The output folder of `input` under `out_root`: `<out_root>/<stem>`.
pub fn output_dir(out_root: &Path, input: &Path) -> PathBuf {
    out_root.join(crate::io::input::input_stem(input))
}

/// Bakes one input into `output_dir(out_root, input)`. `luts` are written beside the other
/// outputs as the target's [`Target::luts`] say (one table each, in that order; empty for
/// none). `progress` is called as each stage starts.
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
    let preview = match &opts.preview {
        None => None,
        Some(p) => Some(timed_stage(Stage::Preview, progress, &mut timings, || {
            // The preview shades with the default model; another target's LUTs don't do.
            let split_sum_lut = opts
                .target
                .luts
                .iter()
                .zip(luts)
                .find(|(s, _)| s.model == LutModel::default() && s.channels == LutChannels::Model)
                .map(|(_, l)| l);
            preview_baked(backend, &baked, split_sum_lut, p)
        })?),
    };
    let BakedEnvironment {
        specular,
        irradiance,
        sheen,
        sh,
        ..
    } = baked;

    progress(Stage::Write);
    let write_start = Instant::now();
    let target = opts.target;
    if opts.container != Container::Exr {
        if let Some(w) = target.format_warning(opts.pixel_format) {
            warnings.push(format!("--target {}: {w}", target.name));
        }
    }
    let specular = target.orientation.apply(specular);
    let dir = output_dir(out_root, input);
    let stem = crate::io::input::input_stem(input);
    let mut out = Staging::default();
    match target.files {
        FileSet::Standard => {
            let irradiance = target
                .irradiance
                .then(|| target.orientation.apply(irradiance));
            stage_standard(
                &mut out,
                &dir,
                opts,
                &specular,
                irradiance.as_ref(),
                sh.as_ref(),
            )?;
        }
        FileSet::FilamentKtx1 => {
            stage_filament(&mut out, &dir, &stem, opts, &specular, sh.as_ref())?;
        }
        FileSet::BabylonEnv => {
            if let Some(w) = stage_babylon(&mut out, &dir, &stem, opts, &specular, sh.as_ref())? {
                warnings.push(w);
            }
        }
        FileSet::GltfSampleViewer => {
            let irradiance = target.orientation.apply(irradiance);
            let sheen = sheen.map(|s| target.orientation.apply(s));
            stage_gltf(&mut out, &dir, opts, &specular, &irradiance, sheen.as_ref())?;
        }
    }
    stage_luts(&mut out, &dir, target, luts)?;
    if let Some(p) = &preview {
        out.add(
            dir.join("preview.png"),
            p.png.clone(),
            ("preview", "png (8-bit sRGB)", p.width, 1),
        );
    }
    // The manifest lists every other file (it cannot hold its own hash).
    let manifest = manifest_json(
        input,
        backend,
        opts,
        luts.first().map(|l| l.width),
        preview.as_ref(),
        &out.outputs,
    );
    let manifest_path = dir.join("manifest.json");
    out.add(
        manifest_path,
        manifest.into_bytes(),
        ("manifest", "json", 0, 0),
    );
    write_all_atomic(&out.staged)?;
    timings.push((Stage::Write, write_start.elapsed().as_secs_f64()));

    Ok(BakeReport {
        out_dir: dir,
        outputs: out.outputs,
        timings,
        warnings,
        preview,
    })
}

/// DESIGN.md's file set ([`FileSet::Standard`]): the specular chain and (when given) the
/// irradiance cube in the bake's container, sh.json and the LUT.
fn stage_standard(
    out: &mut Staging,
    dir: &Path,
    opts: &BakeOptions,
    specular: &Cubemap,
    irradiance: Option<&Cubemap>,
    sh: Option<&ShCoefficients>,
) -> Result<()> {
    let fmt = match opts.container {
        Container::Exr => "rgb32f (OpenEXR cross)",
        _ => opts.pixel_format.name(),
    };
    out.add_cube(
        encode_cube(dir, "specular", specular, opts)?,
        "specular",
        fmt,
        specular,
    );
    if let Some(irradiance) = irradiance {
        out.add_cube(
            encode_cube(dir, "irradiance", irradiance, opts)?,
            "irradiance",
            fmt,
            irradiance,
        );
    }
    if let Some(sh) = sh {
        out.add(
            dir.join("sh.json"),
            sh_json(sh).into_bytes(),
            ("sh", "json", 0, 0),
        );
    }
    Ok(())
}

/// The LUT files of `target` (`luts` holds their tables in the same order).
fn stage_luts(out: &mut Staging, dir: &Path, target: &Target, luts: &[BrdfLut]) -> Result<()> {
    for (spec, lut) in target.luts.iter().zip(luts) {
        let path = dir.join(spec.file);
        let bytes = match spec.channels {
            LutChannels::Model => encode_lut(&path, lut, LutWriteOptions::default())?,
            LutChannels::FirstInBlue => {
                let blue = BrdfLut {
                    third: Some(lut.data.iter().map(|t| t[0]).collect()),
                    ..BrdfLut::new(lut.width, lut.height, vec![[0.0; 2]; lut.data.len()])
                };
                encode_lut(&path, &blue, LutWriteOptions::default())?
            }
        };
        out.add(path, bytes, ("brdf_lut", spec.format(), lut.width, 1));
    }
    Ok(())
}

/// The E/π coefficients in the engine's frame with the basis constants folded in: the
/// plain polynomial Filament's shader evaluates (cmgen `--sh-shader`) and Babylon's
/// spherical polynomial is made of.
pub fn engine_sh(sh: &ShCoefficients, target: &Target) -> [[f32; 3]; 9] {
    let frame = target.orientation.frame.matrix();
    sh_prescaled(&sh_rotated(&sh.irradiance, frame))
}

/// cmgen's deploy set for Filament ([`FileSet::FilamentKtx1`]): `<stem>_ibl.ktx` (the
/// chain, the SH under the key `sh`), `<stem>_skybox.ktx` (level 0) and `sh.txt`.
fn stage_filament(
    out: &mut Staging,
    dir: &Path,
    stem: &str,
    opts: &BakeOptions,
    specular: &Cubemap,
    sh: Option<&ShCoefficients>,
) -> Result<()> {
    let sh = sh.map(|sh| engine_sh(sh, opts.target));
    let fmt = opts.pixel_format.name();
    let ktx = |path: &Path, cube: &Cubemap, key_values: &[(&str, &[u8])]| {
        ktx1::encode(&encode_texture(cube, opts.pixel_format), key_values).map_err(|message| {
            Error::Encode {
                path: path.to_path_buf(),
                format: "KTX 1",
                message,
            }
        })
    };
    let ibl = dir.join(format!("{stem}_ibl.ktx"));
    let sh_value = sh.as_ref().map(sh_text::ktx_value);
    let key_values: Vec<(&str, &[u8])> = sh_value.iter().map(|v| ("sh", v.as_slice())).collect();
    let bytes = ktx(&ibl, specular, &key_values)?;
    let levels = specular.levels.len() as u32;
    out.add(ibl, bytes, ("specular", fmt, specular.size, levels));
    let skybox_cube = Cubemap {
        size: specular.size,
        levels: vec![specular.levels[0].clone()],
    };
    let skybox = dir.join(format!("{stem}_skybox.ktx"));
    let bytes = ktx(&skybox, &skybox_cube, &[])?;
    out.add(skybox, bytes, ("skybox", fmt, specular.size, 1));
    if let Some(sh) = &sh {
        out.add(
            dir.join("sh.txt"),
            sh_text::sh_txt(sh).into_bytes(),
            ("sh", "text (cmgen --sh-shader)", 0, 0),
        );
    }
    Ok(())
}

/// The glTF Sample Viewer's environment ([`FileSet::GltfSampleViewer`]), as
/// glTF-IBL-Sampler lays it out: `lambertian/diffuse.ktx2` (E/π), `ggx/specular.ktx2` and
/// `charlie/sheen.ktx2` (the Charlie chain, in the GGX chain's layout).
fn stage_gltf(
    out: &mut Staging,
    dir: &Path,
    opts: &BakeOptions,
    specular: &Cubemap,
    irradiance: &Cubemap,
    sheen: Option<&Cubemap>,
) -> Result<()> {
    let fmt = opts.pixel_format.name();
    let mut cube = |folder: &str, name: &str, kind: &'static str, cube: &Cubemap| -> Result<()> {
        out.add_cube(
            encode_cube(&dir.join(folder), name, cube, opts)?,
            kind,
            fmt,
            cube,
        );
        Ok(())
    };
    cube("lambertian", "diffuse", "irradiance", irradiance)?;
    cube("ggx", "specular", "specular", specular)?;
    if let Some(sheen) = sheen {
        cube("charlie", "sheen", "sheen", sheen)?;
    }
    Ok(())
}

/// Babylon's prefiltered environment ([`FileSet::BabylonEnv`]): `<stem>.env`, the whole
/// chain in RGBD and the irradiance as a spherical polynomial. Returns a warning when
/// level 0 holds radiance RGBD cannot (above 255).
fn stage_babylon(
    out: &mut Staging,
    dir: &Path,
    stem: &str,
    opts: &BakeOptions,
    specular: &Cubemap,
    sh: Option<&ShCoefficients>,
) -> Result<Option<String>> {
    let path = dir.join(format!("{stem}.env"));
    let enc_err = |message: String| Error::Encode {
        path: path.clone(),
        format: "Babylon .env",
        message,
    };
    let sh = sh.ok_or_else(|| enc_err("a .env carries the irradiance SH".into()))?;
    let polynomial = env::SphericalPolynomial::from_prescaled(&engine_sh(sh, opts.target));
    let bytes = env::encode(specular, &polynomial).map_err(enc_err)?;
    let (clipped, largest) = specular.levels[0]
        .iter()
        .map(|t| t[0].max(t[1]).max(t[2]))
        .filter(|&m| m > env::RGBD_MAX)
        .fold((0usize, 0.0f32), |(n, top), m| (n + 1, top.max(m)));
    let levels = specular.levels.len() as u32;
    out.add(
        path.clone(),
        bytes,
        ("specular", "rgbd png", specular.size, levels),
    );
    Ok((clipped > 0).then(|| {
        format!(
            "{}: {clipped} texels of level 0 are brighter than the {} a .env (RGBD) holds (the largest {largest:.0}) and are clipped; --exposure -N with scene.environmentIntensity = 2^N keeps them",
            path.display(),
            env::RGBD_MAX
        )
    }))
}

/// manifest.json's root.
#[derive(Serialize)]
struct Manifest<'a> {
    tool: &'a str,
    version: &'a str,
    input: String,
    backend: String,
    target: TargetRecord<'a>,
    parameters: Parameters<'a>,
    #[serde(skip_serializing_if = "Option::is_none")]
    preview: Option<PreviewRecord<'a>>,
    outputs: Vec<OutputEntry<'a>>,
}

/// How preview.png was made and what it measured.
#[derive(Serialize)]
struct PreviewRecord<'a> {
    cell: u32,
    exposure: f32,
    tone_mapping: &'a str,
    truth_samples: u32,
    split_sum: &'a str,
    truth: &'a str,
    relative_difference: &'a str,
    spheres: &'a [SphereStats],
}

/// What the target implies, so a reader of the manifest knows how to sample the files.
#[derive(Serialize)]
struct TargetRecord<'a> {
    name: &'a str,
    orientation: &'a str,
    notes: &'a [&'a str],
}

/// Every parameter of the bake.
#[derive(Serialize)]
struct Parameters<'a> {
    specular_size: u32,
    specular_levels: u32,
    min_mip_size: u32,
    roughness_per_mip: &'a str,
    roughest_level: &'a str,
    irradiance_size: u32,
    irradiance: &'a str,
    container: &'a str,
    pixel_format: &'a str,
    zstd: Option<i32>,
    samples: u32,
    rotate_degrees: f32,
    exposure_ev: f32,
    lut_size: Option<u32>,
}

/// One output file.
#[derive(Serialize)]
struct OutputEntry<'a> {
    file: String,
    kind: &'a str,
    format: &'a str,
    size: u32,
    levels: u32,
    bytes: usize,
    sha256: &'a str,
}

/// `manifest.json`: tool version, backend, target, every parameter, every output (file
/// name, kind, format, size, levels, bytes, SHA-256). No timestamps, so equal bakes give
/// equal manifests.
fn manifest_json(
    input: &Path,
    backend: &dyn Backend,
    opts: &BakeOptions,
    lut_size: Option<u32>,
    preview: Option<&Preview>,
    outputs: &[OutputRecord],
) -> String {
    let target = opts.target;
    to_json(&Manifest {
        tool: "splitsum",
        version: env!("CARGO_PKG_VERSION"),
        input: input.to_string_lossy().into_owned(),
        backend: backend.identity(),
        target: TargetRecord {
            name: target.name,
            orientation: target.orientation.description,
            notes: target.notes,
        },
        parameters: Parameters {
            specular_size: opts.specular_size,
            specular_levels: opts.specular_chain().levels,
            min_mip_size: opts.min_mip_size,
            roughness_per_mip: target.roughness.formula(),
            roughest_level: "least-squares fit of the irradiance (E / pi) for bilinear lookups, when the irradiance cube is at least twice as fine",
            irradiance_size: opts.irradiance_size,
            irradiance: "E / pi",
            container: opts.container_name(),
            pixel_format: opts.pixel_format.name(),
            zstd: opts.zstd,
            samples: opts.samples,
            rotate_degrees: opts.rotate_degrees,
            exposure_ev: opts.exposure_ev,
            lut_size,
        },
        preview: preview.zip(opts.preview.as_ref()).map(|(p, o)| PreviewRecord {
            cell: o.cell,
            exposure: p.exposure,
            tone_mapping: "Khronos PBR Neutral, then sRGB",
            truth_samples: o.truth_samples,
            split_sum: "prefiltered(reflect(-v, n), lod(r)) * (F0 * A + B) + irradiance(n) * albedo * (1 - F_roughness(n.v)) * (1 - metallic)",
            truth: "the integral of the same BRDF over the specular chain's level 0 with the real view direction: hot texels summed exactly, the rest by GGX visible-normal and cosine quasi-Monte Carlo",
            relative_difference: "on each pixel's luminance Y: mean_relative = sum |Y_split_sum - Y_truth| / sum Y_truth over the sphere, worst_relative = the largest |Y_split_sum - Y_truth| / Y_truth of one pixel",
            spheres: &p.stats,
        }),
        outputs: outputs
            .iter()
            .map(|o| OutputEntry {
                file: o
                    .path
                    .file_name()
                    .map(|n| n.to_string_lossy().into_owned())
                    .unwrap_or_default(),
                kind: o.kind,
                format: &o.format,
                size: o.size,
                levels: o.levels,
                bytes: o.bytes,
                sha256: &o.sha256,
            })
            .collect(),
    })
}

/// Reads back the light a generic-target KTX2 bake wrote into `dir`: the specular chain,
/// the irradiance cube and, when it was written, the LUT (`None` otherwise). Other targets'
/// files are mirrored and laid out for one engine; [`bake`] previews those in memory.
pub fn read_bake_dir(dir: &Path) -> Result<(BakedEnvironment, Option<BrdfLut>)> {
    let manifest_path = dir.join("manifest.json");
    if !manifest_path.is_file() {
        return Err(Error::UnsupportedInput {
            path: dir.to_path_buf(),
            message: "not a folder `splitsum bake` wrote: it has no manifest.json".into(),
        });
    }
    let text = std::fs::read_to_string(&manifest_path).map_err(|e| Error::io(&manifest_path, e))?;
    let bad = |message: String| Error::Decode {
        path: manifest_path.clone(),
        format: "JSON",
        message,
    };
    let manifest: serde_json::Value =
        serde_json::from_str(&text).map_err(|e| bad(e.to_string()))?;
    let field = |pointer: &str| {
        manifest.pointer(pointer).ok_or_else(|| {
            bad(format!(
                "no {pointer} (not a manifest splitsum bake wrote?)"
            ))
        })
    };
    let target = field("/target/name")?.as_str().unwrap_or_default();
    let container = field("/parameters/container")?.as_str().unwrap_or_default();
    if target != GENERIC.name || container != Container::Ktx2.extension() {
        return Err(Error::UnsupportedInput {
            path: dir.to_path_buf(),
            message: format!(
                "a preview reads bakes made with --target generic --container ktx2; this one is --target {target} --container {container}: add --preview to that bake instead"
            ),
        });
    }
    let levels = field("/parameters/specular_levels")?
        .as_u64()
        .ok_or_else(|| bad("/parameters/specular_levels is not a number".into()))?;
    let specular_path = dir.join("specular.ktx2");
    let specular = crate::io::input::read_ktx2_cube_chain(&specular_path)?;
    if specular.levels.len() as u64 != levels {
        return Err(Error::Decode {
            path: specular_path,
            format: "KTX2",
            message: format!(
                "{} levels, the manifest says {levels}",
                specular.levels.len()
            ),
        });
    }
    let irradiance = crate::io::input::read_ktx2_cube(&dir.join("irradiance.ktx2"))?;
    let lut_path = dir.join("brdf_lut.png");
    let lut = if lut_path.exists() {
        Some(crate::io::lut::read_lut_png(&lut_path)?)
    } else {
        None
    };
    let chain = SpecularChain {
        levels: levels as u32,
        roughness: GENERIC.roughness,
    };
    Ok((
        BakedEnvironment {
            specular,
            chain,
            irradiance,
            sh: None,
            sheen: None,
        },
        lut,
    ))
}
