//! The lights' shadows in the viewer: per light taken out of the environment (the sun, a
//! studio's lamps, at most [`MAX_SHADOW_MAPS`]), a map of how far along the light's rays
//! the object first stands, made on the CPU by the viewer's own rasteriser ([`rasterize`],
//! the sphere ray-cast exactly) through an orthographic camera looking down the rays, and
//! looked up by both renderers' shading (`light_visibility` in
//! `shaders/common/view_sun.wgsl`, [`visibility`] here), so the GPU and CPU frames read
//! the same texels. [`ShadowMaps`] holds them as the kernels read them: one layer of an
//! array texture and one block of the frame's uniform (`FrameUniform::shadow`) a light.
//!
//! Visibility of a surface point p with normal n: q = p + n·[`NORMAL_OFFSET_TEXELS`]
//! texels (off the surface, so a surface does not shadow itself where the map's texels
//! are coarser than its curvature), projected into the map; a texel lights q when the
//! object there stands further along the rays than q, less [`DEPTH_BIAS_TEXELS`]; the
//! visibility is the lit (1) or shadowed (0) state of the 2 × 2 texels around q,
//! interpolated bilinearly at q (percentage-closer filtering, Reeves et al. 1987, with
//! the bilinear weights of its common 2 × 2 form), which softens the edge over one
//! texel, 3 mm on the object's 1.4 m box: four texel loads a fragment, where a 3 × 3 box
//! of nine cost the viewer's frame with the sun about a tenth more on lavapipe. Outside
//! the map nothing casts a shadow (only the object does).
//!
//! An area light (a studio's lamp, degrees wide) casts a penumbra as wide as its angular
//! size times the distance from the blocker to the receiver: percentage-closer soft
//! shadows (Fernando 2005). With s = tan ρ (ρ the light's angular radius, the map's
//! `spread`), a [`BLOCKER_TAPS`]² grid of texels across ±s z (z the receiver's depth from
//! the map's plane, so every blocker between the plane and q is in reach) gives the mean
//! depth z_b of those nearer than q; none lights q fully. The penumbra's half-width is
//! s (z − z_b), at least one texel, and the visibility the fraction of a
//! [`FILTER_TAPS`]² grid of texels across it that light q: 25 texel loads a fragment.

use glam::Vec3;

use crate::view::camera::{CameraFrame, NEAR};
use crate::view::frame::{unpack_material, FrameUniform, Surface, MAX_SHADOW_MAPS};
use crate::view::model::{Model, Shape};
use crate::view::raster::{object_vertices, rasterize};
use crate::view::scene::{FIT_HALF_EXTENT, OBJECT_CENTRE};

/// Texels along each edge of the map.
pub const SHADOW_MAP_SIZE: u32 = 1024;
/// How far a receiver is moved along its normal before the lookup, in texels.
pub const NORMAL_OFFSET_TEXELS: f32 = 1.5;
/// How much nearer than the map's depth a receiver must be to be shadowed, in texels.
pub const DEPTH_BIAS_TEXELS: f32 = 1.0;
/// Depth of a texel where no object stands.
pub const EMPTY_DEPTH: f32 = f32::MAX;
/// Texels per side of the soft shadow's blocker search (`BLOCKER_TAPS` in view_sun.wgsl).
pub const BLOCKER_TAPS: u32 = 3;
/// Texels per side of the soft shadow's filter (`FILTER_TAPS` in view_sun.wgsl).
pub const FILTER_TAPS: u32 = 4;

/// The half extent of the map: the radius of the sphere around the object's fitting box
/// (every model fits a cube of half extent `FIT_HALF_EXTENT` about `OBJECT_CENTRE`), 1 %
/// over.
fn half_extent() -> f32 {
    1.01 * FIT_HALF_EXTENT * 3f32.sqrt()
}

