//! Radiance RGBE (`.hdr`) reader and writer (Greg Ward, "Real Pixels", Graphics Gems II;
//! the Radiance file format). Reads flat, old-style run-length and new-style per-channel
//! RLE scanlines in the standard `-Y H +X W` orientation; writes new-style RLE.

use super::limits::check_dimensions;
use crate::environment::Equirect;
use crate::{Error, Result};
use std::io::Read;
use std::path::{Path, PathBuf};

const FORMAT: &str = "Radiance HDR";

/// Decodes an RGBE texel: (c + 0.5) · 2^(e − 136), the Radiance convention (the encoder
/// truncates, so +0.5 is the centre of the quantisation interval); e = 0 is black.
pub fn rgbe_to_rgb(p: [u8; 4]) -> [f32; 3] {
    if p[3] == 0 {
        return [0.0; 3];
    }
    let f = exponent_scale()[p[3] as usize];
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

/// 2^(e − 136) for every exponent byte (index 0, black, is unused).
fn exponent_scale() -> &'static [f32; 256] {
    static TABLE: std::sync::OnceLock<[f32; 256]> = std::sync::OnceLock::new();
    TABLE.get_or_init(|| std::array::from_fn(|e| (e as f32 - 136.0).exp2()))
}

/// Longest header line accepted (a guard against binary garbage without newlines).
const MAX_HEADER_LINE: usize = 64 * 1024;

/// A buffered byte reader: the header and the run-length scanlines are read a byte at a
/// time, so this keeps that to a bounds check.
struct ByteSource<R> {
    inner: R,
    buf: Box<[u8]>,
    pos: usize,
    len: usize,
    error: Option<std::io::Error>,
}

impl<R: Read> ByteSource<R> {
    fn new(inner: R) -> Self {
        ByteSource {
            inner,
            buf: vec![0; 1 << 18].into_boxed_slice(),
            pos: 0,
            len: 0,
            error: None,
        }
    }

    /// Refills the buffer; false at the end of the input or on an I/O error (kept).
    #[cold]
    fn refill(&mut self) -> bool {
        loop {
            match self.inner.read(&mut self.buf) {
                Ok(0) => return false,
                Ok(n) => {
                    (self.pos, self.len) = (0, n);
                    return true;
                }
                Err(e) if e.kind() == std::io::ErrorKind::Interrupted => continue,
                Err(e) => {
                    self.error = Some(e);
                    return false;
                }
            }
        }
    }

    #[inline]
    fn byte(&mut self) -> Option<u8> {
        if self.pos == self.len && !self.refill() {
            return None;
        }
        let b = self.buf[self.pos];
        self.pos += 1;
        Some(b)
    }

    /// The next line without its '\n'; None at the end of the input, or when the line is
    /// longer than [`MAX_HEADER_LINE`].
    fn line(&mut self) -> Option<Vec<u8>> {
        let mut line = Vec::new();
        loop {
            match self.byte()? {
                b'\n' => return Some(line),
                _ if line.len() == MAX_HEADER_LINE => return None,
                b => line.push(b),
            }
        }
    }
}

/// An incremental `.hdr` reader: [`HdrReader::new`] parses the header, then
/// [`HdrReader::read_rows`] decodes scanlines top to bottom, so a caller can reduce a
/// large image while it is read instead of holding it whole.
pub struct HdrReader<R> {
    path: PathBuf,
    src: ByteSource<R>,
    width: u32,
    height: u32,
    next_row: u32,
    scan: Vec<[u8; 4]>,
}

impl<R: Read> HdrReader<R> {
    /// Parses the header from `reader` (`path` is only used in errors) and checks the
    /// dimensions against the limits before anything is allocated.
    pub fn new(path: &Path, reader: R) -> Result<Self> {
        let mut src = ByteSource::new(reader);
        let bad = |message: String| Error::Decode {
            path: path.to_path_buf(),
            format: FORMAT,
            message,
        };
        let io_or = |src: &mut ByteSource<R>, message: &str| match src.error.take() {
            Some(e) => Error::io(path, e),
            None => bad(message.into()),
        };
        let magic = src
            .line()
            .ok_or_else(|| io_or(&mut src, "empty or missing header"))?;
        if !magic.starts_with(b"#?") {
            return Err(bad("missing the '#?RADIANCE' signature".into()));
        }
        loop {
            let line = src
                .line()
                .ok_or_else(|| io_or(&mut src, "header has no end (no blank line)"))?;
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
        let res = src
            .line()
            .ok_or_else(|| io_or(&mut src, "missing the resolution line"))?;
        let res = String::from_utf8_lossy(&res).to_string();
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
        Ok(HdrReader {
            path: path.to_path_buf(),
            src,
            width,
            height,
            next_row: 0,
            scan: vec![[0u8; 4]; width as usize],
        })
    }

    /// Width in texels.
    pub fn width(&self) -> u32 {
        self.width
    }

    /// Height in texels.
    pub fn height(&self) -> u32 {
        self.height
    }

    /// Decodes the next `out.len() / width` scanlines (at most the rows left) into linear
    /// RGB.
    pub fn read_rows(&mut self, out: &mut [[f32; 3]]) -> Result<()> {
        let w = self.width as usize;
        for row in out.chunks_exact_mut(w) {
            if self.next_row == self.height {
                break;
            }
            let y = self.next_row;
            if let Err(e) = read_scanline(&mut self.src, &mut self.scan) {
                let message = match e {
                    ScanError::Truncated => {
                        if let Some(io) = self.src.error.take() {
                            return Err(Error::io(&self.path, io));
                        }
                        format!("truncated at scanline {y} of {}", self.height)
                    }
                    ScanError::Corrupt(m) => format!("scanline {y}: {m}"),
                };
                return Err(Error::Decode {
                    path: self.path.clone(),
                    format: FORMAT,
                    message,
                });
            }
            for (t, &p) in row.iter_mut().zip(&self.scan) {
                *t = rgbe_to_rgb(p);
            }
            self.next_row += 1;
        }
        Ok(())
    }
}

/// Parses a whole `.hdr` file held in memory; `path` is only used in errors.
pub fn decode(path: &Path, bytes: &[u8]) -> Result<Equirect> {
    let mut reader = HdrReader::new(path, bytes)?;
    let (w, h) = (reader.width() as usize, reader.height() as usize);
    let mut data = Vec::new();
    let mut row = vec![[0.0f32; 3]; w];
    for _ in 0..h {
        reader.read_rows(&mut row)?;
        data.extend_from_slice(&row);
    }
    Ok(Equirect {
        width: w as u32,
        height: h as u32,
        data,
    })
}

enum ScanError {
    Truncated,
    Corrupt(String),
}

fn read_scanline<R: Read>(
    cur: &mut ByteSource<R>,
    scan: &mut [[u8; 4]],
) -> std::result::Result<(), ScanError> {
    let w = scan.len();
    let b = |cur: &mut ByteSource<R>| cur.byte().ok_or(ScanError::Truncated);
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
