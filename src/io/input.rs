//! Loading environments: equirect images (.hdr, .exr, .png, .jpg), cube crosses (4:3
//! horizontal, 3:4 vertical, detected by aspect ratio), six face files, and KTX2/DDS/KTX 1
//! cubemaps in the formats splitsum writes. Every input is sanitised (no NaN, infinity or
//! negative radiance reaches a kernel) and scaled by the exposure.

use std::path::{Path, PathBuf};

use super::{exr, extension_of, hdr, ldr, read_file};
use crate::plan::convert::EquirectToCubeParams;
use crate::environment::{Cubemap, Environment, Equirect, EquirectReducer};
use crate::math::cubemap::FACES;
use crate::{Error, Result};

/// Image extensions accepted as equirects, crosses or faces.
pub const IMAGE_EXTENSIONS: &str = "hdr, exr, png, jpg, jpeg";

/// Where each face sits in a horizontal cross (4×3 faces), as (column, row), in face
/// order +X, −X, +Y, −Y, +Z, −Z:
/// ```text
///       +Y
///   −X  +Z  +X  −Z
///       −Y
/// ```
/// Faces keep the orientation of the face selection table, which makes the cross
/// continuous across every shared edge.
pub const HORIZONTAL_CROSS: [(u32, u32); FACES] = [(2, 1), (0, 1), (1, 0), (1, 2), (1, 1), (3, 1)];

/// Face positions in a vertical cross (3×4 faces); −Z is stored rotated by 180° so it
/// continues below −Y:
/// ```text
///       +Y
///   −X  +Z  +X
///       −Y
///       −Z (rotated 180°)
/// ```
pub const VERTICAL_CROSS: [(u32, u32); FACES] = [(2, 1), (0, 1), (1, 0), (1, 2), (1, 1), (1, 3)];

/// Options applied on input.
#[derive(Clone, Copy, Debug, Default)]
pub struct InputOptions {
    /// Exposure in EV: radiance is multiplied by 2^EV.
    pub exposure_ev: f32,
    /// The face size of the cube the input will be converted to, when known. An equirect
    /// is then reduced, as it is read, to the level of its area-filtered pyramid that such
    /// a conversion integrates ([`reduction_levels`]): a `.hdr`, and an `.exr` stored top
    /// to bottom, are decoded row by row (block by block) into that level and never held
    /// at full size; other files are decoded whole and reduced at once. The conversion's
    /// result is bit-identical either way (tested).
    pub cube_size: Option<u32>,
}

/// How many times an equirect `height` rows high is halved before a `face_size` cube is
/// integrated from it: the level the conversion reads (see
/// [`crate::plan::convert::source_level`]).
pub fn reduction_levels(height: u32, face_size: u32) -> u32 {
    EquirectToCubeParams::new(face_size, 2 * height, height, 0.0).base_level
}

/// Texels decoded per batch when streaming an input (about 12 MiB of f32 RGB).
const STREAM_BATCH_TEXELS: usize = 1 << 20;

/// Sanitises, scales by the exposure and reduces rows as they are decoded. Gives up
/// (returns false) on +∞, whose replacement, the image's largest finite value, is only
/// known at the end; the file is then read whole.
struct ReducingSink {
    reducer: EquirectReducer,
    exposure: Option<f32>,
    nan: usize,
    negative: usize,
}

impl ReducingSink {
    fn new(width: u32, height: u32, levels: u32, opts: &InputOptions) -> Result<Self> {
        Ok(ReducingSink {
            reducer: EquirectReducer::new(width, height, levels),
            exposure: exposure_scale(opts)?,
            nan: 0,
            negative: 0,
        })
    }

    fn finish(self, path: &Path, warnings: &mut Vec<String>) -> Equirect {
        warnings.extend(sanitize_warning(path, (self.nan, self.negative, 0)));
        self.reducer.finish()
    }
}

