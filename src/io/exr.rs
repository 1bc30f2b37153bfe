//! OpenEXR reader (whole, or streamed row by row into a [`RowSink`]) and writer for
//! float32 images with named channels.

use std::io::Cursor;

use exr::prelude::*;

/// The bytes of an OpenEXR file holding `image`.
fn image_bytes<'img, L: exr::image::write::layers::WritableLayers<'img>>(
    image: &'img Image<L>,
) -> std::result::Result<Vec<u8>, String> {
    let mut out = Cursor::new(Vec::new());
    image
        .write()
        .non_parallel()
        .to_buffered(&mut out)
        .map_err(|e| e.to_string())?;
    Ok(out.into_inner())
}

/// Encodes a width×height image with two float32 channels "R" and "G".
pub fn encode_rg32(
    width: u32,
    height: u32,
    rg: &[[f32; 2]],
) -> std::result::Result<Vec<u8>, String> {
    let w = width as usize;
    let channels = SpecificChannels::build()
        .with_channel("R")
        .with_channel("G")
        .with_pixel_fn(|pos: Vec2<usize>| {
            let t = rg[pos.y() * w + pos.x()];
            (t[0], t[1])
        });
    image_bytes(&Image::from_channels(
        (width as usize, height as usize),
        channels,
    ))
}

/// Encodes a width×height RGB float32 image (channels R, G, B), rows top to bottom.
pub fn encode_rgb32(
    width: u32,
    height: u32,
    rgb: &[[f32; 3]],
) -> std::result::Result<Vec<u8>, String> {
    let w = width as usize;
    let channels = SpecificChannels::rgb(|pos: Vec2<usize>| {
        let t = rgb[pos.y() * w + pos.x()];
        (t[0], t[1], t[2])
    });
    image_bytes(&Image::from_channels(
        (width as usize, height as usize),
        channels,
    ))
}

/// Receives an image's rows, top to bottom, in batches of whole rows.
pub trait RowSink {
    /// Takes the next rows (a multiple of the width); returns false to stop caring about
    /// the rest (the caller will read the file another way).
    fn rows(&mut self, rows: &mut [[f32; 3]]) -> bool;
}

/// Width, height, compression and rows per block of an EXR's first layer, after checking
/// its size, that it has R, G and B channels and (DWA files) every chunk's counters;
/// nothing is allocated for pixels yet.
fn check_header<R: std::io::Read + std::io::Seek>(
    path: &std::path::Path,
    mut reader: R,
) -> crate::Result<(usize, usize, Compression, usize)> {
    use crate::Error;
    let meta = exr::meta::MetaData::read_from_buffered(&mut reader, false)
        .map_err(|e| decode_error(path, e))?;
    let header = meta.headers.first().ok_or_else(|| Error::Decode {
        path: path.to_path_buf(),
        format: "OpenEXR",
        message: "no layers".into(),
    })?;
    let size = header.layer_size;
    super::limits::check_dimensions(path, size.0 as u32, size.1 as u32)?;
    let names: Vec<String> = header
        .channels
        .list
        .iter()
        .map(|c| c.name.to_string())
        .collect();
    for needed in ["R", "G", "B"] {
        if !names.iter().any(|n| n == needed) {
            return Err(Error::UnsupportedInput {
                path: path.to_path_buf(),
                message: format!(
                    "OpenEXR first layer has channels [{}]; splitsum needs R, G and B",
                    names.join(", ")
                ),
            });
        }
    }
    let block_rows = match header.blocks {
        exr::meta::BlockDescription::ScanLines => header.compression.scan_lines_per_block(),
        exr::meta::BlockDescription::Tiles(t) => t.tile_size.y(),
    };
    if meta
        .headers
        .iter()
        .any(|h| matches!(h.compression, Compression::DWAA(_) | Compression::DWAB(_)))
    {
        reader
            .seek(std::io::SeekFrom::Start(0))
            .map_err(|e| Error::io(path, e))?;
        check_dwa_chunks(path, reader)?;
    }
    Ok((size.0, size.1, header.compression, block_rows.max(1)))
}

/// Counters 1, 6, 7, 8 and 9 of the eleven little-endian u64s that open every DWA chunk:
/// the uncompressed "unknown" section, the RLE sizes and the AC and DC coefficient counts.
const DWA_SIZE_COUNTERS: [usize; 5] = [1, 6, 7, 8, 9];

