//! In-memory environments: equirectangular images (with an energy-preserving mip pyramid)
//! and cubemaps (with mip chains), both linear RGB radiance.

use rayon::prelude::*;

use crate::math::cubemap::FACES;

/// A linear-RGB equirectangular image, rows top (+Y) to bottom.
#[derive(Clone, Debug, PartialEq)]
pub struct Equirect {
    /// Width in texels.
    pub width: u32,
    /// Height in texels.
    pub height: u32,
    /// Row-major RGB radiance.
    pub data: Vec<[f32; 3]>,
}

impl Equirect {
    /// Texel (x, y).
    pub fn get(&self, x: u32, y: u32) -> [f32; 3] {
        self.data[(y * self.width + x) as usize]
    }

    /// Solid angle of one texel of row `y` (all texels of a row are equal):
    /// (2π / W) · (cos θ_top − cos θ_bottom).
    pub fn row_solid_angle(&self, y: u32) -> f64 {
        let h = self.height as f64;
        let pi = std::f64::consts::PI;
        2.0 * pi / self.width as f64 * ((pi * y as f64 / h).cos() - (pi * (y + 1) as f64 / h).cos())
    }

    /// Half-size copy (floor, at least 1×1) by an exact area filter: every target texel is
    /// the solid-angle-weighted mean of the source area it covers (fractional overlaps
    /// included), so ∫ L dω is the same at every level.
    pub fn downsample(&self) -> Equirect {
        let (w0, h0) = (self.width as usize, self.height as usize);
        let (w1, h1) = ((w0 / 2).max(1), (h0 / 2).max(1));
        // Horizontal pass: plain area weights (all texels of a row have equal solid angle).
        let xw = overlap_weights(w0, w1, |a, b| b - a);
        let mut tmp = vec![[0.0f32; 3]; w1 * h0];
        tmp.par_chunks_mut(w1).enumerate().for_each(|(y, out)| {
            let row = &self.data[y * w0..(y + 1) * w0];
            for (x, taps) in xw.iter().enumerate() {
                out[x] = weighted_sum(taps, |i| row[i]);
            }
        });
        // Vertical pass: weights ∝ solid angle of the overlap, cos θa − cos θb.
        let pi = std::f64::consts::PI;
        let yw = overlap_weights(h0, h1, |a, b| {
            (pi * a / h0 as f64).cos() - (pi * b / h0 as f64).cos()
        });
        let mut data = vec![[0.0f32; 3]; w1 * h1];
        data.par_chunks_mut(w1).zip(&yw).for_each(|(out, taps)| {
            for (x, t) in out.iter_mut().enumerate() {
                *t = weighted_sum(taps, |r| tmp[r * w1 + x]);
            }
        });
        Equirect {
            width: w1 as u32,
            height: h1 as u32,
            data,
        }
    }
}

