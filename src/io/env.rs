//! Babylon.js `.env` writer and reader (Babylon's `EnvironmentTextureTools`, version 2): the
//! 8 magic bytes, a NUL-terminated JSON header (the cube's width, the image type, the
//! irradiance as a spherical polynomial, and for every mip level and face, in that order,
//! the byte length and position of its image), then the images: one PNG per face and
//! level, the full chain down to 1×1, rows bottom to top, each texel RGBD-encoded.
//!
//! RGBD (Babylon's `toRGBD` / `fromRGBD`, helperFunctions.fx): the largest channel m picks
//! D = clamp(floor(255 / m), 1, 255) / 255, stored in alpha; R, G, B hold (colour × D)^(1/2.2)
//! in 8 bits. Babylon's `toGammaSpace` / `toLinearSpace` are the power 2.2
//! (`LinearEncodePowerApprox`) unless an engine is created with `useExactSrgbConversions`,
//! which defaults to false (ThinEngine); its `.env` decode (`rgbdDecode`, no defines of its
//! own) and encode (`EnvironmentTextureTools`) follow the engine, so a default engine's
//! `.env` files are power-2.2 RGBD (measured in Babylon 9.35: with the sRGB curve instead,
//! venice_sunset's level 0 shows 1.2 % brighter than the cube it encodes). A texel
//! decodes as (rgb)^2.2 / a, so the format holds radiance up to 255 (D = 1/255); brighter
//! texels are clipped there.

#[cfg(any(test, feature = "internals"))]
use std::path::Path;

use serde::{Deserialize, Serialize};

use crate::plan::chain::BABYLON_LOD_SCALE;
use crate::environment::Cubemap;
use crate::math::cubemap::FACES;
#[cfg(any(test, feature = "internals"))]
use crate::{Error, Result};

/// The 8 bytes every `.env` file starts with.
pub const MAGIC: [u8; 8] = [0x86, 0x16, 0x87, 0x96, 0xf6, 0xd6, 0x96, 0x36];
/// The largest radiance RGBD holds (Babylon's `rgbdMaxRange`).
pub const RGBD_MAX: f32 = 255.0;
/// The power RGBD's colour is stored under (Babylon's `LinearEncodePowerApprox`).
pub const RGBD_GAMMA: f32 = 2.2;

/// The irradiance as Babylon's `SphericalPolynomial`: per RGB channel, the coefficients of
/// x, y, z, x², y², z², yz, zx, xy. Babylon makes one with `SphericalPolynomial.
/// FromHarmonics` from SH already convolved to E/π, which applies the clamped cosine's band
/// factors (1, 2/3, 1/4) a second time; its shaders undo them (`FromPolynomial`,
/// `preScaledHarmonics`), so what Babylon shades is E/π. Measured: Babylon 9.35's own
/// polynomial of venice_sunset has exactly 2/3 and 1/4 of the exact E/π's band-1 and band-2
/// terms. splitsum writes the same convention, so Babylon shades its E/π.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct SphericalPolynomial {
    pub x: [f32; 3],
    pub y: [f32; 3],
    pub z: [f32; 3],
    pub xx: [f32; 3],
    pub yy: [f32; 3],
    pub zz: [f32; 3],
    pub yz: [f32; 3],
    pub zx: [f32; 3],
    pub xy: [f32; 3],
}

/// The band factors Babylon's polynomial carries on top of E/π (Â₁/π, Â₂/π).
const BAND1: f32 = 2.0 / 3.0;
const BAND2: f32 = 0.25;

impl SphericalPolynomial {
    /// Babylon's polynomial of E/π given with its basis constants folded in
    /// ([`crate::math::sh::sh_prescaled`]: f0 + f1 y + f2 z + f3 x + f4 xy + f5 yz +
    /// f6 (3z² − 1) + f7 xz + f8 (x² − y²)): band 1 × 2/3, band 2 × 1/4, and on the unit
    /// sphere the constant and the (3z² − 1) terms become quadratic through x² + y² + z² = 1.
    pub fn from_prescaled(f: &[[f32; 3]; 9]) -> Self {
        let ch = |g: &dyn Fn(usize) -> f32| -> [f32; 3] { std::array::from_fn(g) };
        SphericalPolynomial {
            x: ch(&|c| BAND1 * f[3][c]),
            y: ch(&|c| BAND1 * f[1][c]),
            z: ch(&|c| BAND1 * f[2][c]),
            xx: ch(&|c| f[0][c] + BAND2 * (f[8][c] - f[6][c])),
            yy: ch(&|c| f[0][c] - BAND2 * (f[6][c] + f[8][c])),
            zz: ch(&|c| f[0][c] + BAND2 * 2.0 * f[6][c]),
            yz: ch(&|c| BAND2 * f[5][c]),
            zx: ch(&|c| BAND2 * f[7][c]),
            xy: ch(&|c| BAND2 * f[4][c]),
        }
    }