/// The `exr` crate sizes some DWAA/DWAB buffers from the counters in each chunk's leader
/// before checking them: a counter of 2⁶¹ AC coefficients made it request 4 EiB, which
/// aborts the process (a fuzz find, `tests/fuzz_regressions/exr-dwa-huge-count.exr`).
/// Every DWA chunk's counters are therefore checked first against a generous bound on
/// what a block can hold: 4 × its pixels (rounded up to whole 8×8 DCT blocks) × the
/// bytes per pixel of all channels.
fn check_dwa_chunks(
    path: &std::path::Path,
    reader: impl std::io::Read + std::io::Seek,
) -> crate::Result<()> {
    let chunks = exr::block::read(reader, false).map_err(|e| decode_error(path, e))?;
    let headers = chunks.headers().to_vec();
    for (index, chunk) in chunks
        .all_chunks(false)
        .map_err(|e| decode_error(path, e))?
        .enumerate()
    {
        let chunk = chunk.map_err(|e| decode_error(path, e))?;
        let Some(header) = headers.get(chunk.layer_index) else {
            continue;
        };
        if !matches!(
            header.compression,
            Compression::DWAA(_) | Compression::DWAB(_)
        ) {
            continue;
        }
        let bytes = match &chunk.compressed_block {
            exr::block::chunk::CompressedBlock::ScanLine(b) => &b.compressed_pixels_le,
            exr::block::chunk::CompressedBlock::Tile(b) => &b.compressed_pixels_le,
            _ => continue,
        };
        let block = header.max_block_pixel_size();
        let bound = 4
            * block.x().next_multiple_of(8) as u64
            * block.y().next_multiple_of(8) as u64
            * header.channels.bytes_per_pixel as u64;
        for k in DWA_SIZE_COUNTERS {
            let Some(counter) = bytes.get(8 * k..8 * k + 8) else {
                break; // a truncated leader: the decoder reports it
            };
            let value = u64::from_le_bytes(counter.try_into().unwrap_or([0; 8]));
            if value > bound {
                return Err(crate::Error::Decode {
                    path: path.to_path_buf(),
                    format: "OpenEXR",
                    message: format!(
                        "DWA chunk {index} claims {value} for a block of at most {bound} bytes"
                    ),
                });
            }
        }
    }
    Ok(())
}

fn decode_error(path: &std::path::Path, e: exr::error::Error) -> crate::Error {
    crate::Error::Decode {
        path: path.to_path_buf(),
        format: "OpenEXR",
        message: e.to_string(),
    }
}

/// Maps a pixel-reading error: an unsupported compression or feature is named.
fn read_error(
    path: &std::path::Path,
    compression: Compression,
    e: exr::error::Error,
) -> crate::Error {
    match e {
        exr::error::Error::NotSupported(what) => crate::Error::UnsupportedInput {
            path: path.to_path_buf(),
            message: format!("OpenEXR {compression} compression or feature not supported: {what}"),
        },
        other => decode_error(path, other),
    }
}

/// Pixel storage of a whole decode that allocates a band of rows only when one of its
/// pixels arrives: a small file claiming a large size (the `exr` fuzz target's find,
/// `tests/fuzz_regressions/exr-huge-claimed-size.exr`) allocates nothing before its
/// blocks are actually read.
struct LazyBands {
    width: usize,
    height: usize,
    bands: Vec<Option<Vec<[f32; 3]>>>,
}

impl LazyBands {
    const ROWS: usize = 64;

    fn new(width: usize, height: usize) -> Self {
        LazyBands {
            width,
            height,
            bands: vec![None; height.div_ceil(Self::ROWS)],
        }
    }

    fn rows_in(&self, band: usize) -> usize {
        Self::ROWS.min(self.height - band * Self::ROWS)
    }

    /// The whole image, row-major; bands never written are black. Each band is freed as
    /// it is copied, so the peak stays about one image.
    fn into_data(self) -> Vec<[f32; 3]> {
        let mut data = Vec::with_capacity(self.width * self.height);
        let rows: Vec<usize> = (0..self.bands.len()).map(|b| self.rows_in(b)).collect();
        for (band, rows) in self.bands.into_iter().zip(rows) {
            match band {
                Some(v) => data.extend_from_slice(&v),
                None => data.resize(data.len() + rows * self.width, [0.0; 3]),
            }
        }
        data
    }
}