impl exr::RowSink for ReducingSink {
    fn rows(&mut self, rows: &mut [[f32; 3]]) -> bool {
        if rows.iter().flatten().any(|&v| v == f32::INFINITY) {
            return false;
        }
        let (nan, negative, _) = sanitize(rows);
        self.nan += nan;
        self.negative += negative;
        self.push_clean(rows);
        true
    }
}

impl ReducingSink {
    /// Scales by the exposure and reduces rows already free of NaN, negative and infinite
    /// values.
    fn push_clean(&mut self, rows: &mut [[f32; 3]]) {
        if let Some(k) = self.exposure {
            scale_values(rows, k);
        }
        self.reducer.push(rows);
    }
}

/// How many halvings an input of this size gets while it is read: the conversion's finest
/// needed level for an equirect when the cube size is known, none otherwise.
fn levels_on_load(width: u32, height: u32, opts: &InputOptions) -> u32 {
    match opts.cube_size {
        Some(size) if width == 2 * height => reduction_levels(height, size),
        _ => 0,
    }
}

/// Opens an input for streaming, refusing an empty file by name.
fn open_input(path: &Path) -> Result<std::io::BufReader<std::fs::File>> {
    let file = std::fs::File::open(path).map_err(|e| Error::io(path, e))?;
    if file.metadata().map(|m| m.len() == 0).unwrap_or(false) {
        return Err(Error::Decode {
            path: path.to_path_buf(),
            format: "input",
            message: "the file is empty".into(),
        });
    }
    Ok(std::io::BufReader::new(file))
}

/// Reads a `.hdr` row by row into a [`ReducingSink`] (RGBE holds only finite,
/// non-negative values, so the rows skip the sink's scan and sanitising), reducing an
/// equirect by [`levels_on_load`]; anything else is returned whole.
fn read_hdr_streaming(
    path: &Path,
    opts: &InputOptions,
    warnings: &mut Vec<String>,
) -> Result<Equirect> {
    let mut reader = hdr::HdrReader::new(path, open_input(path)?)?;
    let (w, h) = (reader.width(), reader.height());
    let mut sink = ReducingSink::new(w, h, levels_on_load(w, h, opts), opts)?;
    let rows_per_batch = (STREAM_BATCH_TEXELS / w as usize).max(1);
    let mut batch = vec![[0.0f32; 3]; rows_per_batch * w as usize];
    let mut y = 0;
    while y < h {
        let n = (rows_per_batch as u32).min(h - y);
        let rows = &mut batch[..(n * w) as usize];
        reader.read_rows(rows)?;
        sink.push_clean(rows);
        y += n;
    }
    Ok(sink.finish(path, warnings))
}

/// Streams an equirect `.exr` into a [`ReducingSink`] when the cube size is known; None
/// when it is not an equirect, not stored top to bottom, or holds +∞ (read it whole).
fn read_exr_streaming(
    path: &Path,
    opts: &InputOptions,
    warnings: &mut Vec<String>,
) -> Result<Option<Equirect>> {
    let info = exr::read_info(path, open_input(path)?)?;
    let levels = levels_on_load(info.width, info.height, opts);
    if levels == 0 {
        return Ok(None);
    }
    let sink = ReducingSink::new(info.width, info.height, levels, opts)?;
    let streamed = exr::decode_streaming(path, info, open_input(path)?, sink, STREAM_BATCH_TEXELS)?;
    Ok(streamed.map(|sink| sink.finish(path, warnings)))
}

/// Reads any image whole, sanitises it, applies the exposure and reduces an equirect by
/// [`levels_on_load`].
fn read_whole(path: &Path, opts: &InputOptions, warnings: &mut Vec<String>) -> Result<Equirect> {
    let mut img = read_image(path)?;
    sanitize_with_warning(path, &mut img.data, warnings);
    apply_exposure(&mut img.data, opts)?;
    let levels = levels_on_load(img.width, img.height, opts);
    if levels == 0 {
        return Ok(img);
    }
    let mut reducer = EquirectReducer::new(img.width, img.height, levels);
    reducer.push_all(&img.data);
    Ok(reducer.finish())
}