/// Box-filters each row along φ over the arc that one row spans in θ, so a texel holds
/// the mean over a patch as wide as it is tall: (π/H) in θ by (π/H) of arc in φ, i.e.
/// 1/sin θ · W/(2H) columns (fractional ends weighted by coverage, wrapping around).
/// Near the poles the equirect is oversampled in φ; after this filter a lookup at the
/// level whose row height matches a footprint averages the whole footprint, in φ too.
/// Row sums are unchanged (the box is circular), so energy is kept.
pub fn prefilter_latitude(img: &mut Equirect) {
    let (w, h) = (img.width as usize, img.height as usize);
    let pi = std::f64::consts::PI;
    img.data.par_chunks_mut(w).enumerate().for_each(|(y, row)| {
        let sin_theta = (pi * (y as f64 + 0.5) / h as f64).sin();
        let width = (w as f64 / (2.0 * h as f64) / sin_theta).min(w as f64);
        if width <= 1.0 {
            return;
        }
        // Prefix sums over three periods, so every window [c − W/2, c + W/2] with c shifted
        // by one period lies inside without wrapping arithmetic (W ≤ w).
        let mut prefix = vec![[0.0f64; 3]; 3 * w + 1];
        for x in 0..3 * w {
            let t = row[x % w];
            for c in 0..3 {
                prefix[x + 1][c] = prefix[x][c] + t[c] as f64;
            }
        }
        let at = |a: f64| -> [f64; 3] {
            let i = (a.floor() as usize).min(3 * w - 1);
            let f = a - i as f64;
            [0, 1, 2].map(|c| prefix[i][c] + f * (prefix[i + 1][c] - prefix[i][c]))
        };
        let half = 0.5 * width;
        let out: Vec<[f32; 3]> = (0..w)
            .map(|x| {
                let centre = x as f64 + 0.5 + w as f64;
                let (lo, hi) = (at(centre - half), at(centre + half));
                [0, 1, 2].map(|c| ((hi[c] - lo[c]) / width) as f32)
            })
            .collect();
        row.copy_from_slice(&out);
    });
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

/// An equirect image's successive half-size levels, down to a height of 1, each
/// prefiltered along φ by [`prefilter_latitude`] for lookups. Levels finer than
/// `first_level` (which no lookup needs) are not kept, to bound memory.
#[derive(Clone, Debug)]
pub struct EquirectPyramid {
    /// Width of level 0 (the input).
    pub width: u32,
    /// Height of level 0.
    pub height: u32,
    /// The finest level kept.
    pub first_level: u32,
    stored: Vec<Equirect>,
}

impl EquirectPyramid {
    /// Builds levels down to 1 texel high from `base`: each level is the exact area
    /// downsample of the unfiltered level above (rows in parallel); levels from
    /// `first_level` on are then latitude-prefiltered and kept. `base` is only copied when
    /// level 0 itself is kept.
    pub fn new(base: &Equirect, first_level: u32) -> Self {
        let (width, height) = (base.width, base.height);
        let count = pyramid_level_count(height);
        let first_level = first_level.min(count - 1);
        let mut stored = Vec::new();
        let (mut current, start) = if first_level == 0 || count == 1 {
            (base.clone(), 0)
        } else {
            (base.downsample(), 1)
        };
        for level in start..count {
            let next = (level + 1 < count).then(|| current.downsample());
            if level >= first_level {
                prefilter_latitude(&mut current);
                stored.push(current);
            }
            match next {
                Some(n) => current = n,
                None => break,
            }
        }
        EquirectPyramid {
            width,
            height,
            first_level,
            stored,
        }
    }

    /// Total number of levels (including the ones not kept).
    pub fn level_count(&self) -> u32 {
        self.first_level + self.stored.len() as u32
    }

    /// Level `l` (≥ `first_level`).
    pub fn level(&self, l: u32) -> &Equirect {
        &self.stored[(l - self.first_level) as usize]
    }

    /// The kept levels, finest first.
    pub fn stored(&self) -> &[Equirect] {
        &self.stored
    }
}

/// A cubemap with a mip chain: `levels[m]` holds the 6 faces (+X, −X, +Y, −Y, +Z, −Z) of
/// size `size >> m`, face-major, rows top to bottom, RGBA (A = 1).
#[derive(Clone, Debug, PartialEq)]
pub struct Cubemap {
    /// Edge of level 0 in texels.
    pub size: u32,
    /// Mip levels, largest first.
    pub levels: Vec<Vec<[f32; 4]>>,
}

impl Cubemap {
    /// Edge of mip `m`.
    pub fn level_size(&self, m: usize) -> u32 {
        (self.size >> m).max(1)
    }

    /// Texel (i, j) of `face` at mip `m`.
    pub fn texel(&self, m: usize, face: u32, i: u32, j: u32) -> [f32; 4] {
        let n = self.level_size(m);
        self.levels[m][((face * n + j) * n + i) as usize]
    }

    /// Texels of one face at mip `m`.
    pub fn face(&self, m: usize, face: usize) -> &[[f32; 4]] {
        let n = self.level_size(m) as usize;
        &self.levels[m][face * n * n..(face + 1) * n * n]
    }

    /// Number of levels in a full chain down to 1×1: log2(size) + 1.
    pub fn full_mip_count(size: u32) -> u32 {
        32 - size.leading_zeros()
    }

    /// Texels per level for `FACES` faces of edge `n`.
    pub fn level_len(n: u32) -> usize {
        FACES * (n as usize) * (n as usize)
    }
}

/// An environment as loaded from a file.
#[derive(Clone, Debug)]
pub enum Environment {
    /// An equirectangular (latitude-longitude) image.
    Equirect(Equirect),
    /// A cubemap (from face files, a cross, or a KTX2/DDS cubemap).
    Cube(Cubemap),
}
