//! The lights' shadows on the floor, looked up from a grid laid on the floor. A floor
//! point's visibility of a light depends on where it is, not on where the eye is, and
//! neither the object nor the lights move while the camera does; so every light's
//! visibility ([`layer_visibility`], its map's lookup and soft shadow) is computed once,
//! at the nodes of one grid over the floor, when the maps are made, each node holding the
//! four lights' as a vec4, and a floor pixel interpolates it bilinearly between four nodes
//! (`floor_visibilities` in `shaders/common/view_floor_shadow.wgsl` mirrors
//! [`FloorShadows::visibilities`]): four loads for every light, where each light's soft
//! shadow took 29, on a floor that is most of the frame.
//!
//! The grid: with c the object's centre on the floor, x and z from c warped each by
//! σ(d) = sign(d) ln(1 + |d|/L) (L = [`FLOOR_SHADOW_WARP`]), uniform in σ over the whole
//! floor, so that the nodes are closest by the object, where contact shadows are sharp,
//! and grow apart with distance, as a penumbra does.

use glam::{Vec3, Vec4};
use rayon::prelude::*;

use crate::view::frame::MAX_SHADOW_MAPS;
use crate::view::scene::{FLOOR_HALF_EXTENT, FLOOR_Y, OBJECT_CENTRE};
use crate::view::shadow::{layer_visibility, ShadowMaps};

/// Nodes along each side of the grid.
pub const FLOOR_SHADOW_NODES: usize = 1024;
/// L of the warp, world units: the nodes are (L + |d|) 2 σ_max/(nodes − 1) apart at d from
/// the object's centre: 2.6 mm there, 6.9 mm half a unit from it, 22 cm at the floor's
/// edge.
pub const FLOOR_SHADOW_WARP: f32 = 0.3;
/// Entries before the grid: (nodes, L, σ_max, 0), (c.x, c.z, 0, 0)
/// (`FLOOR_SHADOW_HEADER` in view_floor_shadow.wgsl).
pub const FLOOR_SHADOW_HEADER: usize = 2;

/// The grid as both renderers read it: [`FLOOR_SHADOW_HEADER`] entries, then node (i
/// along x, j along z) at `FLOOR_SHADOW_HEADER + j nodes + i`, each light's visibility
/// by light (1 for a light without a map).
#[derive(Clone, Debug, PartialEq)]
pub struct FloorShadows {
    /// The entries.
    pub entries: Vec<[f32; 4]>,
}

/// The warp.
fn warp(d: f32) -> f32 {
    d.signum() * (d.abs() / FLOOR_SHADOW_WARP).ln_1p()
}

fn unwarp(sigma: f32) -> f32 {
    sigma.signum() * FLOOR_SHADOW_WARP * sigma.abs().exp_m1()
}

/// The object's centre on the floor.
fn centre() -> Vec3 {
    Vec3::new(OBJECT_CENTRE[0], FLOOR_Y, OBJECT_CENTRE[2])
}

/// σ at the floor's edge (the floor is centred under the object).
fn sigma_max() -> f32 {
    warp(FLOOR_HALF_EXTENT)
}

/// The floor point of node (i, j) of a grid of `n` nodes a side.
fn node(i: usize, j: usize, n: usize) -> Vec3 {
    let at = |k: usize| unwarp(sigma_max() * (2.0 * k as f32 / (n - 1) as f32 - 1.0));
    centre() + Vec3::new(at(i), 0.0, at(j))
}

impl FloorShadows {
    /// The grid of every light with a map in `maps`: [`FLOOR_SHADOW_NODES`] a side, or 2
    /// where no light has a map (every node 1: the floor is lit everywhere).
    pub fn new(maps: &ShadowMaps) -> FloorShadows {
        let n = if maps.is_empty() {
            2
        } else {
            FLOOR_SHADOW_NODES
        };
        let c = centre();
        let mut entries = vec![
            [n as f32, FLOOR_SHADOW_WARP, sigma_max(), 0.0],
            [c.x, c.z, 0.0, 0.0],
        ];
        entries.par_extend((0..n * n).into_par_iter().map(|k| {
            let p = node(k % n, k / n, n);
            std::array::from_fn(|light| {
                if light < maps.len() {
                    layer_visibility(&maps.blocks, maps.size, &maps.depth, light, p, Vec3::Y)
                } else {
                    1.0
                }
            })
        }));
        FloorShadows { entries }
    }

