//! The viewer's scene, after the sandbox of the document splitsum grew from (a LearnOpenGL
//! PBR program cut down to one object): one object centred at (0, 0, 1.5) and turned 180°
//! about y, above a floor plane at y = −0.75 (a dielectric of roughness 0.9 and colour
//! 0.2), lit by the bake and, on a key, by four point lights.
//!
//! Materials are the preview's six (`plan::scene::MATERIALS`: gold, copper, aluminium,
//! titanium, silver, a dielectric), each read as a base colour and a metallic flag, the
//! metallic-roughness model of glTF 2.0 (§ 3.9.2): F0 = mix(0.04, base, metallic),
//! albedo = base (1 − metallic); a metal's base colour is its F0, the dielectric's its
//! albedo. The metallic key flips the flag; roughness is the user's for every material.
//!
//! The point lights shade with Cook-Torrance as the document's program does: GGX D with
//! α = r², Smith with Schlick-GGX G1 and k_direct = (r + 1)²/8 (Karis 2013, "Real Shading
//! in Unreal Engine 4": the remapping for analytic lights; the IBL terms keep k = r²/2),
//! Fresnel-Schlick at v·h, Lambert diffuse weighted by (1 − F)(1 − metallic), and radiance
//! falling off as 1/d². No shadows.

use glam::Vec3;

use crate::plan::material::ShadeMaterial;
use crate::plan::scene::MATERIALS;

/// The object's centre.
pub const OBJECT_CENTRE: [f32; 3] = [0.0, 0.0, 1.5];
/// The object's turn about y, degrees.
pub const OBJECT_TURN_DEG: f32 = 180.0;
/// Half the largest extent of a placed model's bounding box (the sphere's radius): the
/// object keeps 0.05 units above the floor.
pub const FIT_HALF_EXTENT: f32 = 0.7;
/// Height of the floor plane.
pub const FLOOR_Y: f32 = -0.75;
/// Half the edge of the square floor, centred under the object.
pub const FLOOR_HALF_EXTENT: f32 = 25.0;
/// The floor: a dielectric of roughness 0.9 and colour 0.2.
pub const FLOOR_ROUGHNESS: f32 = 0.9;
/// See [`FLOOR_ROUGHNESS`].
pub const FLOOR_COLOUR: f32 = 0.2;
/// F0 of every dielectric (n ≈ 1.5).
pub const DIELECTRIC_F0: f32 = 0.04;

/// A point light: position and radiant intensity (radiance at distance d is colour / d²).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PointLight {
    /// Position.
    pub position: [f32; 3],
    /// Linear RGB intensity.
    pub colour: [f32; 3],
}

/// LearnOpenGL's four lights of its PBR chapters ("Lighting"): ±10 in x and y, 10 units
/// in front of the object towards the starting camera, intensity 300.
pub const POINT_LIGHTS: [PointLight; 4] = [
    light(-10.0, 10.0),
    light(10.0, 10.0),
    light(-10.0, -10.0),
    light(10.0, -10.0),
];

const fn light(x: f32, y: f32) -> PointLight {
    PointLight {
        position: [x, y, OBJECT_CENTRE[2] + 10.0],
        colour: [300.0; 3],
    }
}

/// A material of the viewer: a base colour and a metallic flag.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BaseMaterial {
    /// Name shown in the HUD.
    pub name: &'static str,
    /// Base colour (a metal's F0, a dielectric's albedo), linear RGB.
    pub base: [f32; 3],
    /// Whether it is a metal.
    pub metallic: bool,
}

/// The six materials on keys 1–6: the preview's, as base colours.
pub fn materials() -> [BaseMaterial; 6] {
    MATERIALS.map(|m| BaseMaterial {
        name: m.name,
        base: if m.metallic >= 1.0 { m.f0 } else { m.albedo },
        metallic: m.metallic >= 1.0,
    })
}

impl BaseMaterial {
    /// Linear-RGB reflectance at normal incidence: the base colour for a metal, the
    /// dielectric F0 otherwise.
    pub fn f0(&self) -> Vec3 {
        match self.metallic {
            true => Vec3::from(self.base),
            false => Vec3::splat(DIELECTRIC_F0),
        }
    }

    /// The shading functions' material at `roughness` with the chain's `lod` and the
    /// lookup's `bend` for it and its `stretch`.
    pub fn shade(&self, roughness: f32, lod: f32, bend: f32, stretch: f32) -> ShadeMaterial {
        let base = Vec3::from(self.base);
        let metallic = if self.metallic { 1.0 } else { 0.0 };
        ShadeMaterial {
            f0: self.f0(),
            metallic,
            albedo: base * (1.0 - metallic),
            roughness,
            lod,
            bend,
            stretch,
        }
    }
}

/// The floor's material.
pub fn floor_material() -> BaseMaterial {
    BaseMaterial {
        name: "floor",
        base: [FLOOR_COLOUR; 3],
        metallic: false,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The materials shade as the preview's do: same F0 and metallic, and the same albedo
    /// wherever it counts (a metal's albedo is multiplied by 1 − metallic = 0).
    #[test]
    fn materials_are_the_previews() {
        for (v, p) in materials().iter().zip(MATERIALS.iter()) {
            let m = v.shade(0.5, 1.0, 0.0, 0.0);
            assert_eq!(m.f0, Vec3::from(p.f0), "{}", p.name);
            assert_eq!(m.metallic, p.metallic);
            if p.metallic < 1.0 {
                assert_eq!(m.albedo, Vec3::from(p.albedo));
            }
        }
    }

    /// The paper's placements.
    #[test]
    fn placements() {
        assert_eq!(OBJECT_CENTRE, [0.0, 0.0, 1.5]);
        assert_eq!(OBJECT_TURN_DEG, 180.0);
        assert_eq!(FLOOR_Y, -0.75);
        let f = floor_material().shade(FLOOR_ROUGHNESS, 0.0, 0.0, 0.0);
        assert_eq!((f.roughness, f.metallic), (0.9, 0.0));
        assert_eq!(f.albedo, Vec3::splat(0.2));
        assert_eq!(f.f0, Vec3::splat(0.04));
        const { assert!(OBJECT_CENTRE[1] - FIT_HALF_EXTENT > FLOOR_Y) };
    }
}
