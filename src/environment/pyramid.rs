//! The equirect mip pyramid: exact area-filtered halvings ([`RowDownsampler`], which works
//! on rows as they arrive so a large input never needs a second full-size copy, and
//! [`EquirectReducer`], a chain of them). A conversion reads one level of it.

use rayon::prelude::*;

use super::Equirect;

/// One exact area-filtered halving (floor, at least 1×1) applied to rows as they arrive:
/// each target texel is the solid-angle-weighted mean of the source area it covers,
/// fractional overlaps included, so ∫ L dω is kept. The horizontal pass (plain area
/// weights: all texels of a row have equal solid angle) runs on every incoming row; the
/// vertical pass (weights ∝ cos θa − cos θb of the overlap) emits a target row as soon as
/// every source row it overlaps has arrived; source rows that no later target row needs
/// are dropped. The result is bit-identical however the input is chunked.
#[derive(Clone, Debug)]
pub struct RowDownsampler {
    src_width: usize,
    src_height: usize,
    width: usize,
    height: usize,
    x_taps: Vec<Vec<(usize, f32)>>,
    y_taps: Vec<Vec<(usize, f32)>>,
    /// Horizontally filtered source rows `first..received`, `width` texels each.
    rows: Vec<[f32; 3]>,
    first: usize,
    received: usize,
    emitted: usize,
}

impl RowDownsampler {
    /// A halving of a `src_width`×`src_height` equirect.
    pub fn new(src_width: u32, src_height: u32) -> Self {
        let (w0, h0) = (src_width.max(1) as usize, src_height.max(1) as usize);
        let (w1, h1) = ((w0 / 2).max(1), (h0 / 2).max(1));
        let pi = std::f64::consts::PI;
        RowDownsampler {
            src_width: w0,
            src_height: h0,
            width: w1,
            height: h1,
            x_taps: overlap_weights(w0, w1, |a, b| b - a),
            y_taps: overlap_weights(h0, h1, |a, b| {
                (pi * a / h0 as f64).cos() - (pi * b / h0 as f64).cos()
            }),
            rows: Vec::new(),
            first: 0,
            received: 0,
            emitted: 0,
        }
    }

    /// Width of the halved image.
    pub fn width(&self) -> u32 {
        self.width as u32
    }

    /// Height of the halved image.
    pub fn height(&self) -> u32 {
        self.height as u32
    }

    /// Whether every target row has been emitted.
    #[cfg(test)]
    pub fn is_complete(&self) -> bool {
        self.emitted == self.height
    }

    /// Feeds the next whole source rows, top to bottom (`src.len()` a multiple of the
    /// source width; rows past the source height are ignored) and appends every target row
    /// that is now complete to `out`.
    pub fn push(&mut self, src: &[[f32; 3]], out: &mut Vec<[f32; 3]>) {
        let (w0, w1) = (self.src_width, self.width);
        debug_assert_eq!(src.len() % w0, 0, "partial source row");
        let n = (src.len() / w0).min(self.src_height - self.received);
        let start = self.rows.len();
        self.rows.resize(start + n * w1, [0.0; 3]);
        let x_taps = &self.x_taps;
        self.rows[start..]
            .par_chunks_mut(w1)
            .zip(src[..n * w0].par_chunks(w0))
            .for_each(|(row_out, row)| {
                for (t, taps) in row_out.iter_mut().zip(x_taps) {
                    *t = weighted_sum(taps, |i| row[i]);
                }
            });
        self.received += n;

        // Target rows whose last overlapping source row has arrived.
        let needs = |taps: &Vec<(usize, f32)>| taps.last().map_or(0, |t| t.0 + 1);
        let mut ready = self.emitted;
        while ready < self.height && needs(&self.y_taps[ready]) <= self.received {
            ready += 1;
        }
        if ready > self.emitted {
            let (rows, first) = (&self.rows, self.first);
            let old = out.len();
            out.resize(old + (ready - self.emitted) * w1, [0.0; 3]);
            out[old..]
                .par_chunks_mut(w1)
                .zip(&self.y_taps[self.emitted..ready])
                .for_each(|(row_out, taps)| {
                    for (x, t) in row_out.iter_mut().enumerate() {
                        *t = weighted_sum(taps, |r| rows[(r - first) * w1 + x]);
                    }
                });
            self.emitted = ready;
        }
        // Drop the source rows above the first one the next target row overlaps.
        let keep_from = match self.y_taps.get(self.emitted) {
            Some(taps) => taps.first().map_or(self.received, |t| t.0),
            None => self.received,
        }
        .clamp(self.first, self.received);
        self.rows.drain(..(keep_from - self.first) * w1);
        self.first = keep_from;
    }
}