/// A loaded environment with the warnings its loading produced.
#[derive(Clone, Debug)]
pub struct LoadedEnvironment {
    /// The environment.
    pub env: Environment,
    /// Human-readable warnings (for example replaced non-finite texels).
    pub warnings: Vec<String>,
}


/// Reads any supported 2D image as linear RGB, by extension.
pub fn read_image(path: &Path) -> Result<Equirect> {
    let ext = extension_of(path);
    let check_ext = || -> Result<()> {
        match ext.as_str() {
            "hdr" | "exr" | "png" | "jpg" | "jpeg" => Ok(()),
            _ => Err(Error::UnsupportedInput {
                path: path.to_path_buf(),
                message: format!("unknown image type '.{ext}' (supported: {IMAGE_EXTENSIONS})"),
            }),
        }
    };
    check_ext()?;
    let bytes = read_file(path)?;
    match ext.as_str() {
        "hdr" => hdr::decode(path, &bytes),
        "exr" => exr::decode(path, &bytes),
        "png" => ldr::decode(path, &bytes, "PNG"),
        _ => ldr::decode(path, &bytes, "JPEG"),
    }
}

/// Replaces NaN and negative values with 0 and +∞ with the largest finite value of the
/// image; returns how many of each were replaced.
pub fn sanitize(values: &mut [[f32; 3]]) -> (usize, usize, usize) {
    let max_finite = values
        .iter()
        .flatten()
        .filter(|v| v.is_finite())
        .fold(0.0f32, |a, &b| a.max(b));
    let (mut nan, mut neg, mut inf) = (0, 0, 0);
    for v in values.iter_mut().flatten() {
        if v.is_nan() {
            nan += 1;
            *v = 0.0;
        } else if *v < 0.0 {
            neg += 1;
            *v = 0.0;
        } else if v.is_infinite() {
            inf += 1;
            *v = max_finite;
        }
    }
    (nan, neg, inf)
}

fn sanitize_with_warning(path: &Path, values: &mut [[f32; 3]], warnings: &mut Vec<String>) {
    warnings.extend(sanitize_warning(path, sanitize(values)));
}

/// The warning for (NaN, negative, infinite) replaced values, if any were.
fn sanitize_warning(path: &Path, (nan, neg, inf): (usize, usize, usize)) -> Option<String> {
    let parts: Vec<String> = [
        (nan, "NaN value(s) with 0"),
        (neg, "negative value(s) with 0"),
        (inf, "infinite value(s) with the largest finite one"),
    ]
    .iter()
    .filter(|(n, _)| *n > 0)
    .map(|(n, what)| format!("{n} {what}"))
    .collect();
    (!parts.is_empty()).then(|| format!("{}: replaced {}", path.display(), parts.join(", ")))
}

/// The radiance factor 2^EV of the exposure, None for 0 EV; refuses EV outside ±64.
fn exposure_scale(opts: &InputOptions) -> Result<Option<f32>> {
    if !opts.exposure_ev.is_finite() || opts.exposure_ev.abs() > 64.0 {
        return Err(Error::InvalidOption {
            option: "exposure_ev",
            message: format!("{} EV is not from -64 to 64", opts.exposure_ev),
        });
    }
    Ok((opts.exposure_ev != 0.0).then(|| opts.exposure_ev.exp2()))
}

/// Multiplies radiance by `k`, clamping to the largest finite value.
fn scale_values(values: &mut [[f32; 3]], k: f32) {
    values
        .iter_mut()
        .flatten()
        .for_each(|v| *v = (*v * k).min(f32::MAX));
}

fn apply_exposure(values: &mut [[f32; 3]], opts: &InputOptions) -> Result<()> {
    if let Some(k) = exposure_scale(opts)? {
        scale_values(values, k);
    }
    Ok(())
}