    /// Each light's visibility at floor point `p`, bilinear between the grid's nodes
    /// (`floor_visibilities` in view_floor_shadow.wgsl).
    pub fn visibilities(&self, p: Vec3) -> [f32; MAX_SHADOW_MAPS] {
        let [n, l, sigma_max, _] = self.entries[0];
        let [cx, cz, _, _] = self.entries[1];
        let coordinate = |d: f32| {
            let sigma = d.signum() * (d.abs() / l).ln_1p();
            ((sigma + sigma_max) / (2.0 * sigma_max) * (n - 1.0)).clamp(0.0, n - 1.0)
        };
        let (x, y) = (coordinate(p.x - cx), coordinate(p.z - cz));
        let (i, j) = (x.floor().min(n - 2.0), y.floor().min(n - 2.0));
        let (fx, fy) = (x - i, y - j);
        let w = n as usize;
        let at = |i: usize, j: usize| Vec4::from(self.entries[FLOOR_SHADOW_HEADER + j * w + i]);
        let (i, j) = (i as usize, j as usize);
        let a = at(i, j) + (at(i + 1, j) - at(i, j)) * fx;
        let b = at(i, j + 1) + (at(i + 1, j + 1) - at(i, j + 1)) * fx;
        (a + (b - a) * fy).to_array()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::view::model::Model;

    /// Spot under a lamp 41° up (3.5° in radius) and one 0.5° above the horizon (6°): the
    /// grid holds each light's visibility exactly at its nodes and reads it between them
    /// within 0.012 on average over the floor the shadows fall on (the bilinear error at
    /// the penumbrae's edges, largest where the nodes spread apart along the horizon
    /// lamp's long shadow; measured 0.0064 and 0.0085).
    #[test]
    fn the_grid_holds_the_maps_visibility() {
        let spot = &Model::bundled().unwrap()[0];
        let toward = |az: f32, el: f32| {
            let (az, el) = (az.to_radians(), el.to_radians());
            Vec3::new(el.cos() * az.cos(), el.sin(), el.cos() * az.sin())
        };
        let lights = [
            (toward(-99.0, 41.0), 3.5f32.to_radians().tan()),
            (toward(62.0, 0.5), 6f32.to_radians().tan()),
        ];
        let maps = ShadowMaps::new(&lights, spot);
        let grid = FloorShadows::new(&maps);
        let exact = |k: usize, p: Vec3| {
            layer_visibility(&maps.blocks, maps.size, &maps.depth, k, p, Vec3::Y)
        };
        for (i, j) in [(0, 0), (300, 400), (511, 700), (FLOOR_SHADOW_NODES - 1, 5)] {
            let p = node(i, j, FLOOR_SHADOW_NODES);
            let got = grid.visibilities(p);
            for (k, v) in got.iter().enumerate().take(2) {
                assert!((v - exact(k, p)).abs() < 1e-4, "light {k} node {i} {j}");
            }
            assert_eq!(got[2..], [1.0, 1.0]);
        }
        // The floor 12 m by 12 m about the object.
        for k in 0..2 {
            let (mut sum, mut shadowed) = (0.0f64, 0usize);
            let n = 300;
            for a in 0..n {
                for b in 0..n {
                    let x = -6.0 + 12.0 * (a as f32 + 0.37) / n as f32;
                    let z = -6.0 + 12.0 * (b as f32 + 0.61) / n as f32;
                    let p = centre() + Vec3::new(x, 0.0, z);
                    let want = exact(k, p);
                    if want < 1.0 {
                        shadowed += 1;
                        sum += (grid.visibilities(p)[k] - want).abs() as f64;
                    }
                }
            }
            let mean = sum / shadowed as f64;
            println!("light {k}: {shadowed} points in its shadow, mean |grid − map| {mean:.4}");
            assert!(
                shadowed > 300 && mean <= 0.01,
                "light {k}: {shadowed} {mean}"
            );
        }
    }
}
