//! The preview's fixed scene: a grid of spheres (rows: the seed materials, columns: the
//! roughness steps) seen by a distant camera over the environment. CPU twin of
//! `shaders/common/preview_scene.wgsl` (same function names); every number of the scene
//! reaches the kernels through [`SceneUniform`], so none is typed twice.
//!
//! Geometry of one panel of `columns × rows` cells of `cell` pixels:
//! - a pixel whose centre lies inside the disc of radius [`SPHERE_RADIUS`] · cell around its
//!   cell's centre sees a sphere orthographically: with (x, y) its offset from the centre
//!   over the radius, the normal in camera space is (x, y, √(1 − x² − y²)) and the view
//!   direction v is the camera's backward axis for every pixel (a distant camera);
//! - any other pixel sees the environment along the ray of a pinhole camera at the same
//!   place, covering the panel with a horizontal half-angle of atan([`TAN_HALF_FOV_X`]).

use glam::Vec3;

use crate::environment::texels::SourceTexel;
use crate::environment::Cubemap;
use crate::math::sampling::hammersley;
use crate::plan::lut::BrdfLut;
use crate::plan::material::ShadeMaterial;
use crate::plan::shading::{LightBrdf, ShadingTerms};

/// A material of the preview: Cook-Torrance with GGX D, Smith/Schlick-GGX G and
/// Fresnel-Schlick, plus Lambert diffuse weighted by kD = (1 − F)(1 − metallic).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Material {
    /// Name shown in labels, tables and the manifest.
    pub name: &'static str,
    /// Linear-RGB reflectance at normal incidence.
    pub f0: [f32; 3],
    /// Linear-RGB diffuse albedo c (Lambert c/π); unused by metals.
    pub albedo: [f32; 3],
    /// 1 for a metal (no diffuse), 0 for a dielectric.
    pub metallic: f32,
}

/// The seed materials, one row each, top to bottom. F0 of gold, copper, aluminium and
/// silver: Hoffman, "Physics and Math of Shading" (SIGGRAPH 2015 course), table of
/// metal F0 in linear RGB; titanium: Real-Time Rendering 4th ed., table 9.2; the
/// dielectric: F0 = 0.04 (n ≈ 1.5) with a light grey albedo of 0.8 (docs/conventions.md,
/// "Roughness, BRDF").
pub const MATERIALS: [Material; 6] = [
    metal("gold", [1.0, 0.71, 0.29]),
    metal("copper", [0.95, 0.64, 0.54]),
    metal("aluminium", [0.91, 0.92, 0.92]),
    metal("titanium", [0.542, 0.497, 0.449]),
    metal("silver", [0.95, 0.93, 0.88]),
    Material {
        name: "dielectric",
        f0: [0.04; 3],
        albedo: [0.8; 3],
        metallic: 0.0,
    },
];

const fn metal(name: &'static str, f0: [f32; 3]) -> Material {
    Material {
        name,
        f0,
        albedo: f0,
        metallic: 1.0,
    }
}

/// Perceptual roughness of each column, left to right.
pub const ROUGHNESS: [f32; 5] = [0.0, 0.25, 0.5, 0.75, 1.0];

/// Sphere radius as a fraction of the cell edge (a margin of 5 % of the cell each side).
pub const SPHERE_RADIUS: f32 = 0.45;

/// tan of the background camera's horizontal half-angle (≈ 53° horizontal field of view).
pub const TAN_HALF_FOV_X: f32 = 0.5;

/// The camera: it looks along +X (the centre of an equirect), +Y up, so +Z is to the
/// right (right-handed).
pub const CAMERA_FORWARD: [f32; 3] = [1.0, 0.0, 0.0];
/// The camera's up axis.
pub const CAMERA_UP: [f32; 3] = [0.0, 1.0, 0.0];

/// Smallest n·v the shading uses: the silhouette's normals are perpendicular to v.
pub const MIN_N_DOT_V: f32 = 1e-4;

/// Default cell edge in pixels.
pub const DEFAULT_CELL: u32 = 64;

/// The scene of one panel.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Scene {
    /// Cell edge in pixels.
    pub cell: u32,
}

impl Default for Scene {
    fn default() -> Self {
        Scene { cell: DEFAULT_CELL }
    }
}