/// Extracts the six faces of a cross image.
fn cross_to_cube(img: &Equirect, layout: &[(u32, u32); FACES], vertical: bool) -> Cubemap {
    let n = if vertical {
        img.width / 3
    } else {
        img.width / 4
    };
    let mut level = Vec::with_capacity(Cubemap::level_len(n));
    for (face, &(col, row)) in layout.iter().enumerate() {
        let rotated = vertical && face == 5;
        for j in 0..n {
            for i in 0..n {
                let (fi, fj) = if rotated {
                    (n - 1 - i, n - 1 - j)
                } else {
                    (i, j)
                };
                let t = img.get(col * n + fi, row * n + fj);
                level.push([t[0], t[1], t[2], 1.0]);
            }
        }
    }
    Cubemap {
        size: n,
        levels: vec![level],
    }
}

/// Refuses what is not a file to read, naming it: standard input (`-`, not supported), a
/// folder, or a special file. A missing file is left to the reader's own error.
pub fn check_input_file(path: &Path) -> Result<()> {
    let not_a_file = |message: &str| {
        Err(Error::UnsupportedInput {
            path: path.to_path_buf(),
            message: message.into(),
        })
    };
    if path.as_os_str() == "-" {
        return not_a_file("reading an environment from standard input is not supported: give a file");
    }
    match std::fs::metadata(path) {
        Ok(m) if m.is_dir() => not_a_file("is a folder, not an environment file"),
        Ok(m) if !m.is_file() => not_a_file("is not a regular file"),
        _ => Ok(()),
    }
}

/// The warning for an 8-bit or 16-bit image: it holds no light brighter than white.
fn ldr_warning(path: &Path) -> String {
    format!(
        "{}: a PNG or JPEG holds no radiance above 1, so the sun and lamps light as dim patches and the bake's highlights are flat; bake an HDR image (.hdr, .exr) for real lighting",
        path.display()
    )
}

/// Loads one environment file: an equirect, a cross, or a KTX2/DDS/KTX 1 cubemap.
pub fn load_environment(path: &Path, opts: &InputOptions) -> Result<LoadedEnvironment> {
    check_input_file(path)?;
    let mut warnings = Vec::new();
    let ext = extension_of(path);
    if matches!(ext.as_str(), "png" | "jpg" | "jpeg") {
        warnings.push(ldr_warning(path));
    }
    if let Some(mut cube) = super::cubemap::read_texture_cube(path)? {
        cube.levels.truncate(1);
        let mut rgb: Vec<[f32; 3]> = cube.levels[0].iter().map(|t| [t[0], t[1], t[2]]).collect();
        sanitize_with_warning(path, &mut rgb, &mut warnings);
        apply_exposure(&mut rgb, opts)?;
        cube.levels[0] = rgb.into_iter().map(|t| [t[0], t[1], t[2], 1.0]).collect();
        return Ok(LoadedEnvironment {
            env: Environment::Cube(cube),
            warnings,
        });
    }
    let img = match ext.as_str() {
        "hdr" => read_hdr_streaming(path, opts, &mut warnings)?,
        "exr" => match read_exr_streaming(path, opts, &mut warnings)? {
            Some(img) => img,
            None => read_whole(path, opts, &mut warnings)?,
        },
        _ => read_whole(path, opts, &mut warnings)?,
    };
    let env = environment_from_image(path, img)?;
    Ok(LoadedEnvironment { env, warnings })
}

/// Recognises the layout of a decoded image by its aspect ratio: 2:1 equirect, 4:3
/// horizontal cross, 3:4 vertical cross.
pub fn environment_from_image(path: &Path, img: Equirect) -> Result<Environment> {
    let (w, h) = (img.width, img.height);
    Ok(if w == 2 * h {
        Environment::Equirect(img)
    } else if w * 3 == h * 4 && w % 4 == 0 {
        Environment::Cube(cross_to_cube(&img, &HORIZONTAL_CROSS, false))
    } else if w * 4 == h * 3 && w % 3 == 0 {
        Environment::Cube(cross_to_cube(&img, &VERTICAL_CROSS, true))
    } else {
        return Err(Error::UnsupportedInput {
            path: path.to_path_buf(),
            message: format!(
                "image is {w}×{h}: expected a 2:1 equirect, a 4:3 horizontal cross or a 3:4 vertical cross (or pass six faces with --faces)"
            ),
        });
    })
}

