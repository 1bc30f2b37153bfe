//! Writes a cubemap in the container its path's extension names: `.ktx2`, `.dds` and
//! `.ktx` (KTX 1, as Filament loads it) hold every mip level in a GPU pixel format; `.exr`
//! and `.hdr` hold level 0 for inspection, as six face files `<stem>_px.<ext>` …
//! `<stem>_nz.<ext>`, a horizontal cross, or an equirect. All files of one output are
//! staged and renamed together.

use std::path::{Path, PathBuf};

use super::atomic::write_all_atomic;
use super::format::{EncodedTexture, PixelFormat};
use super::input::HORIZONTAL_CROSS;
use super::{dds, exr, extension_of, hdr, ktx1, ktx2};
use crate::cpu::cube_resample::sample_cube;
use crate::environment::Cubemap;
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

/// Options of a cubemap output.
#[derive(Clone, Copy, Debug)]
pub struct CubeWriteOptions {
    /// Pixel format of KTX2/DDS/KTX 1 outputs.
    pub format: PixelFormat,
    /// KTX2: Zstandard level for per-level supercompression.
    pub zstd: Option<i32>,
    /// Layout of EXR/HDR outputs.
    pub layout: CubeLayout,
}

impl Default for CubeWriteOptions {
    fn default() -> Self {
        CubeWriteOptions {
            format: PixelFormat::Rgba16f,
            zstd: None,
            layout: CubeLayout::Faces,
        }
    }
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

/// Encodes every level of `cube` in `format` (faces concatenated per level).
pub fn encode_texture(cube: &Cubemap, format: PixelFormat) -> EncodedTexture {
    EncodedTexture {
        format,
        width: cube.size,
        height: cube.size,
        faces: FACES as u32,
        levels: cube.levels.iter().map(|l| format.encode(l)).collect(),
    }
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

/// Encodes `cube` for `path` and writes it (and its sibling face files) atomically.
/// Returns the paths written.
pub fn write_cubemap(path: &Path, cube: &Cubemap, opts: &CubeWriteOptions) -> Result<Vec<PathBuf>> {
    check_cube_path(path)?;
    let ext = extension_of(path);
    let enc_err = |format: &'static str| {
        move |message: String| Error::Encode {
            path: path.to_path_buf(),
            format,
            message,
        }
    };
    let image = |w: u32, h: u32, data: &[[f32; 3]]| -> Result<Vec<u8>> {
        if ext == "exr" {
            exr::encode_rgb32(w, h, data).map_err(enc_err("OpenEXR"))
        } else {
            Ok(hdr::encode(w, h, data))
        }
    };
    let files: Vec<(PathBuf, Vec<u8>)> = match ext.as_str() {
        "ktx2" => vec![(
            path.to_path_buf(),
            ktx2::encode(&encode_texture(cube, opts.format), opts.zstd)
                .map_err(|e| enc_err("KTX2")(e.to_string()))?,
        )],
        "dds" => vec![(
            path.to_path_buf(),
            dds::encode(&encode_texture(cube, opts.format)),
        )],
        "ktx" => vec![(
            path.to_path_buf(),
            ktx1::encode(&encode_texture(cube, opts.format), &[]).map_err(enc_err("KTX 1"))?,
        )],
        _ => match opts.layout {
            CubeLayout::Faces => output_paths(path, opts.layout)
                .into_iter()
                .enumerate()
                .map(|(face, p)| Ok((p, image(cube.size, cube.size, &rgb(cube.face(0, face)))?)))
                .collect::<Result<_>>()?,
            CubeLayout::Cross => {
                let (w, h, data) = to_cross(cube);
                vec![(path.to_path_buf(), image(w, h, &data)?)]
            }
            CubeLayout::Equirect => {
                let (w, h, data) = to_equirect(cube);
                vec![(path.to_path_buf(), image(w, h, &data)?)]
            }
        },
    };
    write_all_atomic(&files)?;
    Ok(files.into_iter().map(|(p, _)| p).collect())
}
