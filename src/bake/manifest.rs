//! `manifest.json`, one serde type both ways: what a bake writes beside its files (tool
//! version, backend, the target and how its engine reads the files, every parameter, every
//! output with its size, format, levels, bytes and SHA-256), and what [`read_bake_dir`]
//! reads back. No timestamps, so equal bakes give equal manifests.

use std::path::Path;

use serde::{Deserialize, Serialize};

use crate::bake::options::BakeOptions;
use crate::environment::sun::{Sun, SunMode};
use crate::environment::Cubemap;
use crate::io::staging::OutputRecord;
use crate::io::to_json;
use crate::math::brdf::alpha_from_roughness;
use crate::plan::astc;
use crate::plan::bc6h::{ENCODER, ENCODER_VERSION};
use crate::plan::chain::SpecularChain;
use crate::plan::lut::BrdfLut;
use crate::plan::shading::Shading;
use crate::plan::sheen::sheen_level_roughness;
use crate::stages::light::BakedEnvironment;
use crate::stages::preview::{
    Preview, SphereStats, RELATIVE_DIFFERENCE_DEFINITION, TRUTH_DEFINITION,
};
use crate::targets::generic::read_sun_json;
use crate::targets::GENERIC;
use crate::{Error, Result};

/// `manifest.json`'s root.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Manifest {
    /// "splitsum".
    pub tool: String,
    /// The crate's version.
    pub version: String,
    /// The input as given.
    pub input: String,
    /// The backend's identity (`Backend::identity`).
    pub backend: String,
    /// The target.
    pub target: TargetRecord,
    /// Every parameter of the bake.
    pub parameters: Parameters,
    /// The sun: whether it was taken out, and what was found (in either mode).
    #[serde(default)]
    pub sun: SunRecord,
    /// How preview.png was made and what it measured, when there is one.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub preview: Option<PreviewRecord>,
    /// Every other file of the bake.
    pub outputs: Vec<OutputEntry>,
}

/// What the target implies, so a reader of the manifest knows how to sample the files.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct TargetRecord {
    /// The target's name.
    pub name: String,
    /// Its orientation, in words.
    pub orientation: String,
    /// How its engine reads the files.
    pub notes: Vec<String>,
}

/// Every parameter of the bake.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Parameters {
    /// Specular cube edge.
    pub specular_size: u32,
    /// Levels of the specular chain.
    pub specular_levels: u32,
    /// Edge of its smallest level.
    pub min_mip_size: u32,
    /// Roughness of mip m, as a formula.
    pub roughness_per_mip: String,
    /// Each level of the specular chain in numbers: its edge, the roughness it is
    /// prefiltered at and that roughness's α, as the bake computed them
    /// (`roughness_per_mip` evaluated). Empty when read from a manifest without the field.
    #[serde(default)]
    pub specular_chain_levels: Vec<ChainLevel>,
    /// Each level of the Charlie sheen chain, for a target that writes one (empty
    /// otherwise): the specular chain's edges and roughness, except level 0, which holds
    /// level 1's lobe (`plan::sheen::sheen_level_roughness`).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub sheen_chain_levels: Vec<ChainLevel>,
    /// How the roughest level is made.
    pub roughest_level: String,
    /// Irradiance cube edge.
    pub irradiance_size: u32,
    /// What the irradiance cube holds.
    pub irradiance: String,
    /// The cubes' container.
    pub container: String,
    /// Their pixel format.
    pub pixel_format: String,
    /// The encoder of a block format (BC6H), its version and preset.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub encoder: Option<EncoderRecord>,
    /// KTX2 Zstandard level.
    pub zstd: Option<i32>,
    /// GGX samples per texel of the importance-sampled levels.
    pub samples: u32,
    /// Rotation about +Y.
    pub rotate_degrees: f32,
    /// Exposure applied to the input.
    pub exposure_ev: f32,
    /// Edge of the LUTs written, if any.
    pub lut_size: Option<u32>,
}