/// Face-name placeholder of a face-file pattern such as `sky_{face}.hdr`.
pub const FACE_PLACEHOLDER: &str = "{face}";

/// The six face paths of a pattern containing `{face}` (replaced by px, nx, py, ny, pz,
/// nz), or None when `path` is not a pattern.
pub fn expand_face_pattern(path: &Path) -> Option<Vec<PathBuf>> {
    let text = path.to_str()?;
    text.contains(FACE_PLACEHOLDER).then(|| {
        super::cubemap::FACE_SUFFIXES
            .iter()
            .map(|s| PathBuf::from(text.replace(FACE_PLACEHOLDER, s)))
            .collect()
    })
}

/// The name an input's outputs are called by: its file stem, with a face pattern's
/// placeholder removed and trailing separators trimmed (`sky_{face}.hdr` → `sky`).
pub fn input_stem(path: &Path) -> String {
    let text = path.to_string_lossy().replace(FACE_PLACEHOLDER, "");
    let stem = Path::new(&text)
        .file_stem()
        .map(|s| {
            s.to_string_lossy()
                .trim_end_matches(['_', '-', '.'])
                .to_owned()
        })
        .unwrap_or_default();
    if stem.is_empty() {
        "environment".into()
    } else {
        stem
    }
}

/// Loads an input named on the command line: a face pattern (`sky_{face}.hdr`, see
/// [`expand_face_pattern`]) or one environment file.
pub fn load_input(path: &Path, opts: &InputOptions) -> Result<LoadedEnvironment> {
    match expand_face_pattern(path) {
        Some(faces) => load_faces(&faces, opts),
        None => load_environment(path, opts),
    }
}

