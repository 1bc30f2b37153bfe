//! The one cube container dispatcher: a cubemap written in the container its path's extension names: `.ktx2`, `.dds` and
//! `.ktx` (KTX 1, as Filament loads it) hold every mip level in a GPU pixel format; `.exr`
//! and `.hdr` hold level 0 for inspection, as six face files `<stem>_px.<ext>` …
//! `<stem>_nz.<ext>`, a horizontal cross, or an equirect. All files of one output are
//! staged and renamed together.

use std::path::{Path, PathBuf};

use super::atomic::write_all_atomic;
use super::format::{EncodedTexture, PixelFormat};
use super::input::HORIZONTAL_CROSS;
use super::{dds, exr, extension_of, hdr, ktx1, ktx2};
use crate::stages::resample::sample_cube;
use crate::backend::{Backend, CpuBackend};
use crate::environment::Cubemap;
use crate::plan::astc::AstcQuality;
use crate::plan::bc6h::Bc6hQuality;
use crate::math::cubemap::{equirect_direction, FACES};
use crate::{Error, Result};

/// Extensions a cubemap can be written as.
pub const CUBE_EXTENSIONS: &[&str] = &["ktx2", "dds", "ktx", "exr", "hdr"];

/// Face file suffixes in face order.
pub const FACE_SUFFIXES: [&str; FACES] = ["px", "nx", "py", "ny", "pz", "nz"];

/// How `.exr`/`.hdr` outputs lay the cube out.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum CubeLayout {
    /// Six files `<stem>_px.<ext>` …
    #[default]
    Faces,
    /// One horizontal cross (4×3 faces).
    Cross,
    /// One equirect of 4N×2N texels resampled from the cube.
    Equirect,
}

/// A cube container: KTX2, DDS and KTX 1 hold every level in a GPU pixel format; OpenEXR
/// and Radiance HDR hold linear RGB images in a [`CubeLayout`].
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Container {
    /// KTX 2.0 (`.ktx2`).
    Ktx2,
    /// DDS with the DX10 header (`.dds`).
    Dds,
    /// KTX 1.1 (`.ktx`), as Filament loads it.
    Ktx1,
    /// OpenEXR, 32-bit float RGB (`.exr`).
    Exr,
    /// Radiance RGBE (`.hdr`).
    Hdr,
}

impl Container {
    /// Every container.
    pub const ALL: [Container; 5] = [
        Container::Ktx2,
        Container::Dds,
        Container::Ktx1,
        Container::Exr,
        Container::Hdr,
    ];

    /// File extension.
    pub fn extension(self) -> &'static str {
        match self {
            Container::Ktx2 => "ktx2",
            Container::Dds => "dds",
            Container::Ktx1 => "ktx",
            Container::Exr => "exr",
            Container::Hdr => "hdr",
        }
    }

    /// The container `path`'s extension names.
    pub fn of_path(path: &Path) -> Option<Container> {
        let ext = extension_of(path);
        Container::ALL.into_iter().find(|c| c.extension() == ext)
    }

    /// Whether it holds GPU textures (every level, in a pixel format) rather than images.
    pub fn is_texture(self) -> bool {
        matches!(self, Container::Ktx2 | Container::Dds | Container::Ktx1)
    }

    /// Why it cannot hold `format`, if it cannot: DDS holds DXGI formats (none for ASTC),
    /// KTX 1 the formats Filament's reader takes (`ktx1::holds`); KTX2 holds every pixel
    /// format, and the image containers ignore it. Checked before any work is done.
    pub fn check_format(self, format: PixelFormat) -> Result<()> {
        let why = match self {
            Container::Dds if format.dxgi_format().is_none() => {
                "DXGI has no such format (Direct3D does not sample ASTC): write it as .ktx2"
            }
            Container::Ktx1 if !ktx1::holds(format) => {
                "Filament's KTX 1 reader takes rg11b10f, rgba16f, rgba32f and bc6h"
            }
            _ => return Ok(()),
        };
        Err(Error::InvalidOption {
            option: "pixel_format",
            message: format!(
                "{} cannot be written as {}: {why}",
                format.name(),
                self.extension()
            ),
        })
    }
}