/// Where a decode puts the pixels the `exr` crate delivers, one at a time.
trait PixelStore {
    fn set(&mut self, pos: Vec2<usize>, texel: [f32; 3]);
}

impl PixelStore for LazyBands {
    fn set(&mut self, pos: Vec2<usize>, texel: [f32; 3]) {
        let (x, y) = (pos.x(), pos.y());
        if x >= self.width || y >= self.height {
            return;
        }
        let b = y / Self::ROWS;
        let len = self.rows_in(b) * self.width;
        let band = self.bands[b].get_or_insert_with(|| vec![[0.0; 3]; len]);
        band[(y - b * Self::ROWS) * self.width + x] = texel;
    }
}

/// Decodes the first layer's R, G and B channels (half, float or uint, largest resolution
/// level, blocks one at a time in file order) into `store`.
fn read_rgb<T: PixelStore>(
    path: &std::path::Path,
    compression: Compression,
    reader: impl std::io::Read + std::io::Seek,
    store: T,
) -> crate::Result<T> {
    let slot = std::cell::Cell::new(Some(store));
    let image = read()
        .no_deep_data()
        .largest_resolution_level()
        .rgb_channels(
            |_, _| slot.take(),
            |store: &mut Option<T>, pos: Vec2<usize>, (r, g, b): (f32, f32, f32)| {
                if let Some(store) = store {
                    store.set(pos, [r, g, b]);
                }
            },
        )
        .first_valid_layer()
        .all_attributes()
        .non_parallel()
        .from_buffered(reader)
        .map_err(|e| read_error(path, compression, e))?;
    image
        .layer_data
        .channel_data
        .pixels
        .ok_or_else(|| crate::Error::Decode {
            path: path.to_path_buf(),
            format: "OpenEXR",
            message: "no layer with R, G and B channels".into(),
        })
}

/// Reads the first layer's R, G and B channels (half, float or uint) at full resolution.
/// The header is read first, so the size is checked before any pixel is allocated and an
/// unsupported compression is named in the error.
pub fn decode(path: &std::path::Path, bytes: &[u8]) -> crate::Result<crate::environment::Equirect> {
    let (w, h, compression, _) = check_header(path, Cursor::new(bytes))?;
    let bands = read_rgb(path, compression, Cursor::new(bytes), LazyBands::new(w, h))?;
    Ok(crate::environment::Equirect {
        width: w as u32,
        height: h as u32,
        data: bands.into_data(),
    })
}

/// Collects pixels as the decoder delivers them into a band of whole rows (a multiple of
/// the block height) and hands each full band to a [`RowSink`]. Blocks may arrive in any
/// order within the band (tiles of one tile row); a pixel outside the current band means
/// the file is not stored top to bottom, and streaming stops.
struct RowBatcher<S> {
    sink: S,
    width: usize,
    height: usize,
    band: Vec<[f32; 3]>,
    band_rows: usize,
    band_start: usize,
    filled: usize,
    in_order: bool,
}

impl<S: RowSink> RowBatcher<S> {
    fn rows_in_band(&self) -> usize {
        self.band_rows.min(self.height - self.band_start)
    }
}

impl<S: RowSink> PixelStore for RowBatcher<S> {
    fn set(&mut self, pos: Vec2<usize>, texel: [f32; 3]) {
        let (x, y) = (pos.x(), pos.y());
        if !self.in_order || x >= self.width {
            self.in_order = false;
            return;
        }
        if y < self.band_start || y >= self.band_start + self.rows_in_band() {
            self.in_order = false;
            return;
        }
        self.band[(y - self.band_start) * self.width + x] = texel;
        self.filled += 1;
        if self.filled == self.rows_in_band() * self.width {
            let n = self.filled;
            if !self.sink.rows(&mut self.band[..n]) {
                self.in_order = false;
            }
            self.band[..n].fill([0.0; 3]);
            self.band_start += self.rows_in_band();
            self.filled = 0;
        }
    }
}

