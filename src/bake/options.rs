//! What a bake can be asked for ([`BakeOptions`]), each target's defaults, and the check
//! of every option before any input is read; errors name the option as its field.

use crate::backend::BackendChoice;
use crate::environment::sun::SunMode;
use crate::io::cubemap::Container;
use crate::io::input::InputOptions;
use crate::io::PixelFormat;
use crate::plan::astc::AstcQuality;
use crate::plan::bc6h::Bc6hQuality;
use crate::plan::chain::{chain_levels, SpecularChain, DEFAULT_SAMPLES};
use crate::stages::convert::validate_cube_size;
use crate::stages::light::LightOptions;
use crate::stages::preview::{validate_options as validate_preview, PreviewOptions};
use crate::targets::{Target, GENERIC};
use crate::{Error, Result};

/// Largest GGX sample count per texel.
pub const MAX_SAMPLES: u32 = 65536;

/// Everything a bake can be asked for. Start from [`BakeOptions::for_target`] (or
/// [`Default`], the generic target) and change what you need.
#[derive(Clone, Debug)]
pub struct BakeOptions {
    /// The engine the files are for: orientation, chain layout and which files are
    /// written come from it (pixel format, zstd, minimum mip size, SH and LUTs are its
    /// defaults in [`BakeOptions::for_target`], overridable here).
    pub target: &'static Target,
    /// Where the kernels run. [`BackendChoice::Auto`] falls back to the CPU when no
    /// adapter exists, and redoes an input on the CPU when the GPU fails during it.
    pub backend: BackendChoice,
    /// Specular cube edge (a power of two from 1 to 8192).
    pub specular_size: u32,
    /// Edge of the smallest specular mip (a power of two; 1 gives the full chain): the
    /// chain has log2(specular_size / min_mip_size) + 1 levels (one when the specular size
    /// is not larger).
    pub min_mip_size: u32,
    /// Irradiance cube edge (a power of two from 1 to 8192).
    pub irradiance_size: u32,
    /// Container of the cubes: KTX2, DDS or OpenEXR (crosses, one file per level), for the
    /// targets whose file set does not fix it.
    pub container: Container,
    /// Pixel format of KTX2/DDS/KTX outputs; `None` for the target's
    /// ([`Target::pixel_format`]). Refused for a target whose files have no pixel format
    /// (Babylon's `.env` is RGBD PNGs).
    pub pixel_format: Option<PixelFormat>,
    /// KTX2 Zstandard level (1 to 22), or none.
    pub zstd: Option<i32>,
    /// How hard the BC6H encoder searches, for the BC6H pixel format.
    pub bc6h_quality: Bc6hQuality,
    /// How hard astc-encoder searches, for the ASTC pixel formats.
    pub astc_quality: AstcQuality,
    /// GGX samples per texel for importance-sampled levels (1 to 65536).
    pub samples: u32,
    /// Rotation about +Y in degrees.
    pub rotate_degrees: f32,
    /// Exposure in EV: the input's radiance is multiplied by 2^EV.
    pub exposure_ev: f32,
    /// Write the SH (`sh.json`, or the engine's own place for them).
    pub sh: bool,
    /// Write the target's LUT files ([`Target::luts`]).
    pub luts: bool,
    /// Render `preview.png` (split-sum against ground truth).
    pub preview: Option<PreviewOptions>,
    /// Whether the sun is taken out of the environment and written as a light
    /// ([`SunMode::Split`]) or baked into the IBL ([`SunMode::Keep`]); it is found and
    /// recorded in the manifest either way.
    pub sun: SunMode,
    /// Keep the environment as read at its own resolution for a ground truth
    /// ([`BakedEnvironment::truth`](crate::BakedEnvironment::truth)), as the viewer's
    /// truth view reads it; a bake with a preview keeps it anyway.
    pub ground_truth: bool,
}

impl BakeOptions {
    /// The defaults of `target`: its pixel format, supercompression, minimum mip size, SH
    /// and LUT files; 256² specular, 32² irradiance, KTX2, the automatic backend.
    pub fn for_target(target: &'static Target) -> Self {
        BakeOptions {
            target,
            backend: BackendChoice::Auto,
            specular_size: 256,
            min_mip_size: target.min_mip_size,
            irradiance_size: 32,
            container: Container::Ktx2,
            pixel_format: None,
            zstd: target.zstd,
            bc6h_quality: Bc6hQuality::default(),
            astc_quality: AstcQuality::default(),
            samples: DEFAULT_SAMPLES,
            rotate_degrees: 0.0,
            exposure_ev: 0.0,
            sh: target.sh,
            luts: target.lut,
            preview: None,
            sun: SunMode::Keep,
            ground_truth: false,
        }
    }

