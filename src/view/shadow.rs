//! The sun's shadow in the viewer: a map of how far along the sun's rays the object
//! first stands, made on the CPU by the viewer's own rasteriser ([`rasterize`], the
//! sphere ray-cast exactly) through an orthographic camera looking down the sun's rays,
//! and looked up by both renderers' shading (`sun_visibility` in
//! `shaders/common/view_sun.wgsl`, [`ShadowMap::visibility`] here), so the GPU and CPU
//! frames read the same texels.
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

use glam::Vec3;

use crate::view::camera::{CameraFrame, NEAR};
use crate::view::frame::{unpack_material, FrameUniform, Surface};
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

/// The half extent of the map: the radius of the sphere around the object's fitting box
/// (every model fits a cube of half extent `FIT_HALF_EXTENT` about `OBJECT_CENTRE`), 1 %
/// over.
fn half_extent() -> f32 {
    1.01 * FIT_HALF_EXTENT * 3f32.sqrt()
}

/// The sun's shadow map.
#[derive(Clone, Debug, PartialEq)]
pub struct ShadowMap {
    /// The orthographic camera looking down the sun's rays, `front` = −toward the sun.
    pub camera: CameraFrame,
    /// Texels along an edge.
    pub size: u32,
    /// Row-major: the distance along `front` from the camera's plane to the object, or
    /// [`EMPTY_DEPTH`].
    pub depth: Vec<f32>,
}

impl ShadowMap {
    /// The map of `model` lit from unit direction `toward_sun`.
    pub fn new(toward_sun: Vec3, model: &Model) -> ShadowMap {
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
        }
    }

    /// One texel's edge in world units.
    pub fn texel(&self) -> f32 {
        2.0 * self.camera.half_x / self.size as f32
    }

    /// The block the kernels read (`FrameParams`' shadow fields): (origin, half extent),
    /// (right, depth bias), (up, normal offset), (front, 0), all in world units.
    pub fn uniform(&self) -> [[f32; 4]; 4] {
        let c = &self.camera;
        [
            c.position.extend(c.half_x).into(),
            c.right.extend(DEPTH_BIAS_TEXELS * self.texel()).into(),
            c.up.extend(NORMAL_OFFSET_TEXELS * self.texel()).into(),
            c.front.extend(0.0).into(),
        ]
    }

    /// The sun's visibility at surface point `p` with unit normal `n`, in [0, 1]: mirror
    /// of `sun_visibility` in `shaders/common/view_sun.wgsl` on [`ShadowMap::uniform`].
    pub fn visibility(&self, p: Vec3, n: Vec3) -> f32 {
        visibility(&self.uniform(), self.size, &self.depth, p, n)
    }
}

/// `sun_visibility` of view_sun.wgsl on a map's `uniform` block, edge `size` and texels
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
    // Texel-centre coordinates (texel i's centre at i), the four around, clamped.
    let u = (x + 1.0) * 0.5 * size as f32 - 0.5;
    let w = (1.0 - y) * 0.5 * size as f32 - 0.5;
    let (u0, w0) = (u.floor(), w.floor());
    let (fx, fy) = (u - u0, w - w0);
    let lit = |i: i32, j: i32| {
        let (tx, ty) = (i.clamp(0, last), j.clamp(0, last));
        if depth[(ty * (last + 1) + tx) as usize] >= z {
            1.0
        } else {
            0.0
        }
    };
    let (i, j) = (u0 as i32, w0 as i32);
    (lit(i, j) * (1.0 - fx) + lit(i + 1, j) * fx) * (1.0 - fy)
        + (lit(i, j + 1) * (1.0 - fx) + lit(i + 1, j + 1) * fx) * fy
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
        let map = ShadowMap::new(Vec3::Y, &model);
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
}