/// One level of a prefiltered chain, in numbers.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct ChainLevel {
    /// The level m, 0 the largest.
    pub level: u32,
    /// Its edge in texels.
    pub size: u32,
    /// The perceptual roughness r its lobe is prefiltered at.
    pub roughness: f32,
    /// The lobe's α = r² (docs/conventions.md, "Roughness, BRDF").
    pub alpha: f32,
}

impl ChainLevel {
    /// The levels of a chain of `chain.levels` whose level 0 is `size`², level m at
    /// roughness `roughness(m)`.
    fn table(size: u32, chain: SpecularChain, roughness: impl Fn(u32) -> f32) -> Vec<Self> {
        (0..chain.levels)
            .map(|m| {
                let r = roughness(m);
                ChainLevel {
                    level: m,
                    size: Cubemap::mip_size(size, m),
                    roughness: r,
                    alpha: alpha_from_roughness(r),
                }
            })
            .collect()
    }
}

/// The sun of the bake's environment.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct SunRecord {
    /// `keep` (baked into the IBL) or `split` (taken out; `sun.json` holds the lights).
    pub mode: SunMode,
    /// The compact lights found, the sun first, in the generic frame (rotation applied);
    /// empty when there is none.
    pub lights: Vec<Sun>,
}

/// The encoder of a block format.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct EncoderRecord {
    /// The encoder.
    pub name: String,
    /// Its version.
    pub version: String,
    /// Its preset (which modes and partitions it searches).
    pub preset: String,
    /// The backend it ran on (`cpu`, or the GPU's WGSL port).
    pub ran_on: String,
}

impl EncoderRecord {
    /// The encoder of `opts`'s pixel format, when it is a block format: BC6H on
    /// `bc6h_ran_on`, ASTC with astc-encoder on the CPU.
    fn of(opts: &BakeOptions, bc6h_ran_on: &str) -> Option<EncoderRecord> {
        let format = opts.pixel_format();
        if format.is_astc() {
            Some(EncoderRecord {
                name: astc::ENCODER.into(),
                version: astc::ENCODER_VERSION.into(),
                preset: opts.astc_quality.name().into(),
                ran_on: "cpu".into(),
            })
        } else {
            format.is_block().then(|| EncoderRecord {
                name: ENCODER.into(),
                version: ENCODER_VERSION.into(),
                preset: opts.bc6h_quality.name().into(),
                ran_on: bc6h_ran_on.into(),
            })
        }
    }
}

/// How preview.png was made and what it measured.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct PreviewRecord {
    /// Edge of one sphere's cell.
    pub cell: u32,
    /// The linear exposure factor.
    pub exposure: f32,
    /// The tone mapping.
    pub tone_mapping: String,
    /// Quasi-Monte Carlo points of the truth.
    pub truth_samples: u32,
    /// The split-sum render's definition.
    pub split_sum: String,
    /// The truth render's definition.
    pub truth: String,
    /// The statistics' definition.
    pub relative_difference: String,
    /// Per sphere.
    pub spheres: Vec<SphereRecord>,
}

/// One sphere of the preview ([`SphereStats`]).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct SphereRecord {
    /// The material's name.
    pub material: String,
    /// The roughness.
    pub roughness: f32,
    /// Σ |ΔY| / ΣY over the sphere.
    pub mean_relative: f32,
    /// The largest |ΔY| / Y of one pixel, Y floored (`RELATIVE_DIFFERENCE_DEFINITION`).
    pub worst_relative: f32,
    /// The sphere's mean Y_truth (absent from older manifests).
    #[serde(default)]
    pub truth_luminance: f32,
    /// The sphere's mean Y_split-sum (absent from older manifests).
    #[serde(default)]
    pub split_sum_luminance: f32,
}