/// Uniform block of the preview kernels (`shaders/common/preview_scene.wgsl`; layout
/// checked in tests/shaders.rs).
#[repr(C)]
#[derive(Clone, Copy, Debug, bytemuck::Pod, bytemuck::Zeroable)]
pub struct SceneUniform {
    /// Panel width in pixels.
    pub width: u32,
    /// Panel height in pixels.
    pub height: u32,
    /// Cell edge in pixels.
    pub cell: u32,
    /// Number of roughness columns.
    pub columns: u32,
    /// Sphere radius in pixels.
    pub radius: f32,
    /// tan of the horizontal half field of view.
    pub tan_half_x: f32,
    /// tan of the vertical half field of view.
    pub tan_half_y: f32,
    /// [`MIN_N_DOT_V`].
    pub min_n_dot_v: f32,
    /// Camera right axis (w unused).
    pub right: [f32; 4],
    /// Camera up axis (w unused).
    pub up: [f32; 4],
    /// Camera forward axis (w unused).
    pub forward: [f32; 4],
}

/// What a pixel sees.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum PixelGeometry {
    /// The environment along `dir`.
    Background {
        /// World-space direction of the camera ray.
        dir: Vec3,
    },
    /// A point of the sphere of `material` (row) and roughness `column`.
    Sphere {
        /// World-space unit normal.
        n: Vec3,
        /// World-space unit direction towards the camera.
        v: Vec3,
        /// Index into [`MATERIALS`].
        material: usize,
        /// Index into [`ROUGHNESS`].
        column: usize,
    },
}

impl Scene {
    /// Panel width in pixels.
    pub fn width(&self) -> u32 {
        self.cell * ROUGHNESS.len() as u32
    }

    /// Panel height in pixels.
    pub fn height(&self) -> u32 {
        self.cell * MATERIALS.len() as u32
    }

    /// The kernels' uniform block.
    pub fn uniform(&self) -> SceneUniform {
        let forward = Vec3::from(CAMERA_FORWARD);
        let up = Vec3::from(CAMERA_UP);
        let right = forward.cross(up);
        let (w, h) = (self.width(), self.height());
        SceneUniform {
            width: w,
            height: h,
            cell: self.cell,
            columns: ROUGHNESS.len() as u32,
            radius: SPHERE_RADIUS * self.cell as f32,
            tan_half_x: TAN_HALF_FOV_X,
            tan_half_y: TAN_HALF_FOV_X * h as f32 / w as f32,
            min_n_dot_v: MIN_N_DOT_V,
            right: right.extend(0.0).into(),
            up: up.extend(0.0).into(),
            forward: forward.extend(0.0).into(),
        }
    }
}

/// What pixel (x, y) of a panel sees (x to the right, y down).
pub fn pixel_geometry(s: &SceneUniform, x: u32, y: u32) -> PixelGeometry {
    let right = Vec3::from_slice(&s.right);
    let up = Vec3::from_slice(&s.up);
    let forward = Vec3::from_slice(&s.forward);
    let (col, row) = (x / s.cell, y / s.cell);
    let half = 0.5 * s.cell as f32;
    let cx = (x - col * s.cell) as f32 + 0.5 - half;
    let cy = half - ((y - row * s.cell) as f32 + 0.5);
    let (u, w) = (cx / s.radius, cy / s.radius);
    let r2 = u * u + w * w;
    if r2 < 1.0 {
        let z = (1.0 - r2).sqrt();
        return PixelGeometry::Sphere {
            n: u * right + w * up - z * forward,
            v: -forward,
            material: row as usize,
            column: col as usize,
        };
    }
    let nx = 2.0 * (x as f32 + 0.5) / s.width as f32 - 1.0;
    let ny = 1.0 - 2.0 * (y as f32 + 0.5) / s.height as f32;
    let dir = (nx * s.tan_half_x) * right + (ny * s.tan_half_y) * up + forward;
    PixelGeometry::Background {
        dir: dir.normalize(),
    }
}

/// The material table of the kernels: per material (F0, metallic), (albedo, 0).
pub fn material_table() -> Vec<[f32; 4]> {
    MATERIALS
        .iter()
        .flat_map(|m| {
            [
                [m.f0[0], m.f0[1], m.f0[2], m.metallic],
                [m.albedo[0], m.albedo[1], m.albedo[2], 0.0],
            ]
        })
        .collect()
}

/// The material of the sphere in row `material`, column `column` of the kernels' tables:
/// the row's (F0, metallic), (albedo, 0), the sphere's (roughness, lod, bend, stretch),
/// `spheres` holding a row of `columns` spheres per material. Mirror of
/// `preview_material` in `shaders/common/preview_scene.wgsl`.
pub fn preview_material(
    spheres: &[[f32; 4]],
    materials: &[[f32; 4]],
    columns: usize,
    material: usize,
    column: usize,
) -> ShadeMaterial {
    let fm = materials[2 * material];
    let col = spheres[material * columns + column];
    ShadeMaterial {
        f0: Vec3::new(fm[0], fm[1], fm[2]),
        metallic: fm[3],
        albedo: Vec3::from_slice(&materials[2 * material + 1][..3]),
        roughness: col[0],
        lod: col[1],
        bend: col[2],
        stretch: col[3],
    }
}