/// One light's shadow map.
#[derive(Clone, Debug, PartialEq)]
pub struct ShadowMap {
    /// The orthographic camera looking down the sun's rays, `front` = −toward the sun.
    pub camera: CameraFrame,
    /// Texels along an edge.
    pub size: u32,
    /// Row-major: the distance along `front` from the camera's plane to the object, or
    /// [`EMPTY_DEPTH`].
    pub depth: Vec<f32>,
    /// tan ρ of an area light of angular radius ρ, whose penumbra the lookup draws; 0 for
    /// a directional light (the sun: the 2 × 2 lookup).
    pub spread: f32,
}

impl ShadowMap {
    /// The map of `model` lit from unit direction `toward_sun` by a light whose penumbra
    /// spreads by `spread` (tan of an area light's angular radius, 0 for the sun).
    pub fn new(toward_sun: Vec3, model: &Model, spread: f32) -> ShadowMap {
        let front = -toward_sun.normalize();
        let right = front.any_orthonormal_vector();
        let up = right.cross(front);
        let half = half_extent();
        let centre = Vec3::from(OBJECT_CENTRE);
        let camera = CameraFrame {
            position: centre - front * (half + 2.0 * NEAR),
            right,
            up,
            front,
            half_x: half,
            half_y: half,
            orthographic: true,
        };
        let size = SHADOW_MAP_SIZE;
        let blank = unpack_material(&[[0.0; 4]; 3]);
        let frame = FrameUniform::new(&camera, (size, size), &blank, &blank, 0, 0);
        let g = rasterize(
            &frame,
            &object_vertices(model),
            matches!(model.shape, Shape::Sphere),
        );
        let depth = g
            .position
            .iter()
            .map(|p| match Surface::from_id(p[3]) {
                Surface::Background => EMPTY_DEPTH,
                _ => (Vec3::from_slice(&p[..3]) - camera.position).dot(front),
            })
            .collect();
        ShadowMap {
            camera,
            size,
            depth,
            spread,
        }
    }

    /// One texel's edge in world units.
    pub fn texel(&self) -> f32 {
        2.0 * self.camera.half_x / self.size as f32
    }

    /// The block the kernels read (`FrameParams`' shadow fields): (origin, half extent),
    /// (right, depth bias), (up, normal offset), (front, spread), all in world units.
    pub fn uniform(&self) -> [[f32; 4]; 4] {
        let c = &self.camera;
        [
            c.position.extend(c.half_x).into(),
            c.right.extend(DEPTH_BIAS_TEXELS * self.texel()).into(),
            c.up.extend(NORMAL_OFFSET_TEXELS * self.texel()).into(),
            c.front.extend(self.spread).into(),
        ]
    }

    /// The light's visibility at surface point `p` with unit normal `n`, in [0, 1]: mirror
    /// of `light_visibility` in `shaders/common/view_sun.wgsl` on [`ShadowMap::uniform`].
    #[cfg(any(test, feature = "internals"))]
    pub fn visibility(&self, p: Vec3, n: Vec3) -> f32 {
        visibility(&self.uniform(), self.size, &self.depth, p, n)
    }
}

/// The shadow maps of the lights split out, light by light, as the kernels read them.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct ShadowMaps {
    /// Texels along each map's edge ([`SHADOW_MAP_SIZE`]; 0 without a map).
    pub size: u32,
    /// Each map's [`ShadowMap::uniform`], by light.
    pub blocks: Vec<[[f32; 4]; 4]>,
    /// The maps' texels, layer after layer (each `size`² row-major).
    pub depth: Vec<f32>,
}

impl ShadowMaps {
    /// The maps of `model` lit by each of `lights` (unit direction toward the light, tan of
    /// its angular radius for an area light's penumbra, 0 for a directional light), the
    /// first [`MAX_SHADOW_MAPS`] of them.
    pub fn new(lights: &[(Vec3, f32)], model: &Model) -> ShadowMaps {
        let maps: Vec<ShadowMap> = lights
            .iter()
            .take(MAX_SHADOW_MAPS)
            .map(|&(toward, spread)| ShadowMap::new(toward, model, spread))
            .collect();
        ShadowMaps {
            size: maps.first().map_or(0, |m| m.size),
            blocks: maps.iter().map(ShadowMap::uniform).collect(),
            depth: maps.into_iter().flat_map(|m| m.depth).collect(),
        }
    }

