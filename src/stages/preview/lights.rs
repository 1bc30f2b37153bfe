//! The lights taken out of the environment, shaded on the preview's split-sum side: the sun
//! and the sun-sized lights as directional lights ([`add_sun_light`]), area sources (a
//! light with a [`Sun::shape`]) from an LTC table ([`add_area_light`],
//! [`crate::plan::ltc::shade_polygon`]). An area source is a polygon
//! (a rectangle's corners, a disc's equal-area regular polygon,
//! [`crate::math::ltc::disc_polygon`]) of uniform radiance E⊥ / Ω_polygon, so the light it
//! carries is its E⊥ exactly.

use glam::Vec3;

use crate::cpu::preview_split_sum::{sample_lut, specular_compensation};
use crate::cpu::preview_truth::hot_texels_shade;
use crate::environment::sun::{SourceShape, Sun};
use crate::environment::texels::SourceTexel;
use crate::math::ltc::{disc_polygon, polygon_solid_angle, rect_polygon};
use crate::plan::ltc::{shade_polygon, LtcTable};
use crate::plan::lut::BrdfLut;
use crate::plan::scene::{pixel_geometry, preview_material, PixelGeometry, SceneUniform, MIN_N_DOT_V};
use crate::plan::material::ShadeMaterial;
use crate::plan::shading::LightBrdf;

/// The polygon an area light of `shape` about `light`'s direction is shaded as (unit
/// vertices in order) and its uniform radiance, E⊥ over the polygon's solid angle.
pub fn area_polygon(light: &Sun, shape: SourceShape) -> (Vec<Vec3>, Vec3) {
    let centre = Vec3::from(light.direction);
    let polygon = match shape {
        SourceShape::Disc { radius_deg } => disc_polygon(centre, radius_deg.to_radians()),
        SourceShape::Rect {
            half_width_deg,
            half_height_deg,
            width_axis,
        } => rect_polygon(
            centre,
            Vec3::from(width_axis),
            half_width_deg.to_radians(),
            half_height_deg.to_radians(),
        )
        .to_vec(),
    };
    let omega = polygon_solid_angle(&polygon).max(f32::MIN_POSITIVE);
    (polygon, Vec3::from(light.irradiance) / omega)
}

/// The scene and tables a light is added to the split-sum panel with.
#[derive(Clone, Copy, Debug)]
pub struct LightPass<'a> {
    /// The preview's scene.
    pub scene: &'a SceneUniform,
    /// The kernels' per-sphere table.
    pub spheres: &'a [[f32; 4]],
    /// The kernels' per-material table.
    pub materials: &'a [[f32; 4]],
    /// The BRDF the light is shaded with.
    pub brdf: LightBrdf,
    /// The LUT whose compensation scales the specular where `brdf` is compensated.
    pub lut: &'a BrdfLut,
}

impl LightPass<'_> {
    /// Adds `shade(n, v, n·v, material)` = (specular, diffuse per unit albedo) to every
    /// sphere pixel of `panel`, the specular scaled by the compensation 1 + F0 (1/Ess − 1)
    /// where the BRDF is compensated.
    fn add(
        &self,
        panel: &mut [[f32; 3]],
        shade: impl Fn(Vec3, Vec3, f32, &ShadeMaterial) -> (Vec3, Vec3),
    ) {
        let scene = self.scene;
        for y in 0..scene.height {
            for x in 0..scene.width {
                if let PixelGeometry::Sphere {
                    n,
                    v,
                    material,
                    column,
                } = pixel_geometry(scene, x, y)
                {
                    let m = preview_material(self.spheres, self.materials, scene.columns as usize, material, column);
                    let n_dot_v = n.dot(v).max(MIN_N_DOT_V);
                    let (mut spec, diff) = shade(n, v, n_dot_v, &m);
                    if self.brdf.compensated {
                        spec *= specular_compensation(sample_lut(self.lut, n_dot_v, m.roughness), m.f0);
                    }
                    let c = spec + diff * m.albedo;
                    let p = &mut panel[(y * scene.width + x) as usize];
                    *p = [p[0] + c.x, p[1] + c.y, p[2] + c.z];
                }
            }
        }
    }
}

/// Adds the sun, a directional light of irradiance E⊥ from its direction, to every sphere
/// pixel of the split-sum panel: E⊥ f(l, v) (n·l) with the pass's BRDF, evaluated by the
/// truth's exact sum over one texel (`cpu::preview_truth::hot_texels_shade`), so the
/// light is shaded as the truth shades its hot texels. At r = 0 a mirror reflects no
/// directional light.
pub fn add_sun_light(pass: &LightPass, sun: &Sun, panel: &mut [[f32; 3]]) {
    let d = sun.direction;
    let light = [SourceTexel {
        dir_omega: [d[0], d[1], d[2], 1.0],
        radiance: [sun.irradiance[0], sun.irradiance[1], sun.irradiance[2], 0.0],
    }];
    pass.add(panel, |n, v, n_dot_v, m| {
        let alpha = crate::math::brdf::alpha_from_roughness(m.roughness);
        hot_texels_shade(&light, n, v, n_dot_v, alpha, m.f0, m.metallic, pass.brdf)
    });
}

/// Adds an area light, `light` of `shape`, to every sphere pixel of the split-sum panel,
/// shaded from `table` ([`shade_polygon`]).
pub fn add_area_light(
    pass: &LightPass,
    light: &Sun,
    shape: SourceShape,
    table: &LtcTable,
    panel: &mut [[f32; 3]],
) {
    let (polygon, radiance) = area_polygon(light, shape);
    pass.add(panel, |n, v, n_dot_v, m| {
        shade_polygon(table, n, v, n_dot_v, m, &polygon, radiance)
    });
}