    /// What Babylon shades at unit direction `n`: E/π, the band factors undone (band 0 is
    /// the mean of the diagonal, band 2 being traceless).
    #[cfg(any(test, feature = "internals"))]
    pub fn shade(&self, n: [f32; 3]) -> [f32; 3] {
        let [x, y, z] = n;
        std::array::from_fn(|c| {
            let band0 = (self.xx[c] + self.yy[c] + self.zz[c]) / 3.0;
            let band1 = self.x[c] * x + self.y[c] * y + self.z[c] * z;
            let band2 = (self.xx[c] - band0) * x * x
                + (self.yy[c] - band0) * y * y
                + (self.zz[c] - band0) * z * z
                + self.yz[c] * y * z
                + self.zx[c] * z * x
                + self.xy[c] * x * y;
            band0 + band1 / BAND1 + band2 / BAND2
        })
    }
}

/// One image's place in the binary payload.
#[derive(Clone, Copy, Debug, Serialize, Deserialize)]
struct ImageInfo {
    length: usize,
    position: usize,
}

#[derive(Debug, Serialize, Deserialize)]
#[serde(rename_all = "camelCase")]
struct SpecularInfo {
    mipmaps: Vec<ImageInfo>,
    lod_generation_scale: f32,
}

/// The JSON header (the fields Babylon 9 reads).
#[derive(Debug, Serialize, Deserialize)]
#[serde(rename_all = "camelCase")]
struct Header {
    version: u32,
    width: u32,
    image_type: String,
    irradiance: SphericalPolynomial,
    specular: SpecularInfo,
}

/// RGBD of one linear RGB texel (see the module documentation); channels above
/// [`RGBD_MAX`] are clipped.
pub fn encode_rgbd(rgb: [f32; 3]) -> [u8; 4] {
    let m = rgb[0].max(rgb[1]).max(rgb[2]).max(1e-7);
    let k = (RGBD_MAX / m).floor().clamp(1.0, 255.0);
    let d = k / 255.0;
    let [r, g, b] =
        rgb.map(|c| ((c * d).clamp(0.0, 1.0).powf(1.0 / RGBD_GAMMA) * 255.0).round() as u8);
    [r, g, b, k as u8]
}

#[cfg(any(test, feature = "internals"))]
/// Linear RGB of an RGBD texel (Babylon's `fromRGBD`).
pub fn decode_rgbd(p: [u8; 4]) -> [f32; 3] {
    let d = p[3].max(1) as f32 / 255.0;
    std::array::from_fn(|c| (p[c] as f32 / 255.0).powf(RGBD_GAMMA) / d)
}

/// One face of one level as an 8-bit RGBA PNG of RGBD texels, its last row (t = 1) at the
/// top: Babylon uploads a .env's images flipped (`createTexture(…, invertY = true)`), so
/// the image's bottom row becomes the face's first (measured: with rows top to bottom the
/// sun of venice_sunset comes out 6.4° low, mirrored about the horizon).
fn face_png(texels: &[[f32; 4]], n: u32) -> std::result::Result<Vec<u8>, String> {
    let data: Vec<u8> = texels
        .chunks(n as usize)
        .rev()
        .flatten()
        .flat_map(|t| encode_rgbd([t[0], t[1], t[2]]))
        .collect();
    let img = image::RgbaImage::from_raw(n, n, data)
        .ok_or_else(|| "pixel buffer does not match the face size".to_string())?;
    let mut out = std::io::Cursor::new(Vec::new());
    img.write_to(&mut out, image::ImageFormat::Png)
        .map_err(|e| e.to_string())?;
    Ok(out.into_inner())
}