/// Options of a cubemap file (its container comes from its extension).
#[derive(Clone, Copy, Debug)]
pub struct CubeWriteOptions {
    /// Pixel format of KTX2/DDS/KTX 1 outputs.
    pub format: PixelFormat,
    /// KTX2: Zstandard level for per-level supercompression.
    pub zstd: Option<i32>,
    /// Layout of EXR/HDR outputs.
    pub layout: CubeLayout,
    /// The BC6H preset, for `format` BC6H.
    pub bc6h_quality: Bc6hQuality,
    /// The ASTC preset, for the ASTC formats.
    pub astc_quality: AstcQuality,
}

impl Default for CubeWriteOptions {
    fn default() -> Self {
        CubeWriteOptions {
            format: PixelFormat::Rgba16f,
            zstd: None,
            layout: CubeLayout::Faces,
            bc6h_quality: Bc6hQuality::default(),
            astc_quality: AstcQuality::default(),
        }
    }
}

/// How a cube is encoded.
#[derive(Clone, Copy, Debug)]
pub struct CubeEncoding<'a> {
    /// The container.
    pub container: Container,
    /// Pixel format of texture containers.
    pub format: PixelFormat,
    /// KTX2: Zstandard level for per-level supercompression.
    pub zstd: Option<i32>,
    /// Layout of image containers.
    pub layout: CubeLayout,
    /// Image containers: one file per level, `<stem>_m<m>.<ext>`, instead of level 0 alone.
    pub every_level: bool,
    /// What encodes a block format.
    pub blocks: BlockEncoder<'a>,
}

/// Reads the cube of a texture container (`.ktx2`, `.dds`, `.ktx`: level 0, or the whole
/// chain where the reader has one), or `None` when `path` names no texture container.
pub fn read_texture_cube(path: &Path) -> Result<Option<Cubemap>> {
    Ok(Some(match Container::of_path(path) {
        Some(Container::Ktx2) => ktx2::read_cube(path)?,
        Some(Container::Dds) => dds::read_cube(path)?,
        Some(Container::Ktx1) => ktx1::read_cube(path)?,
        _ => return Ok(None),
    }))
}

/// Checks `path`'s extension before any work is done.
pub fn check_cube_path(path: &Path) -> Result<()> {
    super::check_output_extension(path, "a cubemap", CUBE_EXTENSIONS)
}

/// The files `write_cubemap` would write for `path`.
pub fn output_paths(path: &Path, layout: CubeLayout) -> Vec<PathBuf> {
    let ext = extension_of(path);
    if (ext == "exr" || ext == "hdr") && layout == CubeLayout::Faces {
        let stem = path
            .file_stem()
            .map(|s| s.to_string_lossy().into_owned())
            .unwrap_or_default();
        FACE_SUFFIXES
            .iter()
            .map(|suffix| path.with_file_name(format!("{stem}_{suffix}.{ext}")))
            .collect()
    } else {
        vec![path.to_path_buf()]
    }
}

/// What encodes block formats: BC6H on a backend's kernel, ASTC with astc-encoder on the
/// CPU (`backend::cpu::astc`), each at a preset.
#[derive(Clone, Copy)]
pub struct BlockEncoder<'a> {
    /// The backend that runs the BC6H encoder.
    pub backend: &'a dyn Backend,
    /// The BC6H preset.
    pub quality: Bc6hQuality,
    /// The ASTC preset.
    pub astc_quality: AstcQuality,
}

impl std::fmt::Debug for BlockEncoder<'_> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("BlockEncoder")
            .field("backend", &self.backend.identity())
            .field("quality", &self.quality)
            .field("astc_quality", &self.astc_quality)
            .finish()
    }
}

