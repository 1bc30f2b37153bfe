//! The viewer's G-buffer: the vertices both renderers draw, and the CPU twin of the GPU's
//! raster passes (`shaders/view_gbuffer.wgsl` and `view_forward.wgsl`, whose vertex stage
//! and sphere ray-cast are `common/view_raster.wgsl`).
//!
//! The CPU rasteriser follows the rules a GPU's does (Vulkan specification, "Rasterization",
//! polygon rasterization): triangles are clipped to the near plane in clip space
//! (0 ≤ z ≤ w, wgpu's depth range), a pixel is covered when its centre is inside the
//! triangle's edges (ties broken by the top-left rule), depth z/w is interpolated linearly
//! in screen space and tested with "less", and the other attributes perspective-correctly
//! (barycentrics weighted by 1/w). The sphere is ray-cast at every pixel centre, exactly
//! as the fragment stage does over its bounding box.

use glam::{Vec3, Vec4};
use rayon::prelude::*;

use crate::view::frame::{FrameUniform, Surface};
use crate::view::model::{Model, Shape};
use crate::view::scene::{FIT_HALF_EXTENT, FLOOR_HALF_EXTENT, FLOOR_Y, OBJECT_CENTRE};

/// One corner as the raster pass reads it: (position, surface id), (normal, 0).
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, bytemuck::Pod, bytemuck::Zeroable)]
pub struct Vertex {
    /// World position, w: the surface id ([`Surface`]).
    pub position: [f32; 4],
    /// Unit normal, w unused.
    pub normal: [f32; 4],
}

fn vertex(p: Vec3, n: Vec3, surface: Surface) -> Vertex {
    Vertex {
        position: p.extend(surface as u32 as f32).into(),
        normal: n.extend(0.0).into(),
    }
}

/// The floor's vertices, the last of [`scene_vertices`]: two triangles.
pub const FLOOR_VERTICES: u32 = 6;

/// The triangles of a frame: the model's mesh (none for the sphere), then the floor. The
/// GPU draws them in this order, so the floor's fragments behind the model fail the depth
/// test before they are shaded (nearer first; the picture does not depend on the order).
pub fn scene_vertices(model: &Model) -> Vec<Vertex> {
    let (y, h, cz) = (FLOOR_Y, FLOOR_HALF_EXTENT, OBJECT_CENTRE[2]);
    let corners = [
        Vec3::new(-h, y, cz - h),
        Vec3::new(h, y, cz - h),
        Vec3::new(h, y, cz + h),
        Vec3::new(-h, y, cz + h),
    ];
    // The floor's two triangles, as corner indices.
    let floor: [usize; FLOOR_VERTICES as usize] = [0, 1, 2, 0, 2, 3];
    let mut out = object_vertices(model);
    out.extend(
        floor
            .iter()
            .map(|&k| vertex(corners[k], Vec3::Y, Surface::Floor)),
    );
    out
}

/// The model's triangles alone (none for the sphere): what casts the sun's shadow.
pub fn object_vertices(model: &Model) -> Vec<Vertex> {
    match &model.shape {
        Shape::Mesh(mesh) => mesh
            .positions
            .iter()
            .zip(&mesh.normals)
            .map(|(&p, &n)| vertex(p, n, Surface::Object))
            .collect(),
        Shape::Sphere => Vec::new(),
    }
}

/// The box the GPU rasterises to ray-cast the sphere in (1 % larger than the sphere, 12
/// triangles).
pub fn sphere_box_vertices() -> Vec<Vertex> {
    let c = Vec3::from(OBJECT_CENTRE);
    let r = 1.01 * FIT_HALF_EXTENT;
    let corner = |i: usize| {
        c + r * Vec3::new(
            if i & 1 == 0 { -1.0 } else { 1.0 },
            if i & 2 == 0 { -1.0 } else { 1.0 },
            if i & 4 == 0 { -1.0 } else { 1.0 },
        )
    };
    // Each face as two triangles of corner indices.
    const FACES: [[usize; 4]; 6] = [
        [0, 1, 3, 2],
        [4, 6, 7, 5],
        [0, 4, 5, 1],
        [2, 3, 7, 6],
        [0, 2, 6, 4],
        [1, 5, 7, 3],
    ];
    FACES
        .iter()
        .flat_map(|f| [f[0], f[1], f[2], f[0], f[2], f[3]])
        .map(|i| vertex(corner(i), Vec3::ZERO, Surface::Object))
        .collect()
}