    /// The pixel format of the cubes: the one asked for, or the target's.
    pub fn pixel_format(&self) -> PixelFormat {
        self.pixel_format.unwrap_or(self.target.pixel_format)
    }

    /// The container of the cubes, as manifests name it: the bake's for a file set that
    /// takes one, the engine's own otherwise.
    pub fn container_name(&self) -> &'static str {
        self.target
            .files
            .fixed_container
            .unwrap_or(self.container.extension())
    }

    /// The specular chain's layout: levels down to the minimum mip, the target's roughness
    /// per mip.
    pub fn specular_chain(&self) -> SpecularChain {
        SpecularChain {
            levels: chain_levels(self.specular_size, self.min_mip_size),
            roughness: self.target.roughness,
        }
    }

    /// What the in-memory bake computes.
    pub fn light_options(&self) -> LightOptions {
        LightOptions {
            specular_size: self.specular_size,
            chain: self.specular_chain(),
            irradiance_size: self.irradiance_size,
            samples: self.samples,
            rotate_degrees: self.rotate_degrees,
            sheen: self.target.files.sheen,
            sh: self.sh,
            sun: self.sun,
            truth: self.ground_truth || self.preview.is_some(),
        }
    }

    /// How the input is read.
    pub fn input_options(&self) -> InputOptions {
        InputOptions {
            exposure_ev: self.exposure_ev,
            cube_size: Some(self.specular_size),
        }
    }

    /// Checks every option, alone and against the target, before any work.
    pub fn validate(&self) -> Result<()> {
        let invalid = |option: &'static str, message: String| Err(Error::InvalidOption { option, message });
        validate_cube_size("specular_size", self.specular_size)?;
        validate_cube_size("irradiance_size", self.irradiance_size)?;
        if self.min_mip_size == 0 || !self.min_mip_size.is_power_of_two() {
            return invalid(
                "min_mip_size",
                format!("{} is not a power of two", self.min_mip_size),
            );
        }
        if self.samples == 0 || self.samples > MAX_SAMPLES {
            return invalid(
                "samples",
                format!("{} is not from 1 to {MAX_SAMPLES}", self.samples),
            );
        }
        if let Some(level) = self.zstd.filter(|l| !(1..=22).contains(l)) {
            return invalid("zstd", format!("level {level} is not from 1 to 22"));
        }
        if !self.rotate_degrees.is_finite() {
            return invalid(
                "rotate_degrees",
                format!("{} is not a finite angle", self.rotate_degrees),
            );
        }
        if !self.exposure_ev.is_finite() || self.exposure_ev.abs() > 64.0 {
            return invalid(
                "exposure_ev",
                format!("{} EV is not from -64 to 64", self.exposure_ev),
            );
        }
        if let Some(p) = &self.preview {
            validate_preview(p)?;
        }
        let target = self.target;
        let files = target.files;
        if !matches!(
            self.container,
            Container::Ktx2 | Container::Dds | Container::Exr
        ) {
            return invalid(
                "container",
                format!(
                    "a bake writes its cubes as ktx2, dds or exr, not {}",
                    self.container.extension()
                ),
            );
        }
        if files.fixed_container.is_some() && self.container != Container::Ktx2 {
            return invalid(
                "container",
                format!(
                    "target {} writes the containers its engine loads ({}); the container applies to the generic, bevy and three targets",
                    target.name,
                    self.container_name()
                ),
            );
        }
        if !files.has_pixel_format && self.pixel_format.is_some() {
            return invalid(
                "pixel_format",
                format!(
                    "target {} writes RGBD PNGs into its file, whatever the pixel format",
                    target.name
                ),
            );
        }
        target.check_format(self.pixel_format())?;
        self.container.check_format(self.pixel_format())?;
        if files.cube_container == Container::Ktx1 && !crate::io::ktx1::holds(self.pixel_format()) {
            return invalid(
                "pixel_format",
                format!(
                    "{} cannot be written as KTX 1 for Filament (its KTX 1 reader takes rg11b10f, rgba16f, rgba32f and bc6h)",
                    self.pixel_format().name()
                ),
            );
        }
        if files.carries_sh && !self.sh {
            return invalid(
                "sh",
                format!(
                    "target {} writes the irradiance SH into its file, where the engine reads them",
                    target.name
                ),
            );
        }
        if files.whole_chain && self.min_mip_size != 1 {
            return invalid(
                "min_mip_size",
                format!(
                    "target {} writes the whole chain down to 1x1, the only one its engine reads ({} asked for)",
                    target.name, self.min_mip_size
                ),
            );
        }
        Ok(())
    }
}

impl Default for BakeOptions {
    /// The generic target's defaults.
    fn default() -> Self {
        BakeOptions::for_target(&GENERIC)
    }
}
