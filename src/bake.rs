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
use crate::environment::Cubemap;
use crate::io::atomic::write_all_atomic;
use crate::io::cubemap::{encode_texture, to_cross};
use crate::io::input::{load_input, InputOptions, LoadedEnvironment};
use crate::io::lut::{encode_lut, LutWriteOptions};
use crate::io::{dds, exr, ktx2, PixelFormat};
use crate::lut::BrdfLut;
use crate::math::sh::SH_ORDER;
use crate::target::{Target, GENERIC};
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
    /// Projecting onto spherical harmonics.
    Sh,
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
            Stage::Sh => "sh",
            Stage::Write => "write",
        }
    }

    /// All stages in order.
    pub const ALL: [Stage; 6] = [
        Stage::Load,
        Stage::Cubemap,
        Stage::Specular,
        Stage::Irradiance,
        Stage::Sh,
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
}

/// The output folder of `input` under `out_root`: `<out_root>/<stem>`.
pub fn output_dir(out_root: &Path, input: &Path) -> PathBuf {
    out_root.join(crate::io::input::input_stem(input))
}

/// Bakes one input into `output_dir(out_root, input)`. `lut`, when given, is written as
/// `brdf_lut.png` beside the other outputs. `progress` is called as each stage starts.
pub fn bake(
    backend: &dyn Backend,
    input: &Path,
    out_root: &Path,
    opts: &BakeOptions,
    lut: Option<&BrdfLut>,
    progress: &mut dyn FnMut(Stage),
) -> Result<BakeReport> {
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
    let mut timings = Vec::new();
    let timed = |stage: Stage, progress: &mut dyn FnMut(Stage)| {
        progress(stage);
        let t = Instant::now();
        move |timings: &mut Vec<(Stage, f64)>| timings.push((stage, t.elapsed().as_secs_f64()))
    };

    let done = timed(Stage::Load, progress);
    let LoadedEnvironment {
        env: source,
        mut warnings,
    } = load_input(
        input,
        &InputOptions {
            exposure_ev: opts.exposure_ev,
            cube_size: Some(opts.specular_size),
        },
    )?;
    done(&mut timings);

    let done = timed(Stage::Cubemap, progress);
    let (env, irradiance_source) = environment_into_cube_with_irradiance(
        backend,
        source,
        opts.specular_size,
        true,
        opts.rotate_degrees,
    )?;
    done(&mut timings);

    let done = timed(Stage::Specular, progress);
    let chain = opts.specular_chain();
    let mut specular =
        backend.prefilter_specular(&env, Some(&irradiance_source), chain, opts.samples)?;
    done(&mut timings);

    let done = timed(Stage::Irradiance, progress);
    let irradiance = backend.irradiance(&irradiance_source, opts.irradiance_size)?;
    // The r = 1 level is E/π; its texels are fitted to the finer irradiance cube for the
    // bilinear lookup a shader makes (see `cpu::roughest_level`).
    fit_roughest_level(&mut specular, &irradiance);
    done(&mut timings);

    let done = timed(Stage::Sh, progress);
    let sh = opts.sh.then(|| sh_project(&irradiance_source));
    done(&mut timings);

    let done = timed(Stage::Write, progress);
    let target = opts.target;
    if opts.container != Container::Exr {
        if let Some(w) = target.format_warning(opts.pixel_format) {
            warnings.push(format!("--target {}: {w}", target.name));
        }
    }
    let specular = target.orientation.apply(specular);
    let dir = output_dir(out_root, input);
    let mut out = Staging::default();
    let fmt = match opts.container {
        Container::Exr => "rgb32f (OpenEXR cross)",
        _ => opts.pixel_format.name(),
    };
    for (path, bytes) in encode_cube(&dir, "specular", &specular, opts)? {
        let levels = specular.levels.len() as u32;
        out.add(path, bytes, ("specular", fmt, specular.size, levels));
    }
    if target.irradiance {
        let irradiance = target.orientation.apply(irradiance);
        for (path, bytes) in encode_cube(&dir, "irradiance", &irradiance, opts)? {
            out.add(path, bytes, ("irradiance", fmt, irradiance.size, 1));
        }
    }
    if let Some(sh) = &sh {
        out.add(
            dir.join("sh.json"),
            sh_json(sh).into_bytes(),
            ("sh", "json", 0, 0),
        );
    }
    if let Some(lut) = lut {
        let path = dir.join(target.lut_file.file_name());
        let bytes = encode_lut(&path, lut, LutWriteOptions::default())?;
        out.add(
            path,
            bytes,
            ("brdf_lut", target.lut_file.format(), lut.width, 1),
        );
    }
    // The manifest lists every other file (it cannot hold its own hash).
    let manifest = manifest_json(input, backend, opts, lut.map(|l| l.width), &out.outputs);
    let manifest_path = dir.join("manifest.json");
    out.add(
        manifest_path,
        manifest.into_bytes(),
        ("manifest", "json", 0, 0),
    );
    write_all_atomic(&out.staged)?;
    done(&mut timings);

    Ok(BakeReport {
        out_dir: dir,
        outputs: out.outputs,
        timings,
        warnings,
    })
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
    outputs: Vec<OutputEntry<'a>>,
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
            orientation: target.orientation.description(),
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
            container: opts.container.extension(),
            pixel_format: opts.pixel_format.name(),
            zstd: opts.zstd,
            samples: opts.samples,
            rotate_degrees: opts.rotate_degrees,
            exposure_ev: opts.exposure_ev,
            lut_size,
        },
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
