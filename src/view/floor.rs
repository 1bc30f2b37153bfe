//! The floor's shading by view direction. The floor is a plane of one material
//! ([`crate::view::scene`]) and every light of the bake reaches it from infinity, so what it
//! sends towards the eye at a point p, seen along v, is
//!
//! L(p, v) = T₀(v) + Σₖ Vₖ(p) Tₖ(v) + the point lights at p,
//!
//! T₀ the split-sum IBL and the lights split out that have no shadow map, Tₖ (k = 1 … 4)
//! the lights whose visibility is map k − 1's, Vₖ that visibility. The table holds the
//! T's at a grid of view directions over the upper hemisphere, shaded once a light by the
//! CPU renderer's functions (`cpu::floor_table`); both renderers read it with the same
//! bilinear interpolation (`shaders/common/view_floor.wgsl` mirrors [`FloorTable::radiance`]),
//! so a floor pixel costs a few loads where it cost the split-sum lookup and each area
//! light's LTC: on a software adapter the floor was most of the frame (docs/accuracy.md,
//! "The viewer").
//!
//! The grid: azimuth φ = atan2(v.z, v.x), column i at φᵢ = 2π (i + ½)/W − π, wrapping;
//! polar angle θ = acos(v.y), row j at θⱼ = (π/2) j/(H − 1), so the first row is the
//! zenith and the last the horizon. A view from below the floor reads the horizon's row.
//! How far the interpolation is from shading each pixel: `tests/view.rs`.

use glam::Vec3;
use rayon::prelude::*;
use std::f32::consts::{FRAC_PI_2, PI};

use crate::view::frame::MAX_SHADOW_MAPS;

/// Columns of the table (azimuths): 0.7° apart, for the sun's glossy peak on the floor at
/// grazing views, narrow in azimuth (`tests/view_area.rs`).
pub const FLOOR_AZIMUTHS: usize = 512;
/// Rows of the table (polar angles, zenith to horizon): 0.95° apart.
pub const FLOOR_POLAR_ANGLES: usize = 96;
/// Layers: T₀, then one a shadow map.
pub const FLOOR_LAYERS: usize = 1 + MAX_SHADOW_MAPS;

/// The table: a header entry (W, H, layers, 0), then layer l, row j, column i at entry
/// 1 + (l H + j) W + i, each (radiance, 0): what the GPU renderer uploads as it is.
#[derive(Clone, Debug, PartialEq)]
pub struct FloorTable {
    /// The entries.
    pub entries: Vec<[f32; 4]>,
}

/// Where a view direction falls in the grid: the two columns and the first row around
/// it, and the weights of the second column and row (`FloorCell` in view_floor.wgsl).
struct FloorCell {
    i0: usize,
    i1: usize,
    j0: usize,
    fu: f32,
    fw: f32,
}

/// The view direction of column `i`, row `j` of a grid of `w` × `h`.
pub fn floor_direction(i: usize, j: usize, (w, h): (usize, usize)) -> Vec3 {
    let phi = 2.0 * PI * (i as f32 + 0.5) / w as f32 - PI;
    let theta = FRAC_PI_2 * j as f32 / (h - 1) as f32;
    Vec3::new(
        theta.sin() * phi.cos(),
        theta.cos(),
        theta.sin() * phi.sin(),
    )
}

/// The cell of `v` in a grid of `w` × `h`.
fn floor_cell(v: Vec3, (w, h): (usize, usize)) -> FloorCell {
    let columns = w;
    let (w, h) = (w as f32, h as f32);
    let x = (v.z.atan2(v.x) + PI) / (2.0 * PI) * w - 0.5;
    let xf = x.floor();
    let i0 = (xf as i32).rem_euclid(columns as i32) as usize;
    let y = v.y.clamp(0.0, 1.0).acos() / FRAC_PI_2 * (h - 1.0);
    let j0 = y.floor().min(h - 2.0);
    FloorCell {
        i0,
        i1: (i0 + 1) % columns,
        j0: j0 as usize,
        fu: x - xf,
        fw: y - j0,
    }
}

impl FloorTable {
    /// The table of `shade`, which gives each layer's radiance for a view direction.
    pub fn new(shade: impl Fn(Vec3) -> [Vec3; FLOOR_LAYERS] + Sync) -> FloorTable {
        FloorTable::of_size((FLOOR_AZIMUTHS, FLOOR_POLAR_ANGLES), shade)
    }

    /// A table of 2 × 2 directions holding no light: what a renderer holds before it is
    /// given a light's table.
    pub fn empty() -> FloorTable {
        FloorTable::of_size((2, 2), |_| [Vec3::ZERO; FLOOR_LAYERS])
    }