/// One output file.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct OutputEntry {
    /// File name.
    pub file: String,
    /// What it holds.
    pub kind: String,
    /// Pixel or file format.
    pub format: String,
    /// Edge in texels (0 for non-images).
    pub size: u32,
    /// Mip levels (0 for non-images).
    pub levels: u32,
    /// File size.
    pub bytes: usize,
    /// SHA-256, hex.
    pub sha256: String,
}

impl From<&SphereStats> for SphereRecord {
    fn from(s: &SphereStats) -> Self {
        SphereRecord {
            material: s.material.to_string(),
            roughness: s.roughness,
            mean_relative: s.mean_relative,
            worst_relative: s.worst_relative,
            truth_luminance: s.truth_luminance,
            split_sum_luminance: s.split_sum_luminance,
        }
    }
}

impl Manifest {
    /// The manifest of a bake of `input` with `opts` on the backend `backend` (its
    /// identity) that wrote `outputs` (and the preview, when there is one); the lights
    /// found are set in [`Manifest::sun`] by the caller.
    pub fn new(
        input: &Path,
        backend: String,
        bc6h_ran_on: &str,
        opts: &BakeOptions,
        lut_size: Option<u32>,
        preview: Option<&Preview>,
        outputs: &[OutputRecord],
    ) -> Self {
        let target = opts.target;
        let chain = opts.specular_chain();
        Manifest {
            tool: "splitsum".into(),
            version: env!("CARGO_PKG_VERSION").into(),
            input: input.to_string_lossy().into_owned(),
            backend,
            target: TargetRecord {
                name: target.name.into(),
                orientation: target.orientation.description.into(),
                notes: target.notes.iter().map(|n| n.to_string()).collect(),
            },
            parameters: Parameters {
                specular_size: opts.specular_size,
                specular_levels: chain.levels,
                min_mip_size: opts.min_mip_size,
                roughness_per_mip: target.roughness.formula().into(),
                specular_chain_levels: ChainLevel::table(opts.specular_size, chain, |m| {
                    chain.mip_roughness(m)
                }),
                sheen_chain_levels: match opts.light_options().sheen {
                    true => ChainLevel::table(opts.specular_size, chain, |m| {
                        sheen_level_roughness(&chain, m)
                    }),
                    false => Vec::new(),
                },
                roughest_level: "least-squares fit of the irradiance (E / pi) for bilinear lookups, when the irradiance cube is at least twice as fine".into(),
                irradiance_size: opts.irradiance_size,
                irradiance: "E / pi".into(),
                container: opts.container_name().into(),
                pixel_format: opts.pixel_format().name().into(),
                encoder: EncoderRecord::of(opts, bc6h_ran_on),
                zstd: opts.zstd,
                samples: opts.samples,
                rotate_degrees: opts.rotate_degrees,
                exposure_ev: opts.exposure_ev,
                lut_size,
            },
            sun: SunRecord {
                mode: opts.sun,
                lights: Vec::new(),
            },
            preview: preview.zip(opts.preview.as_ref()).map(|(p, o)| PreviewRecord {
                cell: o.cell,
                exposure: p.exposure,
                tone_mapping: "Khronos PBR Neutral, then sRGB".into(),
                truth_samples: o.truth_samples,
                split_sum: match o.shading == Shading::GENERIC {
                    true => "mix(prefiltered(d, lod(r)), irradiance(n), r^4) * (F0 * A + B) + irradiance(n) * albedo * (1 - F0) * (1 - W(n.v)) * (1 - metallic), d and lod as the README's recipe reads them (math::lookup), W the cosine-weighted mean of (1 - v.h)^5 (math::brdf::diffuse_fresnel_weight)".into(),
                    false => format!("as {}'s shader: {}", o.shading.name, o.shading.describe()),
                },
                truth: match o.shading == Shading::GENERIC {
                    true => TRUTH_DEFINITION.into(),
                    false => format!("{TRUTH_DEFINITION}; the BRDF is {}'s light BRDF", o.shading.name),
                },
                relative_difference: RELATIVE_DIFFERENCE_DEFINITION.into(),
                spheres: p.stats.iter().map(SphereRecord::from).collect(),
            }),
            outputs: outputs
                .iter()
                .map(|o| OutputEntry {
                    file: o
                        .path
                        .file_name()
                        .map(|n| n.to_string_lossy().into_owned())
                        .unwrap_or_default(),
                    kind: o.kind.into(),
                    format: o.format.clone(),
                    size: o.size,
                    levels: o.levels,
                    bytes: o.bytes,
                    sha256: o.sha256.clone(),
                })
                .collect(),
        }
    }