/// Per pixel (row-major): (position, surface id) and (normal, 0), as the GPU pass writes
/// them; background pixels are zero.
#[derive(Clone, Debug, PartialEq)]
pub struct GBuffer {
    /// Width in pixels.
    pub width: u32,
    /// Height in pixels.
    pub height: u32,
    /// (position, surface id).
    pub position: Vec<[f32; 4]>,
    /// (unit normal, 0).
    pub normal: Vec<[f32; 4]>,
}

/// The nearest hit of a ray on the sphere: (offset from the centre, distance), as
/// `sphere_hit` (common/view_raster.wgsl) computes it.
pub fn ray_sphere(origin: Vec3, dir: Vec3, centre: Vec3, radius: f32) -> Option<(Vec3, f32)> {
    let f = origin - centre;
    let b = f.dot(dir);
    let q = f - b * dir;
    let disc = radius * radius - q.dot(q);
    if disc < 0.0 {
        return None;
    }
    let s = disc.sqrt();
    let t = -b - s;
    (t > 0.0).then_some((q - s * dir, t))
}

/// Clips a polygon in clip space to z ≥ 0 (Sutherland-Hodgman against one plane).
fn clip_near(poly: &[(Vec4, usize)]) -> Vec<(Vec4, [f32; 3])> {
    let weights = |i: usize| {
        let mut w = [0.0; 3];
        w[i] = 1.0;
        w
    };
    let input: Vec<(Vec4, [f32; 3])> = poly.iter().map(|&(c, i)| (c, weights(i))).collect();
    let mut out = Vec::with_capacity(4);
    for k in 0..input.len() {
        let (a, wa) = input[k];
        let (b, wb) = input[(k + 1) % input.len()];
        let (ina, inb) = (a.z >= 0.0, b.z >= 0.0);
        if ina {
            out.push((a, wa));
        }
        if ina != inb {
            let t = a.z / (a.z - b.z);
            let w = [0, 1, 2].map(|i| wa[i] + t * (wb[i] - wa[i]));
            out.push((a + t * (b - a), w));
        }
    }
    out
}

/// The CPU raster pass of `vertices` (and the sphere when `sphere`) for `frame`.
pub fn rasterize(frame: &FrameUniform, vertices: &[Vertex], sphere: bool) -> GBuffer {
    let (w, h) = (frame.width as usize, frame.height as usize);
    let vp = glam::Mat4::from_cols_array_2d(&frame.view_projection);
    let mut depth = vec![1.0f32; w * h];
    let mut position = vec![[0.0f32; 4]; w * h];
    let mut normal = vec![[0.0f32; 4]; w * h];

    for tri in vertices.chunks_exact(3) {
        let corners = [tri[0], tri[1], tri[2]];
        let clip: Vec<(Vec4, usize)> = (0..3)
            .map(|i| {
                (
                    vp * Vec3::from_slice(&corners[i].position[..3]).extend(1.0),
                    i,
                )
            })
            .collect();
        let poly = clip_near(&clip);
        for k in 1..poly.len().saturating_sub(1) {
            raster_triangle(
                [poly[0], poly[k], poly[k + 1]],
                &corners,
                (w, h),
                &mut depth,
                &mut position,
                &mut normal,
            );
        }
    }

    if sphere {
        let camera = frame.camera();
        let centre = Vec3::from_slice(&frame.sphere[..3]);
        let radius = frame.sphere[3];
        let hits: Vec<(usize, [f32; 4], [f32; 4], f32)> = (0..w * h)
            .into_par_iter()
            .filter_map(|k| {
                let (x, y) = ((k % w) as u32, (k / w) as u32);
                let (o, d) = camera.pixel_ray(x, y, frame.width, frame.height);
                let (offset, _) = ray_sphere(o, d, centre, radius)?;
                let p = centre + offset;
                let c = vp * p.extend(1.0);
                let z = c.z / c.w;
                (0.0..=1.0).contains(&z).then(|| {
                    let id = Surface::Object as u32 as f32;
                    (
                        k,
                        p.extend(id).into(),
                        (offset / radius).extend(0.0).into(),
                        z,
                    )
                })
            })
            .collect();
        for (k, p, n, z) in hits {
            if z < depth[k] {
                depth[k] = z;
                position[k] = p;
                normal[k] = n;
            }
        }
    }
    GBuffer {
        width: frame.width,
        height: frame.height,
        position,
        normal,
    }
}

