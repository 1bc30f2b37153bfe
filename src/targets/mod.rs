//! Engine targets: how one engine reads IBL files, as data, and the code that writes its
//! file set. A bake or a cubemap for an engine is the generic bake (`docs/conventions.md`)
//! passed through its target's table: the cube orientation the engine's shader samples,
//! the chain layout it reads (levels, roughness per mip), default pixel format and
//! supercompression, and which files it uses ([`FileSet`], whose writer lives in the
//! target's module). Adding a target is adding its module and its line in [`TARGETS`].
//!
//! Every value here was read from the engine's own code and checked by loading the
//! outputs in the engine (`engines/`; `docs/engines.md`).

pub mod babylon;
pub mod bevy;
pub mod filament;
pub mod generic;
pub mod gltf;
pub mod three;

use std::path::Path;

pub use babylon::BABYLON;
pub use bevy::BEVY;
pub use filament::FILAMENT;
pub use generic::GENERIC;
pub use gltf::GLTF;
pub use three::THREE;

use crate::environment::Cubemap;
use crate::io::cubemap::{encode_cube, Container, CubeEncoding};
use crate::io::lut::{encode_lut, LutWriteOptions};
use crate::io::staging::Staging;
use crate::io::PixelFormat;
use crate::math::cubemap::AxisMap;
use crate::math::sh::{sh_prescaled, sh_rotated};
use crate::plan::chain::MipRoughness;
use crate::plan::lut::{BrdfLut, LutModel};
use crate::plan::shading::Shading;
use crate::stages::light::BakedEnvironment;
use crate::stages::sh::ShCoefficients;
use crate::{Error, Result};

/// How an engine's shaders read directions, against the generic (right-handed, +Y up, the
/// equirect's centre along +X).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Orientation {
    /// The engine's world direction for the generic direction d: the identity where the
    /// engine's world is the generic, a quarter turn about +Y for Filament (whose
    /// environments, as cmgen bakes them, face another way). SH written for the engine
    /// (Filament's KTX key, sh.txt) are expressed in this frame.
    pub frame: AxisMap,
    /// Where the engine's shader looks a world direction w up in a cube: a mirror for
    /// engines that negate an axis before every cube lookup (Bevy z, three.js x).
    pub shader: AxisMap,
    /// As written in manifests.
    pub description: &'static str,
}

impl Orientation {
    /// the generic: `textureSample(cube, s, d)` returns the light arriving from d.
    pub const GENERIC: Orientation = Orientation {
        frame: AxisMap::IDENTITY,
        shader: AxisMap::IDENTITY,
        description: "generic: texel at d holds the light arriving from d",
    };

    /// Where the target's cube holds the light arriving from the generic direction d: the
    /// engine's lookup of its own world direction for d.
    pub fn lookup(&self, d: [f32; 3]) -> [f32; 3] {
        self.shader.apply(self.frame.apply(d))
    }

    /// Whether the target's cubes are stored as generic ones (no texel moves).
    pub fn is_generic(&self) -> bool {
        self.texel_map() == AxisMap::IDENTITY
    }

    /// The texel permutation [`Orientation::lookup`] is.
    pub fn texel_map(&self) -> AxisMap {
        self.shader.after(self.frame)
    }

    /// `cube` (in generic orientation) stored for this orientation: every level's texels
    /// permuted so that the engine's lookup of a direction returns the light from it.
    pub fn apply(&self, cube: Cubemap) -> Cubemap {
        let map = self.texel_map();
        if map == AxisMap::IDENTITY {
            cube
        } else {
            cube.remapped(map)
        }
    }
}

/// How a LUT file holds its model's table.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum LutChannels {
    /// As the model lays it out (`splitsum lut --model`).
    Model,
    /// The model's first channel in B, R and G zero: glTF-IBL-Sampler's `lut_charlie`,
    /// which the glTF Sample Viewer reads as `.b`.
    FirstInBlue,
}

/// One LUT file a target writes when LUTs are asked for.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct LutSpec {
    /// File name in the bake folder; the extension picks the container (`io::lut`).
    pub file: &'static str,
    /// The model integrated.
    pub model: LutModel,
    /// How the file holds it.
    pub channels: LutChannels,
}

impl LutSpec {
    /// The format as written in manifests.
    pub fn format(&self) -> &'static str {
        match (
            crate::io::extension_of(std::path::Path::new(self.file)).as_str(),
            self.channels,
        ) {
            ("ktx2", _) => "ktx2 rg16f",
            (_, LutChannels::FirstInBlue) => "png rgb16 (the model in B)",
            _ => "png rgb16",
        }
    }
}

