//! The whole bake of one environment: cubemap, prefiltered specular, irradiance, SH, LUT,
//! and a manifest. Every output of an input is staged and renamed into place together,
//! so a failed bake leaves earlier outputs untouched and no partial files.

use std::path::{Path, PathBuf};
use std::time::Instant;

use sha2::{Digest, Sha256};

use crate::convert::environment_into_cube_with_irradiance;
use crate::cpu::prefilter_specular::chain_levels;
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
}

impl Default for BakeOptions {
    fn default() -> Self {
        BakeOptions {
            specular_size: 256,
            min_mip_size: crate::cpu::prefilter_specular::DEFAULT_MIN_MIP_SIZE,
            irradiance_size: 32,
            container: Container::Ktx2,
            pixel_format: PixelFormat::Rgba16f,
            zstd: None,
            samples: crate::cpu::prefilter_specular::DEFAULT_SAMPLES,
            rotate_degrees: 0.0,
            exposure_ev: 0.0,
        }
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

/// A JSON string literal.
fn json_string(s: &str) -> String {
    let mut out = String::from("\"");
    for c in s.chars() {
        match c {
            '"' => out.push_str("\\\""),
            '\\' => out.push_str("\\\\"),
            '\n' => out.push_str("\\n"),
            c if (c as u32) < 0x20 => out.push_str(&format!("\\u{:04x}", c as u32)),
            c => out.push(c),
        }
    }
    out.push('"');
    out
}

/// A JSON number for an f32 (shortest round-trip form; non-finite values never occur
/// because inputs are sanitised, but are written as 0 to keep the file valid).
fn json_f32(v: f32) -> String {
    if v.is_finite() {
        format!("{v:?}")
    } else {
        "0.0".into()
    }
}

/// `sh.json`: the coefficient order, the radiance projection and the E/π coefficients.
pub fn sh_json(sh: &ShCoefficients) -> String {
    let list = |c: &[[f32; 3]; 9]| {
        c.iter()
            .map(|v| {
                format!(
                    "[{}, {}, {}]",
                    json_f32(v[0]),
                    json_f32(v[1]),
                    json_f32(v[2])
                )
            })
            .collect::<Vec<_>>()
            .join(",\n    ")
    };
    format!(
        "{{\n  \"order\": \"{SH_ORDER}\",\n  \"radiance_sh9\": [\n    {}\n  ],\n  \"irradiance_sh9\": [\n    {}\n  ]\n}}\n",
        list(&sh.radiance),
        list(&sh.irradiance)
    )
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
        warnings,
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
    let levels = chain_levels(opts.specular_size, opts.min_mip_size);
    let mut specular =
        backend.prefilter_specular(&env, Some(&irradiance_source), levels, opts.samples)?;
    done(&mut timings);

    let done = timed(Stage::Irradiance, progress);
    let irradiance = backend.irradiance(&irradiance_source, opts.irradiance_size)?;
    // The r = 1 level is E/π; its texels are fitted to the finer irradiance cube for the
    // bilinear lookup a shader makes (see `cpu::roughest_level`).
    fit_roughest_level(&mut specular, &irradiance);
    done(&mut timings);

    let done = timed(Stage::Sh, progress);
    let sh = sh_project(&irradiance_source);
    done(&mut timings);

    let done = timed(Stage::Write, progress);
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
    for (path, bytes) in encode_cube(&dir, "irradiance", &irradiance, opts)? {
        out.add(path, bytes, ("irradiance", fmt, irradiance.size, 1));
    }
    out.add(
        dir.join("sh.json"),
        sh_json(&sh).into_bytes(),
        ("sh", "json", 0, 0),
    );
    if let Some(lut) = lut {
        let path = dir.join("brdf_lut.png");
        let bytes = encode_lut(&path, lut, LutWriteOptions::default())?;
        out.add(path, bytes, ("brdf_lut", "png rgb16", lut.width, 1));
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

/// `manifest.json`: tool version, backend, every parameter, every output (file name,
/// kind, format, size, levels, bytes, SHA-256). No timestamps, so equal bakes give equal
/// manifests.
fn manifest_json(
    input: &Path,
    backend: &dyn Backend,
    opts: &BakeOptions,
    lut_size: Option<u32>,
    outputs: &[OutputRecord],
) -> String {
    let file_name = |p: &Path| {
        p.file_name()
            .map(|n| n.to_string_lossy().into_owned())
            .unwrap_or_default()
    };
    let outs: Vec<String> = outputs
        .iter()
        .map(|o| {
            format!(
                "    {{\"file\": {}, \"kind\": {}, \"format\": {}, \"size\": {}, \"levels\": {}, \"bytes\": {}, \"sha256\": {}}}",
                json_string(&file_name(&o.path)),
                json_string(o.kind),
                json_string(&o.format),
                o.size,
                o.levels,
                o.bytes,
                json_string(&o.sha256)
            )
        })
        .collect();
    format!(
        "{{\n  \"tool\": \"splitsum\",\n  \"version\": {},\n  \"input\": {},\n  \"backend\": {},\n  \"parameters\": {{\n    \"specular_size\": {},\n    \"specular_levels\": {},\n    \"min_mip_size\": {},\n    \"roughness_per_mip\": \"m / (levels - 1)\",\n    \"roughest_level\": \"least-squares fit of the irradiance (E / pi) for bilinear lookups, when the irradiance cube is at least twice as fine\",\n    \"irradiance_size\": {},\n    \"irradiance\": \"E / pi\",\n    \"container\": {},\n    \"pixel_format\": {},\n    \"zstd\": {},\n    \"samples\": {},\n    \"rotate_degrees\": {},\n    \"exposure_ev\": {},\n    \"lut_size\": {}\n  }},\n  \"outputs\": [\n{}\n  ]\n}}\n",
        json_string(env!("CARGO_PKG_VERSION")),
        json_string(&input.to_string_lossy()),
        json_string(&backend.identity()),
        opts.specular_size,
        chain_levels(opts.specular_size, opts.min_mip_size),
        opts.min_mip_size,
        opts.irradiance_size,
        json_string(opts.container.extension()),
        json_string(opts.pixel_format.name()),
        opts.zstd.map(|z| z.to_string()).unwrap_or_else(|| "null".into()),
        opts.samples,
        json_f32(opts.rotate_degrees),
        json_f32(opts.exposure_ev),
        lut_size.map(|s| s.to_string()).unwrap_or_else(|| "null".into()),
        outs.join(",\n")
    )
}