impl Default for BlockEncoder<'static> {
    /// The CPU backend at the default preset.
    fn default() -> Self {
        BlockEncoder {
            backend: &CpuBackend,
            quality: Bc6hQuality::default(),
            astc_quality: AstcQuality::default(),
        }
    }
}

/// The warning for storing `cube` in `format` when its level 0 holds values above the
/// largest the format holds (rgba16f, BC6H and ASTC HDR 65504, rg11b10f 65024, rgb9e5 65408), which
/// are clipped to it.
pub fn clip_warning(cube: &Cubemap, format: PixelFormat) -> Option<String> {
    let max = format.max_value();
    let (clipped, largest) = cube.levels[0]
        .iter()
        .map(|t| t[0].max(t[1]).max(t[2]))
        .filter(|&m| m > max)
        .fold((0usize, 0.0f32), |(n, top), m| (n + 1, top.max(m)));
    (clipped > 0).then(|| {
        format!(
            "{clipped} texels of level 0 are brighter than the {max:.0} that {} holds (the largest {largest:.0}) and are clipped to it; bake N stops darker (--exposure -N) and raise the engine's intensity by 2^N to keep them",
            format.name()
        )
    })
}

/// Encodes every level of `cube` in `format` (faces concatenated per level); a block
/// format through `blocks`.
pub fn encode_texture(
    cube: &Cubemap,
    format: PixelFormat,
    blocks: &BlockEncoder,
) -> Result<EncodedTexture> {
    let levels = match format.block_footprint() {
        Some(footprint) if format.is_astc() => {
            crate::backend::cpu::astc::encode_astc(cube, footprint, blocks.astc_quality)?
        }
        Some(_) => blocks.backend.encode_bc6h(cube, blocks.quality)?,
        None => cube.levels.iter().map(|l| format.encode(l)).collect(),
    };
    Ok(EncodedTexture {
        format,
        width: cube.size,
        height: cube.size,
        faces: FACES as u32,
        levels,
    })
}

fn rgb(texels: &[[f32; 4]]) -> Vec<[f32; 3]> {
    texels.iter().map(|t| [t[0], t[1], t[2]]).collect()
}

/// Level 0 as a horizontal cross (unused cells black).
pub fn to_cross(cube: &Cubemap) -> (u32, u32, Vec<[f32; 3]>) {
    let n = cube.size;
    let (w, h) = (4 * n, 3 * n);
    let mut out = vec![[0.0f32; 3]; (w * h) as usize];
    for (face, &(col, row)) in HORIZONTAL_CROSS.iter().enumerate() {
        for j in 0..n {
            for i in 0..n {
                let t = cube.texel(0, face as u32, i, j);
                out[((row * n + j) * w + col * n + i) as usize] = [t[0], t[1], t[2]];
            }
        }
    }
    (w, h, out)
}

/// Level 0 resampled to a 4N×2N equirect (bilinear per texel centre).
pub fn to_equirect(cube: &Cubemap) -> (u32, u32, Vec<[f32; 3]>) {
    let (w, h) = (4 * cube.size, 2 * cube.size);
    let data = (0..h)
        .flat_map(|y| (0..w).map(move |x| (x, y)))
        .map(|(x, y)| {
            let d = equirect_direction((x as f32 + 0.5) / w as f32, (y as f32 + 0.5) / h as f32);
            sample_cube(cube, d, 0.0)
        })
        .collect();
    (w, h, data)
}

