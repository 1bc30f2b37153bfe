//! Radiance RGBE (`.hdr`) reader and writer (Greg Ward, "Real Pixels", Graphics Gems II;
//! the Radiance file format). Reads flat, old-style run-length and new-style per-channel
//! RLE scanlines in the standard `-Y H +X W` orientation; writes new-style RLE.

use super::limits::check_dimensions;
use crate::environment::Equirect;
use crate::{Error, Result};
use std::path::Path;

const FORMAT: &str = "Radiance HDR";

/// Decodes an RGBE texel: (c + 0.5) · 2^(e − 136), the Radiance convention (the encoder
/// truncates, so +0.5 is the centre of the quantisation interval); e = 0 is black.
pub fn rgbe_to_rgb(p: [u8; 4]) -> [f32; 3] {
    if p[3] == 0 {
        return [0.0; 3];
    }
    let f = (p[3] as f32 - 136.0).exp2();
    [
        (p[0] as f32 + 0.5) * f,
        (p[1] as f32 + 0.5) * f,
        (p[2] as f32 + 0.5) * f,
    ]
}

/// Encodes linear RGB as RGBE (shared exponent of the largest channel, mantissas
/// truncated as Radiance does). Negative and non-finite values must be removed first.
pub fn rgb_to_rgbe(c: [f32; 3]) -> [u8; 4] {
    let v = c[0].max(c[1]).max(c[2]);
    if v.is_nan() || v < 1e-32 {
        return [0; 4];
    }
    // v = m · 2^e with m in [0.5, 1).
    let e = v.log2().floor() as i32 + 1;
    let scale = (-e as f32).exp2() * 256.0;
    let q = |x: f32| (x * scale).clamp(0.0, 255.0) as u8;
    if e + 128 > 255 {
        return [255, 255, 255, 255];
    }
    [q(c[0]), q(c[1]), q(c[2]), (e + 128) as u8]
}

struct Cursor<'a> {
    data: &'a [u8],
    pos: usize,
}

impl Cursor<'_> {
    fn byte(&mut self) -> Option<u8> {
        let b = *self.data.get(self.pos)?;
        self.pos += 1;
        Some(b)
    }
    fn line(&mut self) -> Option<&[u8]> {
        let start = self.pos;
        let len = self.data[start..].iter().position(|&b| b == b'\n')?;
        self.pos = start + len + 1;
        Some(&self.data[start..start + len])
    }
}

/// Parses a `.hdr` file's bytes; `path` is only used in errors.
pub fn decode(path: &Path, bytes: &[u8]) -> Result<Equirect> {
    let bad = |message: String| Error::Decode {
        path: path.to_path_buf(),
        format: FORMAT,
        message,
    };
    let mut cur = Cursor {
        data: bytes,
        pos: 0,
    };
    let magic = cur
        .line()
        .ok_or_else(|| bad("empty or missing header".into()))?;
    if !(magic.starts_with(b"#?RADIANCE")
        || magic.starts_with(b"#?RGBE")
        || magic.starts_with(b"#?"))
    {
        return Err(bad("missing the '#?RADIANCE' signature".into()));
    }
    loop {
        let line = cur
            .line()
            .ok_or_else(|| bad("header has no end (no blank line)".into()))?;
        if line.is_empty() {
            break;
        }
        if let Some(fmt) = line.strip_prefix(b"FORMAT=") {
            let fmt = String::from_utf8_lossy(fmt).trim().to_string();
            if fmt != "32-bit_rle_rgbe" {
                return Err(Error::UnsupportedInput {
                    path: path.to_path_buf(),
                    message: format!(
                        "Radiance pixel format '{fmt}' is not supported (only 32-bit_rle_rgbe)"
                    ),
                });
            }
        }
    }
    let res = cur
        .line()
        .ok_or_else(|| bad("missing the resolution line".into()))?;
    let res = String::from_utf8_lossy(res).to_string();
    let parts: Vec<&str> = res.split_whitespace().collect();
    let (height, width) = match parts.as_slice() {
        ["-Y", h, "+X", w] => (
            h.parse::<u32>()
                .map_err(|_| bad(format!("bad height in '{res}'")))?,
            w.parse::<u32>()
                .map_err(|_| bad(format!("bad width in '{res}'")))?,
        ),
        [_, _, _, _] => {
            return Err(Error::UnsupportedInput {
                path: path.to_path_buf(),
                message: format!(
                    "Radiance orientation '{res}' is not supported (only the standard '-Y H +X W')"
                ),
            })
        }
        _ => return Err(bad(format!("bad resolution line '{res}'"))),
    };
    check_dimensions(path, width, height)?;
    let w = width as usize;
    let mut data = Vec::with_capacity(w * height as usize);
    let mut scan = vec![[0u8; 4]; w];
    let truncated = |y: u32| bad(format!("truncated at scanline {y} of {height}"));
    for y in 0..height {
        read_scanline(&mut cur, &mut scan).map_err(|e| match e {
            ScanError::Truncated => truncated(y),
            ScanError::Corrupt(m) => bad(format!("scanline {y}: {m}")),
        })?;
        data.extend(scan.iter().map(|&p| rgbe_to_rgb(p)));
    }
    Ok(Equirect {
        width,
        height,
        data,
    })
}

enum ScanError {
    Truncated,
    Corrupt(String),
}