/// Loads six square face images in the order +X, −X, +Y, −Y, +Z, −Z.
pub fn load_faces(paths: &[PathBuf], opts: &InputOptions) -> Result<LoadedEnvironment> {
    if paths.len() != FACES {
        return Err(Error::InvalidOption {
            option: "faces",
            message: format!(
                "expected 6 face files (+X −X +Y −Y +Z −Z), got {}",
                paths.len()
            ),
        });
    }
    let mut warnings = Vec::new();
    let mut level = Vec::new();
    let mut size = 0;
    for (face, path) in paths.iter().enumerate() {
        check_input_file(path)?;
        let ldr = matches!(extension_of(path).as_str(), "png" | "jpg" | "jpeg");
        if ldr && warnings.is_empty() {
            // Once for the six faces.
            warnings.push(ldr_warning(path));
        }
        let mut img = read_image(path)?;
        if img.width != img.height {
            return Err(Error::UnsupportedInput {
                path: path.clone(),
                message: format!(
                    "cube face is {}×{}; faces must be square",
                    img.width, img.height
                ),
            });
        }
        if face == 0 {
            size = img.width;
        } else if img.width != size {
            return Err(Error::UnsupportedInput {
                path: path.clone(),
                message: format!(
                    "face is {0}×{0} but the first face is {size}×{size}",
                    img.width
                ),
            });
        }
        sanitize_with_warning(path, &mut img.data, &mut warnings);
        apply_exposure(&mut img.data, opts)?;
        level.extend(img.data.iter().map(|t| [t[0], t[1], t[2], 1.0]));
    }
    Ok(LoadedEnvironment {
        env: Environment::Cube(Cubemap {
            size,
            levels: vec![level],
        }),
        warnings,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use ::exr::prelude::{Encoding, Image, SpecificChannels, Vec2, WritableImage};

    fn scratch(name: &str) -> PathBuf {
        let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("target/unit-test-tmp");
        std::fs::create_dir_all(&dir).unwrap();
        dir.join(name)
    }

    /// A `w`×`w/2` image with a NaN, a negative texel and, when asked, a +∞. At `w` = 512
    /// a cube of 1 (`OPTS`) reduces it by one halving.
    fn image(w: usize, infinite: bool) -> Vec<[f32; 3]> {
        let mut data: Vec<[f32; 3]> = (0..w * w / 2)
            .map(|i| [(i % 13) as f32 * 0.5, (i % 7) as f32, 1.0 + (i % 3) as f32])
            .collect();
        data[5][1] = f32::NAN;
        data[w * 3 + 1][2] = -2.0;
        if infinite {
            data[w * 10 + 3][0] = f32::INFINITY;
        }
        data
    }

    fn write_exr(path: &Path, w: usize, data: &[[f32; 3]], encoding: Encoding) {
        let channels = SpecificChannels::rgb(|p: Vec2<usize>| {
            let t = data[p.y() * w + p.x()];
            (t[0], t[1], t[2])
        });
        Image::from_encoded_channels((w, w / 2), encoding, channels)
            .write()
            .non_parallel()
            .to_file(path)
            .unwrap();
    }

    const OPTS: InputOptions = InputOptions {
        exposure_ev: 1.5,
        cube_size: Some(1),
    };

    /// An EXR stored top to bottom, as scanlines (ZIP, 16-line blocks) or as 64² tiles
    /// (eight to a row of tiles), is streamed, never held whole, and gives exactly what
    /// decoding it whole gives, warnings included.
    #[test]
    fn top_to_bottom_exr_streams_bit_identically() {
        assert_eq!(levels_on_load(512, 256, &OPTS), 1);
        for (name, encoding) in [
            ("scanlines", Encoding::SMALL_LOSSLESS),
            ("tiles", Encoding::FAST_LOSSLESS),
        ] {
            let path = scratch(&format!("stream_{name}.exr"));
            write_exr(&path, 512, &image(512, false), encoding);
            let (mut w1, mut w2) = (Vec::new(), Vec::new());
            let streamed = read_exr_streaming(&path, &OPTS, &mut w1).unwrap();
            let whole = read_whole(&path, &OPTS, &mut w2).unwrap();
            assert_eq!(whole.height, 128);
            assert_eq!(streamed.as_ref(), Some(&whole), "{name}");
            assert_eq!(w1, w2);
            assert!(
                w1[0].contains("1 NaN") && w1[0].contains("1 negative"),
                "{w1:?}"
            );
        }
    }

    /// +∞ (replaced by the image's largest finite value, known only at the end) makes the
    /// streamed read give up; the loader then reads the file whole, with the same result
    /// as always. (Blocks out of order are the other reason; see `io::exr`'s tests.)
    #[test]
    fn infinite_exr_falls_back_to_a_whole_read() {
        let infinite = scratch("stream_infinite.exr");
        write_exr(&infinite, 512, &image(512, true), Encoding::SMALL_LOSSLESS);
        {
            let path = infinite;
            let mut warnings = Vec::new();
            assert!(read_exr_streaming(&path, &OPTS, &mut warnings)
                .unwrap()
                .is_none());
            assert!(warnings.is_empty());
            let loaded = load_environment(&path, &OPTS).unwrap();
            let whole = read_whole(&path, &OPTS, &mut warnings).unwrap();
            match loaded.env {
                Environment::Equirect(e) => assert_eq!(e, whole),
                Environment::Cube(_) => panic!("not an equirect"),
            }
            assert_eq!(loaded.warnings, warnings);
        }
    }

    /// The bundled real EXR (PIZ, 32-line blocks) streams too.
    #[test]
    fn real_exr_streams() {
        let path = Path::new("tests/data/venice_sunset_1k_f32_piz.exr");
        if path.exists() {
            let streamed = read_exr_streaming(path, &OPTS, &mut Vec::new()).unwrap();
            let whole = read_whole(path, &OPTS, &mut Vec::new()).unwrap();
            assert_eq!(streamed, Some(whole));
        }
    }
}