/// The warning of the targets that take ASTC HDR: where a GPU samples it.
pub(crate) const ASTC_HDR_WHERE: &str = "ASTC HDR is sampled by phones and Apple GPUs (Vulkan's textureCompressionASTC_HDR, Metal on Apple GPUs, WebGL's WEBGL_compressed_texture_astc where getSupportedProfiles() lists \"hdr\"), not by desktop GPUs: bake bc6h for those";

/// `brdf_lut.png`: the default model, 16-bit RGB (B = 0).
pub const BRDF_LUT_PNG: &[LutSpec] = &[LutSpec {
    file: "brdf_lut.png",
    model: LutModel::SchlickGgx,
    channels: LutChannels::Model,
}];

/// One engine's conventions.
#[derive(Clone, Copy, Debug)]
pub struct Target {
    /// Name on the command line and in manifests.
    pub name: &'static str,
    /// The engine and what the target writes for it, in a line (the command line's help).
    pub summary: &'static str,
    /// Where the engine reads each direction.
    pub orientation: Orientation,
    /// Default pixel format of cube outputs.
    pub pixel_format: PixelFormat,
    /// Default KTX2 Zstandard level (None: not supercompressed).
    pub zstd: Option<i32>,
    /// Roughness of each specular mip, as the engine's shader picks the lod.
    pub roughness: MipRoughness,
    /// Default edge of the smallest specular mip.
    pub min_mip_size: u32,
    /// Whether the irradiance cube is written (the engine has a diffuse cube input).
    pub irradiance: bool,
    /// Whether sh.json is written by default.
    pub sh: bool,
    /// Whether the LUTs are written by default.
    pub lut: bool,
    /// The LUT files, when they are written.
    pub luts: &'static [LutSpec],
    /// The files written, their containers and the code that writes them.
    pub files: FileSet,
    /// Pixel formats the engine cannot use everywhere, with the reason (a warning).
    pub format_warnings: &'static [(PixelFormat, &'static str)],
    /// Pixel formats the engine cannot read at all, with the reason (refused).
    pub format_refusals: &'static [(PixelFormat, &'static str)],
    /// How the engine reads the files, for the manifest.
    pub notes: &'static [&'static str],
    /// How the engine's shader shades from the files, as read in its source (the preview's
    /// mode for this target, `preview --target`; the README's recipe for the generic one).
    pub shading: Shading,
}

/// What a target's writer receives besides the baked light.
#[derive(Clone, Copy, Debug)]
pub struct FileContext<'a> {
    /// The output folder.
    pub dir: &'a Path,
    /// The input's stem (engine file sets name files after it).
    pub stem: &'a str,
    /// The target.
    pub target: &'static Target,
    /// How the cubes are encoded (the container applies to [`FileSet::fixed_container`]
    /// `None` sets; the others use their engine's own).
    pub encoding: CubeEncoding<'a>,
}

impl FileContext<'_> {
    /// Stages `cube` (in the generic orientation) at `path` in the target's orientation
    /// and the bake's encoding, recorded in the manifest as `kind` in format `fmt`.
    pub fn add_cube(
        &self,
        out: &mut Staging,
        path: &Path,
        kind: &'static str,
        fmt: &str,
        cube: Cubemap,
    ) -> Result<()> {
        let cube = self.target.orientation.apply(cube);
        out.add_cube(encode_cube(path, &cube, &self.encoding)?, kind, fmt, &cube);
        Ok(())
    }
}

/// Writes a file set: stages the files of `baked` (in the generic orientation; the writer
/// applies the target's) and returns warnings for the user.
pub type WriteFiles = fn(&FileContext, BakedEnvironment, &mut Staging) -> Result<Vec<String>>;

/// Which files a bake writes for an engine, each in the container the engine loads.
#[derive(Clone, Copy, Debug)]
pub struct FileSet {
    /// How manifests name the cubes' container: `None` for the bake's own choice (KTX2,
    /// DDS or OpenEXR), the engine's container otherwise (no other is accepted).
    pub fixed_container: Option<&'static str>,
    /// Whether a pixel format chooses how the cubes are stored (a `.env` is always RGBD).
    pub has_pixel_format: bool,
    /// Whether the irradiance SH are part of the engine's own file (Filament's IBL,
    /// Babylon's .env), so they cannot be left out.
    pub carries_sh: bool,
    /// Whether the set holds a Charlie sheen chain (glTF's `charlie/sheen.ktx2`, for
    /// KHR_materials_sheen), so the bake prefilters one.
    pub sheen: bool,
    /// Whether the engine reads only the whole chain, down to 1×1 (Babylon's .env).
    pub whole_chain: bool,
    /// The container of `splitsum cubemap`'s default output: the engine's cube container.
    pub cube_container: Container,
    /// Stages the files.
    pub write: WriteFiles,
}