/// Edge function of (a, b) at p: positive on the left of a → b in a y-down frame's
/// clockwise sense.
fn edge(a: [f32; 2], b: [f32; 2], p: [f32; 2]) -> f32 {
    (b[0] - a[0]) * (p[1] - a[1]) - (b[1] - a[1]) * (p[0] - a[0])
}

/// Whether a pixel centre exactly on edge (a, b) belongs to the triangle (the top-left
/// rule, for a triangle whose edge functions are positive inside).
fn owns_edge(a: [f32; 2], b: [f32; 2]) -> bool {
    let (dx, dy) = (b[0] - a[0], b[1] - a[1]);
    dy < 0.0 || (dy == 0.0 && dx > 0.0)
}

fn raster_triangle(
    tri: [(Vec4, [f32; 3]); 3],
    corners: &[Vertex; 3],
    (w, h): (usize, usize),
    depth: &mut [f32],
    position: &mut [[f32; 4]],
    normal: &mut [[f32; 4]],
) {
    if tri.iter().any(|(c, _)| c.w <= 0.0) {
        return;
    }
    let screen = tri.map(|(c, _)| {
        [
            (c.x / c.w + 1.0) * 0.5 * w as f32,
            (1.0 - c.y / c.w) * 0.5 * h as f32,
        ]
    });
    let area = edge(screen[0], screen[1], screen[2]);
    if area == 0.0 || !area.is_finite() {
        return;
    }
    // Orient so that the edge functions are positive inside.
    let order = if area > 0.0 { [0, 1, 2] } else { [0, 2, 1] };
    let s = order.map(|i| screen[i]);
    let t = order.map(|i| tri[i]);
    let area = area.abs();
    let (min_x, max_x) = (
        s.iter().map(|p| p[0]).fold(f32::MAX, f32::min),
        s.iter().map(|p| p[0]).fold(f32::MIN, f32::max),
    );
    let (min_y, max_y) = (
        s.iter().map(|p| p[1]).fold(f32::MAX, f32::min),
        s.iter().map(|p| p[1]).fold(f32::MIN, f32::max),
    );
    let x0 = (min_x - 0.5).ceil().max(0.0) as usize;
    let x1 = ((max_x - 0.5).floor().min(w as f32 - 1.0)).max(-1.0);
    let y0 = (min_y - 0.5).ceil().max(0.0) as usize;
    let y1 = ((max_y - 0.5).floor().min(h as f32 - 1.0)).max(-1.0);
    if x1 < 0.0 || y1 < 0.0 {
        return;
    }
    let inv_w = t.map(|(c, _)| 1.0 / c.w);
    let z = t.map(|(c, _)| c.z / c.w);
    let attribute = |weights: [f32; 3], field: fn(&Vertex) -> [f32; 4]| -> Vec3 {
        (0..3)
            .map(|i| weights[i] * Vec3::from_slice(&field(&corners[i])[..3]))
            .sum()
    };
    for y in y0..=y1 as usize {
        for x in x0..=x1 as usize {
            let p = [x as f32 + 0.5, y as f32 + 0.5];
            let e = [
                edge(s[1], s[2], p),
                edge(s[2], s[0], p),
                edge(s[0], s[1], p),
            ];
            let inside = (0..3).all(|i| {
                let (a, b) = (s[(i + 1) % 3], s[(i + 2) % 3]);
                e[i] > 0.0 || (e[i] == 0.0 && owns_edge(a, b))
            });
            if !inside {
                continue;
            }
            let l = e.map(|v| v / area);
            let d = l[0] * z[0] + l[1] * z[1] + l[2] * z[2];
            let k = y * w + x;
            if !(0.0..=1.0).contains(&d) || d >= depth[k] {
                continue;
            }
            // Perspective-correct weights of the clipped corners, then of the original ones.
            let pw = [l[0] * inv_w[0], l[1] * inv_w[1], l[2] * inv_w[2]];
            let sum = pw[0] + pw[1] + pw[2];
            let mut weights = [0.0f32; 3];
            for (j, (_, cw)) in t.iter().enumerate() {
                for i in 0..3 {
                    weights[i] += pw[j] / sum * cw[i];
                }
            }
            depth[k] = d;
            let id = corners[0].position[3];
            position[k] = attribute(weights, |v| v.position).extend(id).into();
            normal[k] = attribute(weights, |v| v.normal)
                .normalize_or_zero()
                .extend(0.0)
                .into();
        }
    }
}