    fn of_size(
        (w, h): (usize, usize),
        shade: impl Fn(Vec3) -> [Vec3; FLOOR_LAYERS] + Sync,
    ) -> FloorTable {
        let texels: Vec<[Vec3; FLOOR_LAYERS]> = (0..w * h)
            .into_par_iter()
            .map(|k| shade(floor_direction(k % w, k / w, (w, h))))
            .collect();
        let mut entries = vec![[w as f32, h as f32, FLOOR_LAYERS as f32, 0.0]];
        for l in 0..FLOOR_LAYERS {
            entries.extend(texels.iter().map(|t| t[l].extend(0.0).to_array()));
        }
        FloorTable { entries }
    }

    /// The grid's columns and rows, from the header.
    fn size(&self) -> (usize, usize) {
        (self.entries[0][0] as usize, self.entries[0][1] as usize)
    }

    /// Layer `l` at `c`, bilinear.
    fn layer(&self, c: &FloorCell, l: usize) -> Vec3 {
        let (w, h) = self.size();
        let at = |i: usize, j: usize| Vec3::from_slice(&self.entries[1 + (l * h + j) * w + i][..3]);
        let row = |j: usize| at(c.i0, j) + (at(c.i1, j) - at(c.i0, j)) * c.fu;
        let (a, b) = (row(c.j0), row(c.j0 + 1));
        a + (b - a) * c.fw
    }

    /// The floor's radiance seen along `v` (unit, towards the eye), less the point
    /// lights: T₀ plus each of the first `count` lights' maps' layer times its
    /// `visibility` (`floor_table_radiance` in view_floor.wgsl).
    pub fn radiance(&self, v: Vec3, visibility: &[f32; MAX_SHADOW_MAPS], count: u32) -> Vec3 {
        let c = floor_cell(v, self.size());
        let mut sum = self.layer(&c, 0);
        for (k, vis) in visibility
            .iter()
            .enumerate()
            .take((count as usize).min(MAX_SHADOW_MAPS))
        {
            sum += *vis * self.layer(&c, 1 + k);
        }
        sum
    }
}

/// The layer of the light whose shadow map is `index` (a record's w): 1 + index, or 0 past
/// the maps (`shadowed` reads no map for it).
pub fn floor_layer(index: f32) -> usize {
    let k = index as usize;
    if k < MAX_SHADOW_MAPS {
        1 + k
    } else {
        0
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A table of a smooth function of v reads it back at the grid's directions exactly
    /// and between them within the bilinear error; the azimuth wraps and the horizon
    /// clamps.
    #[test]
    fn reads_back_what_it_holds() {
        let f =
            |v: Vec3| [0, 1, 2, 3, 4].map(|l| Vec3::splat(1.0 + v.x + 0.5 * v.z * v.y + l as f32));
        let t = FloorTable::new(f);
        let vis = [1.0; MAX_SHADOW_MAPS];
        let sum = |v: Vec3| f(v).iter().copied().sum::<Vec3>();
        for (i, j) in [(0, 0), (5, 7), (FLOOR_AZIMUTHS - 1, FLOOR_POLAR_ANGLES - 1)] {
            let v = floor_direction(i, j, (FLOOR_AZIMUTHS, FLOOR_POLAR_ANGLES));
            assert!(
                (t.radiance(v, &vis, 4) - sum(v)).abs().max_element() < 1e-4,
                "{i} {j}"
            );
        }
        let mut worst = 0.0f32;
        for k in 0..1000 {
            let phi = k as f32 * 2.399;
            let theta = (k as f32 * 0.618).fract() * FRAC_PI_2;
            let v = Vec3::new(
                theta.sin() * phi.cos(),
                theta.cos(),
                theta.sin() * phi.sin(),
            );
            worst = worst.max((t.radiance(v, &vis, 4) - sum(v)).abs().max_element() / sum(v).x);
        }
        assert!(worst < 1e-3, "worst {worst}");
        let below = Vec3::new(0.6, -0.8, 0.0);
        let horizon = Vec3::new(1.0, 0.0, 0.0);
        assert_eq!(t.radiance(below, &vis, 4), t.radiance(horizon, &vis, 4));
        // Visibility weighs its layer only (within the bilinear error between columns).
        let dark = [0.0, 1.0, 1.0, 1.0];
        let d = t.radiance(horizon, &vis, 4) - t.radiance(horizon, &dark, 4);
        assert!((d - f(horizon)[1]).abs().max_element() < 1e-3 * f(horizon)[1].x);
        assert_eq!(floor_layer(0.0), 1);
        assert_eq!(floor_layer(MAX_SHADOW_MAPS as f32), 0);
    }
}