/// Every target, for the command line.
pub const TARGETS: [&Target; 6] = [&GENERIC, &BEVY, &THREE, &FILAMENT, &BABYLON, &GLTF];

impl PartialEq for Target {
    /// Targets are equal when they are the same entry of [`TARGETS`] (names are unique).
    fn eq(&self, other: &Self) -> bool {
        self.name == other.name
    }
}

impl Target {
    /// The target called `name`.
    pub fn by_name(name: &str) -> Option<&'static Target> {
        TARGETS.iter().copied().find(|t| t.name == name)
    }

    /// The warning for writing `format` for this target, if any.
    pub fn format_warning(&self, format: PixelFormat) -> Option<&'static str> {
        self.format_warnings
            .iter()
            .find(|(f, _)| *f == format)
            .map(|(_, w)| *w)
    }

    /// Why the engine cannot read `format`, if it cannot.
    pub fn format_refusal(&self, format: PixelFormat) -> Option<&'static str> {
        self.format_refusals
            .iter()
            .find(|(f, _)| *f == format)
            .map(|(_, w)| *w)
    }

    /// An [`Error::InvalidOption`] (`pixel_format`) when the engine cannot read `format`.
    pub fn check_format(&self, format: PixelFormat) -> Result<()> {
        match self.format_refusal(format) {
            None => Ok(()),
            Some(why) => Err(Error::InvalidOption {
                option: "pixel_format",
                message: format!("target {} cannot use {}: {why}", self.name, format.name()),
            }),
        }
    }
}

/// The E/π coefficients in the engine's frame with the basis constants folded in: the
/// plain polynomial Filament's shader evaluates (cmgen `--sh-shader`) and Babylon's
/// spherical polynomial is made of.
pub fn engine_sh(sh: &ShCoefficients, target: &Target) -> [[f32; 3]; 9] {
    let frame = target.orientation.frame.matrix();
    sh_prescaled(&sh_rotated(&sh.irradiance, frame))
}

/// Stages the LUT files of `target` into `dir`, each from the table of `luts` that holds
/// its model (an error names the model when none does). The files are in the format the
/// engine reads: where that is a PNG (glTF's `lut_charlie.png`, `lut_sheen_E.png`), values
/// above 1 are stored as 1, as the engine's own files store them.
pub fn write_luts(out: &mut Staging, dir: &Path, target: &Target, luts: &[BrdfLut]) -> Result<()> {
    for spec in target.luts {
        let lut = luts
            .iter()
            .find(|l| l.model == spec.model)
            .ok_or_else(|| Error::InvalidOption {
                option: "luts",
                message: format!(
                    "target {} writes {} from the {} model, and no table of it was given",
                    target.name,
                    spec.file,
                    spec.model.name()
                ),
            })?;
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::environment::walk::texel_centres;
    use crate::math::cubemap::cube_face_coords;

    /// A cube whose texels hold their own direction.
    fn direction_cube(n: u32) -> Cubemap {
        let levels = (0..Cubemap::full_mip_count(n))
            .map(|m| {
                texel_centres((n >> m).max(1))
                    .map(|(_, _, _, d)| [d[0], d[1], d[2], 1.0])
                    .collect()
            })
            .collect();
        Cubemap { size: n, levels }
    }

    #[test]
    fn a_mirrored_cube_returns_the_light_from_d_where_the_engine_looks() {
        for orientation in TARGETS.map(|t| t.orientation) {
            let cube = orientation.apply(direction_cube(8));
            for m in 0..cube.levels.len() {
                let n = cube.level_size(m);
                let idx = |c: f32| ((c + 1.0) * 0.5 * n as f32).floor() as u32;
                for (f, i, j, d) in texel_centres(n) {
                    // The engine looks world direction d up at lookup(d).
                    let (face, s, t) = cube_face_coords(orientation.lookup(d));
                    let got = cube.texel(m, face, idx(s).min(n - 1), idx(t).min(n - 1));
                    for k in 0..3 {
                        assert!(
                            (got[k] - d[k]).abs() < 1e-6,
                            "{} {m} {f} {i} {j}",
                            orientation.description
                        );
                    }
                }
            }
        }
    }

    #[test]
    fn every_target_is_found_by_its_name() {
        for t in TARGETS {
            assert_eq!(Target::by_name(t.name), Some(t));
        }
        assert_eq!(Target::by_name("unity"), None);
    }

    #[test]
    fn a_mirror_twice_is_the_identity() {
        let cube = direction_cube(16);
        for axis in [0, 2] {
            assert_eq!(cube.mirrored(axis).mirrored(axis), cube);
        }
    }
}