fn read_scanline(cur: &mut Cursor<'_>, scan: &mut [[u8; 4]]) -> std::result::Result<(), ScanError> {
    let w = scan.len();
    let b = |cur: &mut Cursor<'_>| cur.byte().ok_or(ScanError::Truncated);
    let first = [b(cur)?, b(cur)?, b(cur)?, b(cur)?];
    if (8..0x8000).contains(&w) && first[0] == 2 && first[1] == 2 && first[2] & 0x80 == 0 {
        // New-style RLE: four channel planes, each a sequence of runs and literals.
        let len = ((first[2] as usize) << 8) | first[3] as usize;
        if len != w {
            return Err(ScanError::Corrupt(format!(
                "run-length scanline of {len} texels, expected {w}"
            )));
        }
        for c in 0..4 {
            let mut x = 0;
            while x < w {
                let count = b(cur)? as usize;
                if count > 128 {
                    let run = count - 128;
                    if x + run > w {
                        return Err(ScanError::Corrupt("run overflows the scanline".into()));
                    }
                    let v = b(cur)?;
                    scan[x..x + run].iter_mut().for_each(|p| p[c] = v);
                    x += run;
                } else {
                    if count == 0 || x + count > w {
                        return Err(ScanError::Corrupt("bad literal length".into()));
                    }
                    for p in &mut scan[x..x + count] {
                        p[c] = b(cur)?;
                    }
                    x += count;
                }
            }
        }
        return Ok(());
    }
    // Flat texels, possibly with old-style repeat markers (1, 1, 1, n).
    let mut x = 0;
    let mut shift = 0;
    let mut px = first;
    loop {
        if px[0] == 1 && px[1] == 1 && px[2] == 1 {
            if x == 0 {
                return Err(ScanError::Corrupt(
                    "repeat marker at the start of a scanline".into(),
                ));
            }
            let count = (px[3] as usize) << shift;
            if x + count > w {
                return Err(ScanError::Corrupt("repeat overflows the scanline".into()));
            }
            let prev = scan[x - 1];
            scan[x..x + count].iter_mut().for_each(|p| *p = prev);
            x += count;
            shift += 8;
        } else {
            scan[x] = px;
            x += 1;
            shift = 0;
        }
        if x >= w {
            return Ok(());
        }
        px = [b(cur)?, b(cur)?, b(cur)?, b(cur)?];
    }
}

/// Encodes an image as a `.hdr` file with new-style RLE scanlines (flat when the width is
/// outside 8..32768, where RLE is not allowed).
pub fn encode(width: u32, height: u32, rgb: &[[f32; 3]]) -> Vec<u8> {
    let mut out = format!(
        "#?RADIANCE\nSOFTWARE=splitsum {}\nFORMAT=32-bit_rle_rgbe\n\n-Y {height} +X {width}\n",
        env!("CARGO_PKG_VERSION")
    )
    .into_bytes();
    let w = width as usize;
    for row in rgb.chunks_exact(w) {
        let texels: Vec<[u8; 4]> = row.iter().map(|&c| rgb_to_rgbe(c)).collect();
        if !(8..0x8000).contains(&w) {
            texels.iter().for_each(|t| out.extend_from_slice(t));
            continue;
        }
        out.extend_from_slice(&[2, 2, (w >> 8) as u8, (w & 0xff) as u8]);
        for c in 0..4 {
            let plane: Vec<u8> = texels.iter().map(|t| t[c]).collect();
            encode_plane(&plane, &mut out);
        }
    }
    out
}

/// Run-length codes one channel plane: runs of ≥ 3 equal bytes as (128 + n, v), the rest
/// as literal blocks of up to 128 bytes.
fn encode_plane(plane: &[u8], out: &mut Vec<u8>) {
    let mut i = 0;
    while i < plane.len() {
        let mut run = 1;
        while i + run < plane.len() && run < 127 && plane[i + run] == plane[i] {
            run += 1;
        }
        if run >= 3 {
            out.extend_from_slice(&[128 + run as u8, plane[i]]);
            i += run;
            continue;
        }
        // Literal block until the next run of ≥ 3 (or 128 bytes).
        let start = i;
        while i < plane.len() && i - start < 128 {
            if i + 2 < plane.len() && plane[i] == plane[i + 1] && plane[i] == plane[i + 2] {
                break;
            }
            i += 1;
        }
        out.push((i - start) as u8);
        out.extend_from_slice(&plane[start..i]);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rgbe_round_trips_within_quantisation() {
        for c in [[1.0f32, 0.5, 0.25], [64000.0, 1.0, 0.0], [1e-3, 2e-3, 3e-3]] {
            let back = rgbe_to_rgb(rgb_to_rgbe(c));
            let m = c[0].max(c[1]).max(c[2]);
            for k in 0..3 {
                assert!((back[k] - c[k]).abs() <= m / 128.0, "{c:?} -> {back:?}");
            }
        }
    }

    #[test]
    fn encode_decode_round_trip() {
        let (w, h) = (37u32, 9u32);
        let rgb: Vec<[f32; 3]> = (0..w * h)
            .map(|i| {
                if i % 5 < 3 {
                    [1.0, 2.0, 3.0]
                } else {
                    [i as f32, 0.5, 0.0]
                }
            })
            .collect();
        let bytes = encode(w, h, &rgb);
        let img = decode(Path::new("t.hdr"), &bytes).unwrap();
        assert_eq!((img.width, img.height), (w, h));
        for (a, b) in img.data.iter().zip(&rgb) {
            let m = b[0].max(b[1]).max(b[2]);
            for k in 0..3 {
                assert!((a[k] - b[k]).abs() <= m / 128.0);
            }
        }
    }
}