/// Serialises `cube` (every level down to 1×1, faces +X … −Z, rows top to bottom) with the
/// irradiance polynomial as a `.env` file, whose header names [`BABYLON_LOD_SCALE`] as the
/// chain's `lodGenerationScale` (its roughness per mip,
/// [`crate::plan::chain::MipRoughness::Babylon`]).
pub fn encode(
    cube: &Cubemap,
    irradiance: &SphericalPolynomial,
) -> std::result::Result<Vec<u8>, String> {
    let full = Cubemap::full_mip_count(cube.size) as usize;
    if !cube.size.is_power_of_two() || cube.levels.len() != full {
        return Err(format!(
            "a .env holds a power-of-two cube with its whole chain down to 1×1 ({full} levels for {}²); this one has {}",
            cube.size,
            cube.levels.len()
        ));
    }
    let mut images = Vec::with_capacity(full * FACES);
    for m in 0..full {
        let n = cube.level_size(m);
        for face in 0..FACES {
            images.push(face_png(cube.face(m, face), n)?);
        }
    }
    let mut position = 0;
    let mipmaps = images
        .iter()
        .map(|png| {
            let info = ImageInfo {
                length: png.len(),
                position,
            };
            position += png.len();
            info
        })
        .collect();
    let header = Header {
        version: 2,
        width: cube.size,
        image_type: "image/png".into(),
        irradiance: *irradiance,
        specular: SpecularInfo {
            mipmaps,
            lod_generation_scale: BABYLON_LOD_SCALE,
        },
    };
    let json = serde_json::to_string(&header).map_err(|e| e.to_string())?;
    let mut out = Vec::with_capacity(MAGIC.len() + json.len() + 1 + position);
    out.extend_from_slice(&MAGIC);
    out.extend_from_slice(json.as_bytes());
    out.push(0);
    for png in images {
        out.extend(png);
    }
    Ok(out)
}

#[cfg(any(test, feature = "internals"))]
/// A `.env` file as read: the cube (decoded from RGBD), the irradiance polynomial and the
/// lod scale.
#[derive(Clone, Debug)]
pub struct EnvFile {
    /// Every level, decoded.
    pub cube: Cubemap,
    /// The irradiance.
    pub irradiance: SphericalPolynomial,
    /// `specular.lodGenerationScale`.
    pub lod_generation_scale: f32,
}

