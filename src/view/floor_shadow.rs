//! The lights' shadows on the floor, looked up from a grid laid on the floor per light.
//! A floor point's visibility of a light depends on where it is, not on where the eye is,
//! and neither the object nor the lights move while the camera does; so each light's
//! visibility ([`layer_visibility`], its map's lookup and soft shadow) is computed
//! once, at the nodes of a grid on the floor, when the maps are made, and a floor pixel
//! interpolates it bilinearly between four nodes (`floor_visibility` in
//! `shaders/common/view_floor_shadow.wgsl` mirrors [`FloorShadows::visibility`]): four
//! loads a light where the soft shadow took 29, on a floor that is most of the frame.
//!
//! Light k's grid lies along its shadow: with c the object's centre on the floor, a the
//! unit horizontal direction away from the light and b = (−a.z, a.x), a point is at
//! s = (p − c)·a along and t = (p − c)·b across. Only where the map covers the floor can
//! the object shadow it; that region is the map's square cast along the rays onto the
//! floor (to the floor's far corner for a light near the horizon), and the grid spans it:
//! t over ±T, and s through σ(s) = sign(s) ln(1 + |s|/L) (L = [`FLOOR_SHADOW_WARP`]),
//! uniform in σ, so that the nodes are closest near the object, where contact shadows are
//! sharp, and grow apart with distance, as the penumbra does. Outside the grid the visibility is 1,
//! as outside the map.

use glam::Vec3;
use rayon::prelude::*;

use crate::view::frame::MAX_SHADOW_MAPS;
use crate::view::scene::{FLOOR_HALF_EXTENT, FLOOR_Y, OBJECT_CENTRE};
use crate::view::shadow::{layer_visibility, ShadowMaps};

/// Nodes of a light's grid along its shadow (σ).
pub const FLOOR_SHADOW_ALONG: usize = 1024;
/// Nodes of a light's grid across its shadow (t).
pub const FLOOR_SHADOW_ACROSS: usize = 768;
/// L of the warp along the shadow, world units: near the object a node every
/// L (σ₁ − σ₀)/(nodes − 1) (2.8 mm for a lamp at the horizon, whose grid runs to the
/// floor's corner).
pub const FLOOR_SHADOW_WARP: f32 = 0.5;
/// Entries before the grids: (nodes along, nodes across, lights, 0), then
/// [`FLOOR_SHADOW_PARAMS`] a light (`FLOOR_SHADOW_HEADER` in view_floor_shadow.wgsl).
pub const FLOOR_SHADOW_HEADER: usize = 4 + FLOOR_SHADOW_PARAMS * MAX_SHADOW_MAPS;
/// A light's parameters: (a.x, a.z, σ₀, σ₁), (T, L, c.x, c.z) (`FLOOR_SHADOW_PARAMS` in
/// view_floor_shadow.wgsl).
pub const FLOOR_SHADOW_PARAMS: usize = 8;

/// The lights' grids as both renderers read them: a header of [`FLOOR_SHADOW_HEADER`]
/// floats, then light k's node (i along, j across) at
/// `FLOOR_SHADOW_HEADER + (k across + j) along + i`.
#[derive(Clone, Debug, PartialEq)]
pub struct FloorShadows {
    /// The entries.
    pub entries: Vec<f32>,
}

/// The warp along the shadow.
fn warp(s: f32) -> f32 {
    s.signum() * (s.abs() / FLOOR_SHADOW_WARP).ln_1p()
}

fn unwarp(sigma: f32) -> f32 {
    sigma.signum() * FLOOR_SHADOW_WARP * sigma.abs().exp_m1()
}

/// A light's grid: its axes and extent on the floor.
struct Grid {
    a: Vec3,
    b: Vec3,
    sigma: (f32, f32),
    half_across: f32,
    centre: Vec3,
}

impl Grid {
    /// The grid of a map's `block` (`ShadowMap::uniform`): over the floor its square
    /// covers, cast along the rays.
    fn of(block: &[[f32; 4]; 4]) -> Grid {
        let [origin, right, up, front] = block.map(|r| Vec3::from_slice(&r[..3]));
        let half = block[0][3];
        let centre = Vec3::new(OBJECT_CENTRE[0], FLOOR_Y, OBJECT_CENTRE[2]);
        let horizontal = Vec3::new(front.x, 0.0, front.z);
        let a = horizontal.try_normalize().unwrap_or(Vec3::X);
        let b = Vec3::new(-a.z, 0.0, a.x);
        // The floor's corner furthest from c: nothing beyond it is drawn.
        let far = FLOOR_HALF_EXTENT * 2f32.sqrt();
        let (mut lo, mut hi, mut across) = (f32::MAX, f32::MIN, 0.0f32);
        for (x, y) in [(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)] {
            let q = origin + (right * x + up * y) * half;
            // Along the rays to the floor, or as far as the floor goes where they do not
            // come down within it.
            let s = if front.y < 0.0 {
                let hit = q + front * ((FLOOR_Y - q.y) / front.y);
                (hit - centre).dot(a).min(far)
            } else {
                far
            };
            lo = lo.min(s);
            hi = hi.max(s);
            across = across.max((q - centre).dot(b).abs());
        }
        Grid {
            a,
            b,
            sigma: (warp(lo.max(-far)), warp(hi)),
            half_across: across,
            centre,
        }
    }

