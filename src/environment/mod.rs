//! In-memory environments: equirectangular images (with an energy-preserving mip pyramid,
//! see [`EquirectReducer`], and the cumulative sums a conversion integrates, see
//! [`EquirectIntegral`]) and cubemaps (with mip chains), both linear RGB radiance.

pub mod hot;
mod integral;
pub mod inventory;
pub mod mips;
mod pyramid;
pub mod sample;
pub mod sun;
pub mod texels;
pub mod walk;

pub use hot::IrradianceSource;
pub use integral::EquirectIntegral;
pub use pyramid::{pyramid_level_count, EquirectReducer};

use crate::math::cubemap::{AxisMap, FACES};

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
    /// included), so ∫ L dω is the same at every level. Streams the rows through a
    /// row downsampler (`pyramid::RowDownsampler`), so the only extra memory is the result and a few rows.
    pub fn downsample(&self) -> Equirect {
        let mut reducer = EquirectReducer::new(self.width, self.height, 1);
        reducer.push_all(&self.data);
        reducer.finish()
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
        Cubemap::mip_size(self.size, m as u32)
    }

    /// Edge of mip `m` of a cube whose level 0 is `size`²: halved per level, at least 1.
    pub fn mip_size(size: u32, m: u32) -> u32 {
        (size >> m).max(1)
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

    /// This cube re-expressed through `map`, every level: the returned cube's texel at
    /// direction t holds this cube's texel at `map⁻¹(t)`, so sampling it at `map(d)` gives
    /// what sampling this cube at d gives. A signed permutation of axes maps texel centres
    /// onto texel centres, so this is an exact permutation of texels (no resampling).
    pub fn remapped(&self, map: AxisMap) -> Cubemap {
        use crate::math::cubemap::cube_face_coords;
        let source_of = map.inverse();
        let levels = (0..self.levels.len())
            .map(|m| {
                let n = self.level_size(m);
                // (s, t) is a texel centre: s = (2i + 1)/n − 1.
                let index = |c: f32| {
                    (((c + 1.0) * n as f32 - 1.0) * 0.5)
                        .round()
                        .clamp(0.0, (n - 1) as f32) as u32
                };
                let mut out = Vec::with_capacity(Cubemap::level_len(n));
                for (_, _, _, d) in walk::texel_centres(n) {
                    let (f, s, t) = cube_face_coords(source_of.apply(d));
                    out.push(self.texel(m, f, index(s), index(t)));
                }
                out
            })
            .collect();
        Cubemap {
            size: self.size,
            levels,
        }
    }

    /// This cube mirrored along world axis `axis` (0 = x, 1 = y, 2 = z), every level:
    /// the returned cube's texel at direction d holds this cube's texel at d with that
    /// coordinate negated ([`Cubemap::remapped`] with a mirror of one axis).
    pub fn mirrored(&self, axis: usize) -> Cubemap {
        self.remapped(AxisMap::mirror(axis))
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