/// Default number of quasi-Monte Carlo points per lobe and pixel.
pub const DEFAULT_TRUTH_SAMPLES: u32 = 2048;

/// The environment the truth integrates: what `truth_shade` reads besides the point.
#[derive(Clone, Copy, Debug)]
pub struct TruthLight<'a> {
    /// The environment (level 0 read).
    pub env: &'a Cubemap,
    /// The environment without its hot texels (level 0 read).
    pub cold: &'a Cubemap,
    /// The hot texels, summed exactly.
    pub hot: &'a [SourceTexel],
    /// The quasi-Monte Carlo points ([`disk_points`]).
    pub points: &'a [[f32; 4]],
    /// The BRDF integrated (its compensation is applied by the preview's render, which
    /// has the LUT: [`TruthInputs::lut`]).
    pub brdf: LightBrdf,
}

/// The baked light the split-sum reads: what `split_sum_shade` reads besides the point.
#[derive(Clone, Copy, Debug)]
pub struct SplitSumLight<'a> {
    /// The prefiltered specular chain (level 0: the environment), generic orientation.
    pub specular: &'a Cubemap,
    /// The irradiance cube (E/π).
    pub irradiance: &'a Cubemap,
    /// The split-sum LUT (scale A, bias B).
    pub lut: &'a BrdfLut,
    /// How the shading combines the reads (the recipe's, or an engine's).
    pub terms: ShadingTerms,
    /// The recipe's taps at grazing views (`plan::filtered`), reading the chain's levels as
    /// this mapping says; None for a lookup without them.
    pub filtered: Option<crate::plan::chain::MipRoughness>,
}

/// What the truth render reads: the environment and the kernels' tables.
#[derive(Clone, Copy, Debug)]
pub struct TruthInputs<'a> {
    /// The environment the truth integrates.
    pub light: TruthLight<'a>,
    /// Per sphere, row by row: (roughness, lod, bend, stretch); only the roughness is
    /// read here.
    pub spheres: &'a [[f32; 4]],
    /// Per material: (F0, metallic), (albedo, 0).
    pub materials: &'a [[f32; 4]],
    /// The LUT (A, B) the light BRDF's compensation reads, when it is compensated.
    pub lut: &'a BrdfLut,
}

/// The N points of the truth's quadrature: Hammersley (i/N, φ-radical-inverse) as
/// (u₁, cos 2πu₂, sin 2πu₂, 0); a pixel maps one to the unit disk as
/// √frac(u₁ + s) (cos, sin) rotated by its own angle.
pub fn disk_points(samples: u32) -> Vec<[f32; 4]> {
    (0..samples)
        .map(|i| {
            let [u1, u2] = hammersley(i, samples);
            let phi = 2.0 * std::f32::consts::PI * u2;
            [u1, phi.cos(), phi.sin(), 0.0]
        })
        .collect()
}

/// What the split-sum render reads: the baked light and the kernels' tables.
#[derive(Clone, Copy, Debug)]
pub struct SplitSumInputs<'a> {
    /// The baked light.
    pub light: SplitSumLight<'a>,
    /// Per sphere, row by row (`stages::preview::sphere_table`): (roughness, the chain's
    /// lod for it, the lookup's bend for it and the row's F0, the lookup's stretch).
    pub spheres: &'a [[f32; 4]],
    /// Per material: (F0, metallic), (albedo, 0) (`scene::material_table`).
    pub materials: &'a [[f32; 4]],
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The centre pixel of a cell faces the camera, the corner sees the background, and
    /// the sphere's normals are unit vectors on the camera's side.
    #[test]
    fn geometry_of_a_cell() {
        let s = Scene { cell: 64 }.uniform();
        match pixel_geometry(&s, 64 + 32, 2 * 64 + 32) {
            PixelGeometry::Sphere {
                n,
                v,
                material,
                column,
            } => {
                assert_eq!((material, column), (2, 1));
                assert!(n.dot(v) > 0.999 && (n.length() - 1.0).abs() < 1e-6);
                assert_eq!(v, Vec3::new(-1.0, 0.0, 0.0));
            }
            g => panic!("{g:?}"),
        }
        assert!(matches!(
            pixel_geometry(&s, 0, 0),
            PixelGeometry::Background { .. }
        ));
        // Right of the cell centre the normal leans to +Z (the camera's right).
        match pixel_geometry(&s, 32 + 25, 32) {
            PixelGeometry::Sphere { n, .. } => assert!(n.z > 0.5),
            g => panic!("{g:?}"),
        }
    }
}