/// Encodes `cube` as `path` in `enc`: one file holding every level for a texture
/// container; for an image container, level 0 (or, with `every_level`, each level as
/// `<stem>_m<m>.<ext>`) in the layout. Returns each file's path and bytes.
pub fn encode_cube(
    path: &Path,
    cube: &Cubemap,
    enc: &CubeEncoding,
) -> Result<Vec<(PathBuf, Vec<u8>)>> {
    let enc_err = |path: &Path, format: &'static str, message: String| Error::Encode {
        path: path.to_path_buf(),
        format,
        message,
    };
    let texture = || encode_texture(cube, enc.format, &enc.blocks);
    Ok(match enc.container {
        Container::Ktx2 => vec![(
            path.to_path_buf(),
            ktx2::encode(&texture()?, enc.zstd)
                .map_err(|e| enc_err(path, "KTX2", e.to_string()))?,
        )],
        Container::Dds => vec![(
            path.to_path_buf(),
            dds::encode(&texture()?).map_err(|e| enc_err(path, "DDS", e))?,
        )],
        Container::Ktx1 => vec![(
            path.to_path_buf(),
            ktx1::encode(&texture()?, &[]).map_err(|e| enc_err(path, "KTX 1", e))?,
        )],
        Container::Exr | Container::Hdr if enc.every_level => {
            let stem = path
                .file_stem()
                .map(|s| s.to_string_lossy().into_owned())
                .unwrap_or_default();
            let mut files = Vec::new();
            for m in 0..cube.levels.len() {
                let level = Cubemap {
                    size: cube.level_size(m),
                    levels: vec![cube.levels[m].clone()],
                };
                let level_path =
                    path.with_file_name(format!("{stem}_m{m}.{}", enc.container.extension()));
                files.extend(encode_images(&level_path, &level, enc)?);
            }
            files
        }
        Container::Exr | Container::Hdr => encode_images(path, cube, enc)?,
    })
}

/// Level 0 of `cube` as the image files of `enc.layout` for `path`.
fn encode_images(
    path: &Path,
    cube: &Cubemap,
    enc: &CubeEncoding,
) -> Result<Vec<(PathBuf, Vec<u8>)>> {
    let image = |path: &Path, w: u32, h: u32, data: &[[f32; 3]]| -> Result<Vec<u8>> {
        match enc.container {
            Container::Exr => exr::encode_rgb32(w, h, data).map_err(|message| Error::Encode {
                path: path.to_path_buf(),
                format: "OpenEXR",
                message,
            }),
            _ => Ok(hdr::encode(w, h, data)),
        }
    };
    Ok(match enc.layout {
        CubeLayout::Faces => output_paths(path, enc.layout)
            .into_iter()
            .enumerate()
            .map(|(face, p)| {
                let bytes = image(&p, cube.size, cube.size, &rgb(cube.face(0, face)))?;
                Ok((p, bytes))
            })
            .collect::<Result<_>>()?,
        CubeLayout::Cross => {
            let (w, h, data) = to_cross(cube);
            vec![(path.to_path_buf(), image(path, w, h, &data)?)]
        }
        CubeLayout::Equirect => {
            let (w, h, data) = to_equirect(cube);
            vec![(path.to_path_buf(), image(path, w, h, &data)?)]
        }
    })
}

/// Encodes `cube` as `path` (its extension names the container; an image container holds
/// level 0) and writes the files atomically, together; BC6H and ASTC are encoded on the CPU. Returns
/// the paths written.
pub fn write_cubemap(path: &Path, cube: &Cubemap, opts: &CubeWriteOptions) -> Result<Vec<PathBuf>> {
    write_cubemap_with(path, cube, opts, &CpuBackend)
}

/// [`write_cubemap`], a block format encoded on `backend`.
pub fn write_cubemap_with(
    path: &Path,
    cube: &Cubemap,
    opts: &CubeWriteOptions,
    backend: &dyn Backend,
) -> Result<Vec<PathBuf>> {
    check_cube_path(path)?;
    let enc = CubeEncoding {
        container: Container::of_path(path).unwrap_or(Container::Ktx2),
        format: opts.format,
        zstd: opts.zstd,
        layout: opts.layout,
        every_level: false,
        blocks: BlockEncoder {
            backend,
            quality: opts.bc6h_quality,
            astc_quality: opts.astc_quality,
        },
    };
    let files = encode_cube(path, cube, &enc)?;
    write_all_atomic(&files)?;
    Ok(files.into_iter().map(|(p, _)| p).collect())
}