    /// How many lights have a map.
    pub fn len(&self) -> usize {
        self.blocks.len()
    }

    /// Whether no light has one.
    pub fn is_empty(&self) -> bool {
        self.blocks.is_empty()
    }
}

/// Light `k`'s visibility at `p` with unit normal `n`, in [0, 1], from a frame's shadow
/// blocks, the maps' edge `size` and their texels `layers` (as [`ShadowMaps`] holds them).
pub fn layer_visibility(
    blocks: &[[[f32; 4]; 4]],
    size: u32,
    layers: &[f32],
    k: usize,
    p: Vec3,
    n: Vec3,
) -> f32 {
    let texels = (size * size) as usize;
    visibility(
        &blocks[k],
        size,
        &layers[k * texels..(k + 1) * texels],
        p,
        n,
    )
}

/// `light_visibility` of view_sun.wgsl on a map's `uniform` block, edge `size` and texels
/// `depth`.
pub fn visibility(uniform: &[[f32; 4]; 4], size: u32, depth: &[f32], p: Vec3, n: Vec3) -> f32 {
    let [origin, right, up, front] = uniform.map(|r| Vec3::from_slice(&r[..3]));
    let (half, bias, offset) = (uniform[0][3], uniform[1][3], uniform[2][3]);
    let d = p + n * offset - origin;
    let x = d.dot(right) / half;
    let y = d.dot(up) / half;
    if x.abs() >= 1.0 || y.abs() >= 1.0 {
        return 1.0;
    }
    let z = d.dot(front) - bias;
    let last = size as i32 - 1;
    // Texel-centre coordinates (texel i's centre at i).
    let u = (x + 1.0) * 0.5 * size as f32 - 0.5;
    let w = (1.0 - y) * 0.5 * size as f32 - 0.5;
    let at = |i: i32, j: i32| depth[(j.clamp(0, last) * (last + 1) + i.clamp(0, last)) as usize];
    let spread = uniform[3][3];
    if spread > 0.0 {
        return soft_visibility(&at, (u, w), z, spread / (2.0 * half / size as f32));
    }
    let lit = |i: i32, j: i32| if at(i, j) >= z { 1.0 } else { 0.0 };
    // The four around, interpolated bilinearly.
    let (u0, w0) = (u.floor(), w.floor());
    let (fx, fy) = (u - u0, w - w0);
    let (i, j) = (u0 as i32, w0 as i32);
    (lit(i, j) * (1.0 - fx) + lit(i + 1, j) * fx) * (1.0 - fy)
        + (lit(i, j + 1) * (1.0 - fx) + lit(i + 1, j + 1) * fx) * fy
}

/// The texel nearest texel-centre coordinate `c`.
fn nearest(c: f32) -> i32 {
    (c + 0.5).floor() as i32
}

