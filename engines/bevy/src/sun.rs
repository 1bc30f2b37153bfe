//! The sun case: quarry_01 baked with `--sun split`, its sun.json as a `DirectionalLight`
//! beside the residual IBL, the scenes and cameras that measure it.

use std::path::Path;

use bevy::asset::UntypedAssetId;
use bevy::camera::visibility::RenderLayers;
use bevy::light::EnvironmentMapLight;
use bevy::prelude::*;

use crate::capture::{check_camera, float_target};
use crate::{
    view_geometry, Check, Shot, View, FORMATS, SHADOW_CAMERA_HEIGHT, SHADOW_EXTENT, SHADOW_HEIGHT,
    SUN_HDRI, SUN_LABEL,
};

/// The sun of a `--sun split` bake's sun.json: toward the sun, in Bevy's world, and E.
#[derive(Clone, Copy)]
pub struct SunLight {
    pub direction: Vec3,
    pub irradiance: Vec3,
}

impl SunLight {
    pub fn read(path: &Path) -> SunLight {
        let text = match std::fs::read_to_string(path) {
            Ok(text) => text,
            Err(e) => panic!("{}: {e}", path.display()),
        };
        let json: serde_json::Value =
            serde_json::from_str(&text).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
        let v = |key: &str| {
            Vec3::from_array([0, 1, 2].map(|i| json[key][i].as_f64().expect("sun.json") as f32))
        };
        SunLight {
            direction: v("direction"),
            irradiance: v("irradiance"),
        }
    }

    /// Bevy's `DirectionalLight` of this sun, next to an `EnvironmentMapLight` of
    /// `intensity`: Bevy shades a directional light with colour × illuminance and the
    /// environment with radiance × intensity, so illuminance = max(E) × intensity and the
    /// colour E / max(E); it shines along −direction.
    pub fn bundle(&self, intensity: f32, shadows: bool) -> (DirectionalLight, Transform) {
        let peak = self.irradiance.max_element();
        let c = self.irradiance / peak;
        (
            DirectionalLight {
                color: Color::linear_rgb(c.x, c.y, c.z),
                illuminance: peak * intensity,
                shadow_maps_enabled: shadows,
                ..default()
            },
            Transform::IDENTITY.looking_to(-self.direction, Vec3::Y),
        )
    }
}

/// The sun case's scene and cameras. Render layers keep it apart from the other shots and
/// give each light only the views it belongs to (Bevy skips a directional light in a view
/// whose layers it does not share, and casts its shadows from the meshes it shares a layer
/// with): 3 the diffuse sphere, seen by both sphere cameras; 4 the sun's light, in the
/// split camera's layers only; 5 the floor and box, seen from above; 6 a second light of
/// the same sun, casting shadows, sharing a layer with the floor, the box and the camera
/// above.
#[allow(clippy::too_many_arguments)]
pub fn sun_shots(
    commands: &mut Commands,
    assets: &AssetServer,
    images: &mut Assets<Image>,
    meshes: &mut Assets<Mesh>,
    materials: &mut Assets<StandardMaterial>,
    check: &Check,
    intensity: f32,
    shots: &mut Vec<Shot>,
    handles: &mut Vec<UntypedAssetId>,
) {
    let geometry = view_geometry();
    let diffuse_white = materials.add(StandardMaterial {
        base_color: Color::WHITE,
        metallic: 0.0,
        perceptual_roughness: 1.0,
        // F0 = 0 (and with it Bevy's F90): no specular, the Lambertian term alone.
        reflectance: 0.0,
        ..default()
    });
    commands.spawn((
        Mesh3d(meshes.add(Sphere::new(1.0).mesh().uv(128, 64))),
        MeshMaterial3d(diffuse_white.clone()),
        RenderLayers::layer(3),
    ));
    let sun = check.sun_light;
    commands.spawn((sun.bundle(intensity, false), RenderLayers::layer(4)));
    commands.spawn((sun.bundle(intensity, true), RenderLayers::layer(6)));
    commands.spawn((
        Mesh3d(
            meshes.add(
                Plane3d::default()
                    .mesh()
                    .size(4.0 * SHADOW_EXTENT, 4.0 * SHADOW_EXTENT),
            ),
        ),
        MeshMaterial3d(diffuse_white.clone()),
        RenderLayers::from_layers(&[5, 6]),
    ));
    commands.spawn((
        Mesh3d(meshes.add(Cuboid::new(1.0, 1.0, 1.0))),
        MeshMaterial3d(diffuse_white),
        Transform::from_xyz(0.0, SHADOW_HEIGHT, 0.0),
        RenderLayers::from_layers(&[5, 6]),
    ));

    // The sphere cameras 90° from the sun: half the sphere lit, half shaded.
    let toward = sun.direction;
    let axis = Vec3::Y.cross(toward).normalize();
    let view_dir = Quat::from_axis_angle(axis, 90f32.to_radians()) * toward;
    let sphere_transform = Transform::from_translation(view_dir * geometry.sphere_distance)
        .looking_at(Vec3::ZERO, Vec3::Y);
    let full = format!("{}/{SUN_HDRI}", FORMATS[0].0);
    let split = format!("split/{SUN_HDRI}");
    for (view, dir, layers) in [
        (View::SunFull, full.as_str(), RenderLayers::layer(3)),
        (
            View::SunSplit,
            split.as_str(),
            RenderLayers::from_layers(&[3, 4]),
        ),
        (View::SunShadow, "", RenderLayers::from_layers(&[5, 6])),
    ] {
        let size = geometry.size;
        let target = float_target(images, size);
        let (transform, fov) = match view {
            View::SunShadow => (
                Transform::from_xyz(0.0, SHADOW_CAMERA_HEIGHT, 0.0)
                    .looking_at(Vec3::ZERO, Vec3::NEG_Z),
                2.0 * (SHADOW_EXTENT / SHADOW_CAMERA_HEIGHT).atan(),
            ),
            _ => (sphere_transform, geometry.sphere_fov),
        };
        let mut camera =
            commands.spawn((check_camera(shots.len(), &target, fov, transform), layers));
        if view != View::SunShadow {
            let specular: Handle<Image> = assets.load(format!("{dir}/specular.ktx2"));
            let diffuse: Handle<Image> = assets.load(format!("{dir}/irradiance.ktx2"));
            handles.extend([specular.id().untyped(), diffuse.id().untyped()]);
            camera.insert(EnvironmentMapLight {
                diffuse_map: diffuse,
                specular_map: specular,
                intensity,
                ..default()
            });
        }
        shots.push(Shot {
            hdri: SUN_HDRI,
            format: SUN_LABEL,
            view,
            size,
            transform,
            fov,
            target,
        });
    }
}