/// Reduces an equirect by a number of halvings (a chain of `RowDownsampler`s) while its
/// rows are pushed, top to bottom: a reader can decode a large image row by row and keep
/// only the level a conversion needs. The result is bit-identical to halving the whole
/// image level by level.
#[derive(Clone, Debug)]
pub struct EquirectReducer {
    stages: Vec<RowDownsampler>,
    width: u32,
    height: u32,
    src_width: u32,
    data: Vec<[f32; 3]>,
}

impl EquirectReducer {
    /// Texels pushed at once by [`EquirectReducer::push_all`]: bounds the intermediate
    /// buffers (about 12 MiB) while keeping the row passes parallel.
    const CHUNK_TEXELS: usize = 1 << 20;

    /// A reduction of a `width`×`height` equirect by `levels` halvings, clamped to the
    /// pyramid's depth (a height of 1 is not halved further).
    pub fn new(width: u32, height: u32, levels: u32) -> Self {
        let levels = levels.min(pyramid_level_count(height) - 1);
        let mut stages: Vec<RowDownsampler> = Vec::new();
        let (mut w, mut h) = (width.max(1), height.max(1));
        for _ in 0..levels {
            let stage = RowDownsampler::new(w, h);
            (w, h) = (stage.width(), stage.height());
            stages.push(stage);
        }
        EquirectReducer {
            stages,
            width: w,
            height: h,
            src_width: width.max(1),
            data: Vec::new(),
        }
    }

    #[cfg(any(test, feature = "internals"))]
    /// Halvings applied.
    pub fn levels(&self) -> u32 {
        self.stages.len() as u32
    }

    #[cfg(any(test, feature = "internals"))]
    /// Width of the result.
    pub fn width(&self) -> u32 {
        self.width
    }

    #[cfg(any(test, feature = "internals"))]
    /// Height of the result.
    pub fn height(&self) -> u32 {
        self.height
    }

    /// Feeds the next whole rows of the full-size image.
    pub fn push(&mut self, rows: &[[f32; 3]]) {
        let Some((last, chain)) = self.stages.split_last_mut() else {
            let room = self.width as usize * self.height as usize - self.data.len();
            self.data.extend_from_slice(&rows[..rows.len().min(room)]);
            return;
        };
        let mut carried: Option<Vec<[f32; 3]>> = None;
        for stage in chain {
            let mut out = Vec::new();
            stage.push(carried.as_deref().unwrap_or(rows), &mut out);
            carried = Some(out);
        }
        last.push(carried.as_deref().unwrap_or(rows), &mut self.data);
    }

    /// Feeds a whole image (or many rows) in bounded chunks.
    pub fn push_all(&mut self, data: &[[f32; 3]]) {
        let w = self.src_width as usize;
        for chunk in data.chunks((Self::CHUNK_TEXELS / w).max(1) * w) {
            self.push(chunk);
        }
    }

    #[cfg(any(test, feature = "internals"))]
    /// Whether every row of the result has been produced.
    pub fn is_complete(&self) -> bool {
        self.data.len() == self.width as usize * self.height as usize
    }

    /// The reduced image; rows never produced (input cut short) are black.
    pub fn finish(mut self) -> Equirect {
        let len = self.width as usize * self.height as usize;
        self.data.resize(len, [0.0; 3]);
        Equirect {
            width: self.width,
            height: self.height,
            data: self.data,
        }
    }
}

/// For each of `n1` target cells covering `n0` source cells, the (source index, weight)
/// pairs of the overlap, with weights from `measure(a, b)` of the overlapping interval in
/// source units, normalised to sum 1.
fn overlap_weights(
    n0: usize,
    n1: usize,
    measure: impl Fn(f64, f64) -> f64,
) -> Vec<Vec<(usize, f32)>> {
    let scale = n0 as f64 / n1 as f64;
    (0..n1)
        .map(|t| {
            let (a, b) = (t as f64 * scale, (t + 1) as f64 * scale);
            let mut taps: Vec<(usize, f64)> = (a.floor() as usize..(b.ceil() as usize).min(n0))
                .map(|i| {
                    let lo = a.max(i as f64);
                    let hi = b.min((i + 1) as f64);
                    (i, measure(lo, hi).max(0.0))
                })
                .filter(|&(_, w)| w > 0.0)
                .collect();
            let total: f64 = taps.iter().map(|t| t.1).sum();
            if total > 0.0 {
                taps.iter_mut().for_each(|t| t.1 /= total);
            }
            taps.into_iter().map(|(i, w)| (i, w as f32)).collect()
        })
        .collect()
}

fn weighted_sum(taps: &[(usize, f32)], texel: impl Fn(usize) -> [f32; 3]) -> [f32; 3] {
    let mut acc = [0.0f32; 3];
    for &(i, w) in taps {
        let v = texel(i);
        for c in 0..3 {
            acc[c] += w * v[c];
        }
    }
    acc
}