    /// Pretty JSON with a final newline.
    pub fn to_json(&self) -> String {
        to_json(self)
    }

    /// Reads `manifest.json` of the bake folder `dir`.
    pub fn read(dir: &Path) -> Result<Manifest> {
        let path = dir.join("manifest.json");
        if !path.is_file() {
            return Err(Error::UnsupportedInput {
                path: dir.to_path_buf(),
                message: "not a folder `splitsum bake` wrote: it has no manifest.json".into(),
            });
        }
        let text = std::fs::read_to_string(&path).map_err(|e| Error::io(&path, e))?;
        serde_json::from_str(&text).map_err(|e| Error::Decode {
            path,
            format: "JSON",
            message: format!("{e} (not a manifest splitsum bake wrote?)"),
        })
    }
}

/// Reads back the light a generic-target KTX2 bake wrote into `dir`: the specular chain,
/// the irradiance cube and, when it was written, the LUT (`None` otherwise). Other targets'
/// files are mirrored and laid out for one engine; a bake previews those in memory.
pub fn read_bake_dir(dir: &Path) -> Result<(BakedEnvironment, Option<BrdfLut>)> {
    let manifest = Manifest::read(dir)?;
    let (target, container) = (&manifest.target.name, &manifest.parameters.container);
    if *target != GENERIC.name || container != "ktx2" {
        return Err(Error::UnsupportedInput {
            path: dir.to_path_buf(),
            message: format!(
                "a preview reads bakes made for the generic target in KTX2; this one is for target {target} in {container}: add a preview to that bake instead (bake --preview)"
            ),
        });
    }
    let levels = manifest.parameters.specular_levels;
    let specular_path = dir.join("specular.ktx2");
    let specular = crate::io::ktx2::read_cube_chain(&specular_path)?;
    if specular.levels.len() as u32 != levels {
        return Err(Error::Decode {
            path: specular_path,
            format: "KTX2",
            message: format!(
                "{} levels, the manifest says {levels}",
                specular.levels.len()
            ),
        });
    }
    let irradiance: Cubemap = crate::io::ktx2::read_cube(&dir.join("irradiance.ktx2"))?;
    let lut_path = dir.join("brdf_lut.png");
    let lut = if lut_path.exists() {
        Some(crate::io::lut::read_lut_png(&lut_path)?)
    } else {
        None
    };
    let chain = SpecularChain {
        levels,
        roughness: GENERIC.roughness,
    };
    // The environment as seen, for a ground truth: a split bake's background.
    let background_path = dir.join("background.ktx2");
    let background = match background_path.is_file() {
        true => Some(crate::io::ktx2::read_cube(&background_path)?),
        false => None,
    };
    let sun_path = dir.join("sun.json");
    let lights = match manifest.sun.mode {
        SunMode::Split if sun_path.is_file() => read_sun_json(&sun_path)?,
        SunMode::Split => Vec::new(),
        SunMode::Keep => manifest.sun.lights.clone(),
    };
    Ok((
        BakedEnvironment {
            specular,
            chain,
            irradiance,
            sh: None,
            sheen: None,
            lights,
            sun_mode: manifest.sun.mode,
            background,
            truth: None,
        },
        lut,
    ))
}