/// The info [`decode_streaming`] needs before it reads pixels.
#[derive(Clone, Copy, Debug)]
pub struct ExrInfo {
    /// Width of the first layer.
    pub width: u32,
    /// Height of the first layer.
    pub height: u32,
    compression: Compression,
    /// Rows per block: the scanlines of one compressed block, or the tile height.
    block_rows: usize,
}

/// Reads and checks the header of an EXR file (see [`decode`]).
pub fn read_info(
    path: &std::path::Path,
    reader: impl std::io::Read + std::io::Seek,
) -> crate::Result<ExrInfo> {
    let (w, h, compression, block_rows) = check_header(path, reader)?;
    Ok(ExrInfo {
        width: w as u32,
        height: h as u32,
        compression,
        block_rows,
    })
}

/// Decodes the first layer like [`decode`] but hands its rows to `sink` in bands of
/// about `batch_texels` texels (whole blocks) instead of holding the image. Blocks are
/// decompressed one at a time in file order, so a file stored top to bottom (INCREASING_Y
/// scanlines, or tiles row of tiles by row of tiles) streams; for any other order, or when
/// the sink returns false, the result is `None` and the caller reads the file whole.
pub fn decode_streaming<S: RowSink>(
    path: &std::path::Path,
    info: ExrInfo,
    reader: impl std::io::Read + std::io::Seek,
    sink: S,
    batch_texels: usize,
) -> crate::Result<Option<S>> {
    let (w, h) = (info.width as usize, info.height as usize);
    let band_rows = (batch_texels / (w * info.block_rows)).max(1) * info.block_rows;
    let batcher = RowBatcher {
        sink,
        width: w,
        height: h,
        band: vec![[0.0; 3]; band_rows.min(h) * w],
        band_rows,
        band_start: 0,
        filled: 0,
        in_order: true,
    };
    let batcher = read_rgb(path, info.compression, reader, batcher)?;
    let complete = batcher.in_order && batcher.band_start == h;
    Ok(complete.then_some(batcher.sink))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Records the first texel of every band it receives.
    struct Firsts(Vec<[f32; 3]>);

    impl RowSink for Firsts {
        fn rows(&mut self, rows: &mut [[f32; 3]]) -> bool {
            self.0.push(rows[0]);
            true
        }
    }

    fn batcher(width: usize, height: usize, band_rows: usize) -> RowBatcher<Firsts> {
        RowBatcher {
            sink: Firsts(Vec::new()),
            width,
            height,
            band: vec![[0.0; 3]; band_rows.min(height) * width],
            band_rows,
            band_start: 0,
            filled: 0,
            in_order: true,
        }
    }

    /// Tiles arrive in any order within a band of rows: each band is handed on once full,
    /// the last (short) band included.
    #[test]
    fn bands_fill_in_any_order() {
        let mut b = batcher(4, 5, 2);
        // Right half before left half in every band, as tiles of a row of tiles would.
        for y0 in [0, 2, 4] {
            for xs in [2..4, 0..2] {
                for y in y0..(y0 + 2).min(5) {
                    for x in xs.clone() {
                        b.set(Vec2(x, y), [(y * 4 + x) as f32; 3]);
                    }
                }
            }
        }
        assert!(b.in_order);
        assert_eq!(b.band_start, 5);
        assert_eq!(b.sink.0, vec![[0.0; 3], [8.0; 3], [16.0; 3]]);
    }

    /// A block from a later band before the current band is full (bottom-up lines,
    /// random tiles) stops streaming; so does a position outside the image.
    #[test]
    fn a_block_from_another_band_stops_streaming() {
        let mut b = batcher(4, 4, 2);
        b.set(Vec2(0, 2), [1.0; 3]);
        assert!(!b.in_order);
        let mut b = batcher(4, 4, 2);
        b.set(Vec2(4, 0), [1.0; 3]);
        assert!(!b.in_order);
        let mut b = batcher(4, 4, 2);
        for x in 0..4 {
            b.set(Vec2(x, 1), [1.0; 3]);
        }
        assert!(b.in_order && b.band_start == 0);
        for x in 0..4 {
            b.set(Vec2(x, 0), [1.0; 3]);
        }
        assert_eq!(b.band_start, 2);
        b.set(Vec2(0, 1), [1.0; 3]);
        assert!(!b.in_order);
    }
}