/// Number of levels of an equirect pyramid whose level 0 is `height` texels high: levels
/// halve (floor, at least 1) down to a height of 1.
pub fn pyramid_level_count(height: u32) -> u32 {
    32 - height.max(1).leading_zeros()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A deterministic, non-smooth test image.
    fn image(width: u32, height: u32) -> Equirect {
        let data = (0..width * height)
            .map(|i| {
                let h = i.wrapping_mul(2_654_435_761);
                [
                    (h % 1000) as f32 / 100.0,
                    ((h >> 10) % 1000) as f32,
                    (i % 7) as f32 * 0.25,
                ]
            })
            .collect();
        Equirect {
            width,
            height,
            data,
        }
    }

    /// The halving done the obvious way: a full horizontal pass into a temporary image,
    /// then a full vertical pass (the formulation the streaming version must match).
    fn two_pass_halving(img: &Equirect) -> Equirect {
        let (w0, h0) = (img.width as usize, img.height as usize);
        let (w1, h1) = ((w0 / 2).max(1), (h0 / 2).max(1));
        let xw = overlap_weights(w0, w1, |a, b| b - a);
        let tmp: Vec<[f32; 3]> = (0..h0)
            .flat_map(|y| {
                let row = &img.data[y * w0..(y + 1) * w0];
                xw.iter().map(move |taps| weighted_sum(taps, |i| row[i]))
            })
            .collect();
        let pi = std::f64::consts::PI;
        let yw = overlap_weights(h0, h1, |a, b| {
            (pi * a / h0 as f64).cos() - (pi * b / h0 as f64).cos()
        });
        let data = yw
            .iter()
            .flat_map(|taps| (0..w1).map(|x| weighted_sum(taps, |r| tmp[r * w1 + x])))
            .collect();
        Equirect {
            width: w1 as u32,
            height: h1 as u32,
            data,
        }
    }

    fn energy(img: &Equirect) -> [f64; 3] {
        let mut e = [0.0; 3];
        for y in 0..img.height {
            let omega = img.row_solid_angle(y);
            for x in 0..img.width {
                let t = img.get(x, y);
                (0..3).for_each(|c| e[c] += t[c] as f64 * omega);
            }
        }
        e
    }

    #[test]
    fn streaming_halving_is_bit_identical_for_any_chunking() {
        for (w, h) in [
            (64, 32),
            (37, 18),
            (101, 50),
            (10, 5),
            (3, 1),
            (1, 1),
            (2, 3),
        ] {
            let img = image(w, h);
            let expected = two_pass_halving(&img);
            for rows_per_push in [1usize, 2, 3, 7, h as usize] {
                let mut stage = RowDownsampler::new(w, h);
                let mut out = Vec::new();
                for chunk in img.data.chunks(rows_per_push * w as usize) {
                    stage.push(chunk, &mut out);
                }
                assert!(stage.is_complete(), "{w}×{h} by {rows_per_push}");
                assert_eq!(
                    out, expected.data,
                    "{w}×{h} pushed {rows_per_push} rows at a time"
                );
                // Rows are dropped as soon as no target row needs them.
                assert!(stage.rows.len() <= 4 * stage.width + rows_per_push * w as usize);
            }
        }
    }

    #[test]
    fn reducer_equals_repeated_halving_and_keeps_energy() {
        let img = image(256, 128);
        let mut expected = img.clone();
        for levels in 0..=8 {
            let mut reducer = EquirectReducer::new(img.width, img.height, levels);
            for row in img.data.chunks(img.width as usize * 5) {
                reducer.push(row);
            }
            assert!(reducer.is_complete());
            assert_eq!(reducer.levels(), levels.min(7));
            let got = reducer.finish();
            assert_eq!(got, expected, "{levels} halvings");
            let (e0, e1) = (energy(&img), energy(&got));
            for c in 0..3 {
                assert!(
                    (e1[c] - e0[c]).abs() <= 1e-5 * e0[c],
                    "energy {levels}: {e0:?} {e1:?}"
                );
            }
            if levels < 7 {
                expected = expected.downsample();
            }
        }
    }

    #[test]
    fn a_short_input_leaves_the_missing_rows_black() {
        let img = image(16, 8);
        let mut reducer = EquirectReducer::new(16, 8, 1);
        reducer.push(&img.data[..16 * 4]);
        assert!(!reducer.is_complete());
        let got = reducer.finish();
        assert_eq!(got.data.len(), 8 * 4);
        assert!(got.data[8 * 3..].iter().all(|t| *t == [0.0; 3]));
    }
}