    /// The floor point of node (i, j).
    fn node(&self, i: usize, j: usize) -> Vec3 {
        let f = i as f32 / (FLOOR_SHADOW_ALONG - 1) as f32;
        let s = unwarp(self.sigma.0 + (self.sigma.1 - self.sigma.0) * f);
        let t = -self.half_across
            + 2.0 * self.half_across * j as f32 / (FLOOR_SHADOW_ACROSS - 1) as f32;
        self.centre + self.a * s + self.b * t
    }
}

impl FloorShadows {
    /// The grids of every light with a map in `maps`.
    pub fn new(maps: &ShadowMaps) -> FloorShadows {
        let (along, across) = (FLOOR_SHADOW_ALONG, FLOOR_SHADOW_ACROSS);
        let mut entries = vec![0.0; FLOOR_SHADOW_HEADER];
        entries[..3].copy_from_slice(&[along as f32, across as f32, maps.len() as f32]);
        for (k, block) in maps.blocks.iter().enumerate() {
            let g = Grid::of(block);
            entries[4 + FLOOR_SHADOW_PARAMS * k..4 + FLOOR_SHADOW_PARAMS * (k + 1)]
                .copy_from_slice(&[
                    g.a.x,
                    g.a.z,
                    g.sigma.0,
                    g.sigma.1,
                    g.half_across,
                    FLOOR_SHADOW_WARP,
                    g.centre.x,
                    g.centre.z,
                ]);
            let nodes: Vec<f32> = (0..along * across)
                .into_par_iter()
                .map(|n| {
                    let p = g.node(n % along, n / along);
                    layer_visibility(&maps.blocks, maps.size, &maps.depth, k, p, Vec3::Y)
                })
                .collect();
            entries.extend(nodes);
        }
        FloorShadows { entries }
    }

    /// Light k's visibility at floor point `p`, bilinear between its grid's nodes, 1
    /// outside the grid (`floor_visibility` in view_floor_shadow.wgsl).
    pub fn visibility(&self, k: usize, p: Vec3) -> f32 {
        let e = &self.entries;
        let (along, across) = (e[0], e[1]);
        let q = &e[4 + FLOOR_SHADOW_PARAMS * k..4 + FLOOR_SHADOW_PARAMS * (k + 1)];
        let (dx, dz) = (p.x - q[6], p.z - q[7]);
        let s = dx * q[0] + dz * q[1];
        let t = -dx * q[1] + dz * q[0];
        let sigma = s.signum() * (s.abs() / q[5]).ln_1p();
        let x = (sigma - q[2]) / (q[3] - q[2]) * (along - 1.0);
        let y = (t + q[4]) / (2.0 * q[4]) * (across - 1.0);
        if !(x >= 0.0 && x <= along - 1.0 && y >= 0.0 && y <= across - 1.0) {
            return 1.0;
        }
        let (i, j) = (x.floor().min(along - 2.0), y.floor().min(across - 2.0));
        let (fx, fy) = (x - i, y - j);
        let (w, base) = (
            along as usize,
            FLOOR_SHADOW_HEADER + k * (along * across) as usize,
        );
        let at = |i: usize, j: usize| e[base + j * w + i];
        let (i, j) = (i as usize, j as usize);
        let a = at(i, j) + (at(i + 1, j) - at(i, j)) * fx;
        let b = at(i, j + 1) + (at(i + 1, j + 1) - at(i, j + 1)) * fx;
        a + (b - a) * fy
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::view::model::Model;

    /// Spot under a lamp 41° up (3.5° in radius) and one 0.5° above the horizon (6°): the
    /// grids hold each light's visibility exactly at their nodes, read it between them
    /// within 0.01 on average over the floor the shadows fall on (the bilinear error at
    /// the penumbrae's edges; measured 0.0044 and 0.0018), and nothing the map shadows
    /// lies outside them.
    #[test]
    fn the_grids_hold_the_maps_visibility() {
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
        let grids = FloorShadows::new(&maps);
        let exact = |k: usize, p: Vec3| {
            layer_visibility(&maps.blocks, maps.size, &maps.depth, k, p, Vec3::Y)
        };
        for (k, block) in maps.blocks.iter().enumerate() {
            let g = Grid::of(block);
            for (i, j) in [(0, 0), (300, 400), (511, 383), (FLOOR_SHADOW_ALONG - 1, 5)] {
                let p = g.node(i, j);
                assert!(
                    (grids.visibility(k, p) - exact(k, p)).abs() < 1e-4,
                    "light {k} node {i} {j}"
                );
            }
            // The floor along the shadow, 12 m by 6 m from under the object.
            let (mut sum, mut shadowed, mut outside) = (0.0f64, 0usize, 0usize);
            let n = 200;
            for a in 0..n {
                for b in 0..n {
                    let s = -2.0 + 12.0 * (a as f32 + 0.37) / n as f32;
                    let t = -3.0 + 6.0 * (b as f32 + 0.61) / n as f32;
                    let p = g.centre + g.a * s + g.b * t;
                    let (want, got) = (exact(k, p), grids.visibility(k, p));
                    if want < 1.0 {
                        shadowed += 1;
                        sum += (got - want).abs() as f64;
                        let x = (warp(s) - g.sigma.0) / (g.sigma.1 - g.sigma.0);
                        outside +=
                            usize::from(!(0.0..=1.0).contains(&x) || t.abs() > g.half_across);
                    }
                }
            }
            let mean = sum / shadowed as f64;
            println!("light {k}: {shadowed} points in its shadow, mean |grid − map| {mean:.4}");
            assert!(
                shadowed > 500 && mean <= 0.01,
                "light {k}: {shadowed} {mean}"
            );
            assert_eq!(outside, 0, "light {k}");
        }
    }
}