/// An area light's visibility at texel-centre coordinates `(u, w)` of a receiver at depth
/// `z` (less the bias), `spread` the penumbra's growth in texels per unit of depth
/// (`soft_visibility` in view_sun.wgsl; the module's doc says how).
fn soft_visibility(at: &impl Fn(i32, i32) -> f32, (u, w): (f32, f32), z: f32, spread: f32) -> f32 {
    let grid = |taps: u32, radius: f32, k: u32| {
        let step = 2.0 * radius / taps as f32;
        let (a, b) = ((k % taps) as f32, (k / taps) as f32);
        (
            nearest(u - radius + (a + 0.5) * step),
            nearest(w - radius + (b + 0.5) * step),
        )
    };
    let search = spread * z;
    let (mut sum, mut count) = (0.0f32, 0.0f32);
    for k in 0..BLOCKER_TAPS * BLOCKER_TAPS {
        let (i, j) = grid(BLOCKER_TAPS, search, k);
        let d = at(i, j);
        if d < z {
            sum += d;
            count += 1.0;
        }
    }
    if count == 0.0 {
        return 1.0;
    }
    let radius = (spread * (z - sum / count)).max(1.0);
    let taps = FILTER_TAPS * FILTER_TAPS;
    let lit = (0..taps)
        .filter(|&k| {
            let (i, j) = grid(FILTER_TAPS, radius, k);
            at(i, j) >= z
        })
        .count();
    lit as f32 / taps as f32
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A sun straight above the sphere: the floor under the sphere's centre is in full
    /// shadow, a point beside the sphere's shadow in full light, and the sphere's top (lit,
    /// facing the sun) is not shadowed by itself.
    #[test]
    fn sphere_shadows_the_floor_below_it_and_not_itself() {
        let model = Model {
            name: "sphere".into(),
            shape: Shape::Sphere,
        };
        let map = ShadowMap::new(Vec3::Y, &model, 0.0);
        let c = Vec3::from(OBJECT_CENTRE);
        let floor = Vec3::new(c.x, crate::view::scene::FLOOR_Y, c.z);
        assert_eq!(map.visibility(floor, Vec3::Y), 0.0);
        let beside = floor + Vec3::X * (FIT_HALF_EXTENT * 1.2);
        assert_eq!(map.visibility(beside, Vec3::Y), 1.0);
        let top = c + Vec3::Y * FIT_HALF_EXTENT;
        assert_eq!(map.visibility(top, Vec3::Y), 1.0);
        // The side facing away from the sun is behind the sphere's own near half.
        let bottom = c - Vec3::Y * FIT_HALF_EXTENT;
        assert_eq!(map.visibility(bottom, -Vec3::Y), 0.0);
    }

    /// An area light's penumbra: along the floor across the edge of the sphere's shadow
    /// (the light straight above), the visibility rises from 0.1 to 0.9 over about the
    /// penumbra 2 s h (s = tan ρ, h the height of the sphere's equator above the floor):
    /// measured 1.03 / 1.13 / 1.27 × it for lights of 3° / 6° / 12° (the blocker search
    /// averages in the sphere's upper part, nearer the light than its equator, more so the
    /// wider it reaches); bars 0.6 to 1.4 ×. A directional light's edge is at most two
    /// texels wide.
    #[test]
    fn an_area_lights_penumbra_is_as_wide_as_the_light() {
        let model = Model {
            name: "sphere".into(),
            shape: Shape::Sphere,
        };
        let c = Vec3::from(OBJECT_CENTRE);
        let h = c.y - crate::view::scene::FLOOR_Y;
        let edge_width = |map: &ShadowMap| {
            // From under the centre outward along +x, in steps of a tenth of a texel.
            let step = 0.1 * map.texel();
            let (mut start, mut end) = (None, None);
            for k in 0..40_000 {
                let x = k as f32 * step;
                let v = map.visibility(
                    Vec3::new(c.x + x, crate::view::scene::FLOOR_Y, c.z),
                    Vec3::Y,
                );
                if start.is_none() && v >= 0.1 {
                    start = Some(x);
                }
                if v >= 0.9 {
                    end = Some(x);
                    break;
                }
            }
            end.unwrap() - start.unwrap()
        };
        let hard = ShadowMap::new(Vec3::Y, &model, 0.0);
        assert!(
            edge_width(&hard) <= 2.0 * hard.texel(),
            "{}",
            edge_width(&hard)
        );
        for degrees in [3.0f32, 6.0, 12.0] {
            let s = degrees.to_radians().tan();
            let map = ShadowMap::new(Vec3::Y, &model, s);
            let (got, want) = (edge_width(&map), 2.0 * s * h);
            assert!(
                got >= 0.6 * want && got <= 1.4 * want,
                "{degrees}°: {got} vs {want}"
            );
        }
    }
}