#[cfg(any(test, feature = "internals"))]
/// Parses a `.env` file (version 2, PNG images); errors name `path`.
pub fn decode(path: &Path, bytes: &[u8]) -> Result<EnvFile> {
    let bad = |message: String| Error::Decode {
        path: path.to_path_buf(),
        format: "Babylon .env",
        message,
    };
    if bytes.len() < MAGIC.len() || bytes[..MAGIC.len()] != MAGIC {
        return Err(bad("not a Babylon .env file (no magic bytes)".into()));
    }
    let rest = &bytes[MAGIC.len()..];
    let nul = rest
        .iter()
        .position(|&b| b == 0)
        .ok_or_else(|| bad("the JSON header has no NUL terminator".into()))?;
    let header: Header =
        serde_json::from_slice(&rest[..nul]).map_err(|e| bad(format!("header: {e}")))?;
    if header.version != 2 || header.image_type != "image/png" {
        return Err(bad(format!(
            "version {} with {}: splitsum reads version 2 with PNG images",
            header.version, header.image_type
        )));
    }
    super::limits::check_dimensions(path, header.width, header.width)?;
    let payload = &rest[nul + 1..];
    let full = Cubemap::full_mip_count(header.width) as usize;
    if header.specular.mipmaps.len() != full * FACES {
        return Err(bad(format!(
            "{} images, {} expected for a {}² chain",
            header.specular.mipmaps.len(),
            full * FACES,
            header.width
        )));
    }
    let mut levels = vec![Vec::new(); full];
    for (k, info) in header.specular.mipmaps.iter().enumerate() {
        let (m, face) = (k / FACES, k % FACES);
        let n = (header.width >> m).max(1);
        let png = info
            .position
            .checked_add(info.length)
            .and_then(|end| payload.get(info.position..end))
            .ok_or_else(|| {
                bad(format!(
                    "level {m} face {face} lies past the end of the file"
                ))
            })?;
        let img = image::load_from_memory_with_format(png, image::ImageFormat::Png)
            .map_err(|e| bad(format!("level {m} face {face}: {e}")))?
            .to_rgba8();
        if img.dimensions() != (n, n) {
            return Err(bad(format!(
                "level {m} face {face} is {:?}, {n}×{n} expected",
                img.dimensions()
            )));
        }
        // Rows bottom to top in the image (see `face_png`).
        for row in img.rows().rev() {
            levels[m].extend(row.map(|p| {
                let [r, g, b] = decode_rgbd(p.0);
                [r, g, b, 1.0]
            }));
        }
    }
    Ok(EnvFile {
        cube: Cubemap {
            size: header.width,
            levels,
        },
        irradiance: header.irradiance,
        lod_generation_scale: header.specular.lod_generation_scale,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rgbd_keeps_radiance_to_its_precision_and_clips_above_255() {
        for v in [0.0f32, 0.001, 0.2, 0.9, 1.0, 3.7, 42.0, 200.0, 255.0] {
            let rgb = [v, v * 0.5, v * 0.25];
            let back = decode_rgbd(encode_rgbd(rgb));
            for c in 0..3 {
                // 8 bits of (colour × D)^(1/2.2): half a step is 2.2 × 0.5 / code of the
                // value, within 1.5 % of the largest channel (code ≥ 11 from 0.001 up) and
                // 4 % of the others (code ≥ 6); the smallest codes are a larger fraction of
                // tiny values, 1.6e-4 absolute over D ≈ 1 / max(1, v).
                let tol = if c == 0 { 0.015 } else { 0.04 } * rgb[c] + 1.6e-4 * v.max(1.0);
                assert!((back[c] - rgb[c]).abs() <= tol, "{v}: {back:?} vs {rgb:?}");
            }
        }
        assert!((decode_rgbd(encode_rgbd([64000.0, 0.0, 0.0]))[0] - RGBD_MAX).abs() < 1e-3);
        // Babylon's D: floor(255 / m) / 255.
        assert_eq!(encode_rgbd([2.0, 0.0, 0.0])[3], 127);
        assert_eq!(encode_rgbd([0.5, 0.0, 0.0])[3], 255);
    }

    #[test]
    fn a_file_reads_back() {
        let n = 8;
        let cube = Cubemap {
            size: n,
            levels: (0..Cubemap::full_mip_count(n) as usize)
                .map(|m| {
                    let s = (n >> m).max(1);
                    (0..Cubemap::level_len(s))
                        .map(|i| [0.5 + i as f32 * 0.01, m as f32 + 0.25, 2.0, 1.0])
                        .collect()
                })
                .collect(),
        };
        let f: [[f32; 3]; 9] = std::array::from_fn(|k| [k as f32, -(k as f32), 0.5]);
        let poly = SphericalPolynomial::from_prescaled(&f);
        let bytes = encode(&cube, &poly).unwrap();
        assert_eq!(&bytes[..8], &MAGIC);
        let env = decode(Path::new("x.env"), &bytes).unwrap();
        assert_eq!(env.irradiance, poly);
        assert_eq!(env.lod_generation_scale, 0.8);
        for (a, b) in env
            .cube
            .levels
            .iter()
            .flatten()
            .zip(cube.levels.iter().flatten())
        {
            for c in 0..3 {
                assert!(
                    (a[c] - b[c]).abs() <= 0.02 * b[c].max(0.1),
                    "{a:?} vs {b:?}"
                );
            }
        }
        // A chain that stops short is refused.
        let mut short = cube.clone();
        short.levels.pop();
        assert!(encode(&short, &poly).is_err());
        for cut in [0, 9, 40, bytes.len() - 10] {
            assert!(decode(Path::new("x.env"), &bytes[..cut]).is_err(), "{cut}");
        }
    }

    #[test]
    fn babylon_shades_the_prescaled_expansion() {
        let f: [[f32; 3]; 9] =
            std::array::from_fn(|k| [0.3 * k as f32 - 1.0, (k * k) as f32 * 0.05, 0.2]);
        let poly = SphericalPolynomial::from_prescaled(&f);
        for n in [[0.6f32, 0.0, 0.8], [0.0, 1.0, 0.0], [0.48, 0.6, -0.64]] {
            let [x, y, z] = n;
            let p = [
                1.0,
                y,
                z,
                x,
                x * y,
                y * z,
                3.0 * z * z - 1.0,
                x * z,
                x * x - y * y,
            ];
            let want: [f32; 3] = std::array::from_fn(|c| (0..9).map(|k| f[k][c] * p[k]).sum());
            let got = poly.shade(n);
            for c in 0..3 {
                assert!(
                    (got[c] - want[c]).abs() < 1e-5,
                    "{n:?}: {got:?} vs {want:?}"
                );
            }
        }
    }
}
