//! The studio case: a studio's lamps as Bevy's own `RectLight`s. studio_small_03 is baked
//! by the README recipe's shell lines (`--sun split`: its lamps taken out) and its lamps
//! spawned by the recipe's `setup` as written; the same HDRI is baked with its lamps kept in
//! the IBL beside it. White spheres, a metal of F0 = 1 and a dielectric of F0 = 0.04 at
//! r = 0.25, 0.5 and 1, are seen 40° from the first lamp and written as linear floats (row
//! 0 at the bottom, as `engines/measure.js` reads pixels) with the camera in
//! `results.json`: tests/engine_renders.rs holds them against the integral of the HDRI as
//! read with Bevy's BRDF, the preview's truth (docs/targets.md, "Area lights").
//!
//! The split bake is drawn with `splitsum_bevy::CompensatedRectLights` (`sphere_*`, the
//! README's advice) and as Bevy shades rect lights unaided (`plain_sphere_*`). Bevy lights
//! every view with every `RectLight` (their render layers are not applied to them) and the
//! plugin patches a shader for the whole app, so each is drawn by a process of its own:
//! `splitsum-engine-bevy studio split|plain|kept`, which the check runs after its other
//! shots.

use std::path::{Path, PathBuf};
use std::process::Command;

use bevy::camera::visibility::RenderLayers;
use bevy::light::EnvironmentMapLight;
use bevy::prelude::*;

use crate::capture::{
    capture_round, check_camera, float_target, save_png, Captures, CheckCamera, Progress,
};
use crate::{copy_as_sky, readme_recipe, run, run_recipe_commands, view_geometry};

/// The studio HDRI (a 6° lamp holding 72 % of the light and a soft source on its horizon).
pub const HDRI: &str = "studio_small_03_1k";
/// Edge of the sphere renders (three.js's studio case's, `STUDIO_SIZE`).
const SIZE: u32 = 96;
/// The spheres' roughness.
const ROUGHNESS: [f32; 3] = [0.25, 0.5, 1.0];
/// The camera's angle from the first lamp, degrees (three.js's studio case's).
const CAMERA_FROM_LAMP_DEG: f32 = 40.0;

/// Which bake a studio process draws, and how.
#[derive(Clone, Copy, PartialEq, Eq)]
enum Mode {
    /// The lamps taken out, as the README's recipe spawns them, shaded with
    /// `splitsum_bevy::CompensatedRectLights`.
    Split,
    /// The same as Bevy shades them unaided.
    Plain,
    /// The lamps kept in the IBL.
    Kept,
}

impl Mode {
    fn name(self) -> &'static str {
        match self {
            Mode::Split => "split",
            Mode::Plain => "plain",
            Mode::Kept => "kept",
        }
    }

    /// Whether the README's recipe spawns its camera and lights.
    fn recipe(self) -> bool {
        self != Mode::Kept
    }

    /// Its folder under the check's output: `sky.hdr` and the bake in `assets/sky/`.
    fn folder(self, out: &Path) -> PathBuf {
        let bake = if self.recipe() { "split" } else { "kept" };
        out.join(format!("studio_{bake}"))
    }

    /// The prefix of its renders' file names (tests/engine_renders.rs reads them).
    fn prefix(self) -> &'static str {
        match self {
            Mode::Split => "",
            Mode::Plain => "plain_",
            Mode::Kept => "kept_",
        }
    }
}

/// Bakes both: the README's shell lines in the split folder, `--sun keep` in the kept one.
pub fn bake(splitsum: &Path, out: &Path) {
    run_recipe_commands(splitsum, &Mode::Split.folder(out), HDRI);
    let kept = Mode::Kept.folder(out);
    copy_as_sky(&kept, HDRI);
    run(Command::new(splitsum).current_dir(&kept).args([
        "bake", "sky.hdr", "--target", "bevy", "--sun", "keep", "-q", "--no-sh", "--no-lut", "-o",
        "assets/",
    ]));
}

/// Draws each mode in a process of its own; whether each wrote its renders.
pub fn render_all(out: &Path) -> bool {
    let exe = std::env::current_exe().expect("the check's own executable");
    [Mode::Split, Mode::Plain, Mode::Kept]
        .into_iter()
        .all(|mode| {
            let status = Command::new(&exe)
                .args(["studio", mode.name()])
                .status()
                .unwrap_or_else(|e| panic!("{}: {e}", exe.display()));
            println!(
                "{} studio {HDRI} {}: renders in {}",
                if status.success() { "ok  " } else { "FAIL" },
                mode.name(),
                out.display()
            );
            status.success()
        })
}

/// How far away the README's recipe puts a rect light, in world units.
const LAMP_DISTANCE: f32 = 100.0;

/// A rect light as sun.json describes it: where the recipe must put it and how bright.
struct Lamp {
    /// Toward the light.
    toward: Vec3,
    /// The rectangle's transform: at `LAMP_DISTANCE` along `toward`, its local x along the
    /// width axis and its local z along `toward`, so that it faces the origin (Bevy's rect
    /// light shines along its local −z).
    transform: Transform,
    width: f32,
    height: f32,
    /// Radiance per channel, in the HDRI's units.
    radiance: Vec3,
}

/// The lights of a bake's `sun.json` (the sun, then `additional_lights`): those with a
/// `rect_light`, and how many without.
fn lamps(sun_json: &Path) -> (Vec<Lamp>, usize) {
    let text =
        std::fs::read_to_string(sun_json).unwrap_or_else(|e| panic!("{}: {e}", sun_json.display()));
    let json: serde_json::Value =
        serde_json::from_str(&text).unwrap_or_else(|e| panic!("{}: {e}", sun_json.display()));
    let v =
        |j: &serde_json::Value| Vec3::from_array([0, 1, 2].map(|i| j[i].as_f64().unwrap() as f32));
    let lights: Vec<&serde_json::Value> = std::iter::once(&json)
        .chain(json["additional_lights"].as_array().into_iter().flatten())
        .collect();
    let mut lamps = Vec::new();
    for light in &lights {
        let rect = &light["rect_light"];
        if !rect.is_object() {
            continue;
        }
        let toward = v(&light["direction"]);
        let x = v(&rect["width_axis"]);
        let side =
            |k: &str| 2.0 * LAMP_DISTANCE * (rect[k].as_f64().unwrap() as f32).to_radians().tan();
        let frame = Quat::from_mat3(&Mat3::from_cols(x, toward.cross(x), toward));
        lamps.push(Lamp {
            toward,
            transform: Transform::from_translation(toward * LAMP_DISTANCE).with_rotation(frame),
            width: side("half_width_deg"),
            height: side("half_height_deg"),
            radiance: v(&rect["radiance"]),
        });
    }
    let directional = lights.len() - lamps.len();
    (lamps, directional)
}

/// Whether the recipe's `RectLight` at `transform` is `lamp` at `intensity` (the
/// `EnvironmentMapLight`'s): its place and frame, its size, and the radiance Bevy gives it,
/// colour × lumens / (π w h) (bevy_pbr's `extract_lights`), within f32 rounding.
fn spawned_as(light: &RectLight, transform: &Transform, lamp: &Lamp, intensity: f32) -> bool {
    const EPS: f32 = 1e-4;
    let c = light.color.to_linear();
    let radiance = Vec3::new(c.red, c.green, c.blue) * light.intensity
        / (std::f32::consts::PI * light.width * light.height)
        / intensity;
    transform.translation.distance(lamp.transform.translation) <= EPS * LAMP_DISTANCE
        && transform.rotation.angle_between(lamp.transform.rotation) <= EPS
        && (light.width / lamp.width - 1.0).abs() <= EPS
        && (light.height / lamp.height - 1.0).abs() <= EPS
        && (radiance - lamp.radiance).abs().max_element() <= EPS * lamp.radiance.max_element()
}

/// One studio process's state.
#[derive(Resource)]
struct Studio {
    mode: Mode,
    out: PathBuf,
    /// The split bake's rect lights.
    lamps: Vec<Lamp>,
    /// How many lights of its sun.json have no rect light (directional lights).
    directional: usize,
    /// Each sphere's name and image.
    shots: Vec<(String, Handle<Image>)>,
    camera: Transform,
    progress: Progress,
}

/// `splitsum-engine-bevy studio split|plain|kept`: draws one mode's spheres.
pub fn main(mode: &str, out: &Path) -> AppExit {
    let mode = [Mode::Split, Mode::Plain, Mode::Kept]
        .into_iter()
        .find(|m| m.name() == mode)
        .unwrap_or_else(|| panic!("studio {mode}: the modes are split, plain and kept"));
    let folder = mode.folder(out);
    let sun_json = Mode::Split.folder(out).join("assets/sky/sun.json");
    let (lamps, directional) = lamps(&sun_json);
    assert!(
        !lamps.is_empty(),
        "{}: no light with a rect_light",
        sun_json.display()
    );
    // The recipe's `setup` reads `assets/sky/sun.json` from the working directory.
    std::env::set_current_dir(&folder).unwrap_or_else(|e| panic!("{}: {e}", folder.display()));
    let mut app = crate::headless_app(&folder.join("assets"));
    app.insert_resource(Captures::default())
        .insert_resource(Studio {
            mode,
            out: out.to_path_buf(),
            lamps,
            directional,
            shots: Vec::new(),
            camera: Transform::IDENTITY,
            progress: Progress::default(),
        })
        .add_systems(PostStartup, setup)
        .add_systems(Update, capture);
    if mode.recipe() {
        readme_recipe::add(&mut app);
    }
    if mode == Mode::Split {
        app.add_plugins(crate::splitsum_bevy::CompensatedRectLights);
    }
    app.run()
}

/// The spheres and their cameras (after the recipe's `setup`, whose camera goes: the
/// spheres' cameras take its place, its lights stay). Sphere k is on render layer k + 1,
/// its camera on layers 0 (where the recipe's directional lights are) and k + 1.
#[allow(clippy::too_many_arguments)]
fn setup(
    mut commands: Commands,
    assets: Res<AssetServer>,
    mut images: ResMut<Assets<Image>>,
    mut meshes: ResMut<Assets<Mesh>>,
    mut materials: ResMut<Assets<StandardMaterial>>,
    recipe_cameras: Query<Entity, (With<Camera3d>, Without<CheckCamera>)>,
    rect_lights: Query<(&RectLight, &Transform)>,
    directional_lights: Query<&DirectionalLight>,
    mut studio: ResMut<Studio>,
) {
    let intensity = 1.0 / bevy::camera::Exposure::default().exposure();
    if studio.mode.recipe() {
        // The recipe spawned each light of sun.json, each rect light where and as bright
        // as sun.json says.
        let spawned = (
            rect_lights.iter().count(),
            directional_lights.iter().count(),
        );
        let want = (studio.lamps.len(), studio.directional);
        assert_eq!(
            spawned, want,
            "the README's recipe spawned (RectLights, DirectionalLights) {spawned:?} for sun.json's {want:?}"
        );
        for (i, lamp) in studio.lamps.iter().enumerate() {
            assert!(
                rect_lights
                    .iter()
                    .any(|(light, transform)| spawned_as(light, transform, lamp, intensity)),
                "the README's recipe spawned no RectLight as sun.json's rect light {i} (toward {:?})",
                lamp.toward
            );
        }
    }
    for camera in &recipe_cameras {
        commands.entity(camera).despawn();
    }
    let diffuse: Handle<Image> = assets.load("sky/irradiance.ktx2");
    let specular: Handle<Image> = assets.load("sky/specular.ktx2");
    studio.progress.assets = vec![diffuse.id().untyped(), specular.id().untyped()];
    let geometry = view_geometry();
    let lamp = studio.lamps[0].toward;
    let axis = Vec3::Y.cross(lamp).normalize();
    let eye = Quat::from_axis_angle(axis, CAMERA_FROM_LAMP_DEG.to_radians()) * lamp;
    studio.camera =
        Transform::from_translation(eye * geometry.sphere_distance).looking_at(Vec3::ZERO, Vec3::Y);
    let sphere = meshes.add(Sphere::new(1.0).mesh().uv(128, 64));
    for metalness in [1u8, 0] {
        for r in ROUGHNESS {
            let k = studio.shots.len();
            let layer = RenderLayers::layer(k + 1);
            commands.spawn((
                Mesh3d(sphere.clone()),
                MeshMaterial3d(materials.add(StandardMaterial {
                    base_color: Color::WHITE,
                    metallic: f32::from(metalness),
                    perceptual_roughness: r,
                    ..default()
                })),
                layer.clone(),
            ));
            let target = float_target(&mut images, SIZE);
            commands.spawn((
                check_camera(k, &target, geometry.sphere_fov, studio.camera),
                EnvironmentMapLight {
                    diffuse_map: diffuse.clone(),
                    specular_map: specular.clone(),
                    intensity,
                    ..default()
                },
                layer.with(0),
            ));
            let name = format!("{HDRI}_{}sphere_m{metalness}_r{r}", studio.mode.prefix());
            studio.shots.push((name, target));
        }
    }
}

fn capture(
    mut commands: Commands,
    assets: Res<AssetServer>,
    captures: Res<Captures>,
    mut studio: ResMut<Studio>,
    mut exit: MessageWriter<AppExit>,
) {
    let studio = &mut *studio;
    let targets = studio.shots.iter().map(|(_, t)| t);
    let label = format!("studio {}", studio.mode.name());
    if capture_round(
        &mut studio.progress,
        &assets,
        &captures,
        &mut commands,
        &mut exit,
        &label,
        targets,
    ) {
        write(studio, &captures);
        exit.write(AppExit::Success);
    }
}

/// Writes each sphere's linear floats (row 0 at the bottom) and a PNG, and in the split
/// process the camera and the lights in `results.json`.
fn write(studio: &Studio, captures: &Captures) {
    let map = captures.0.lock().unwrap();
    let row = 4 * SIZE as usize;
    for (i, (name, _)) in studio.shots.iter().enumerate() {
        let data = map[&i].last().unwrap();
        save_png(&studio.out.join(format!("{name}.png")), data, SIZE);
        let bytes: Vec<u8> = data
            .chunks_exact(row)
            .rev()
            .flatten()
            .flat_map(|v| v.to_le_bytes())
            .collect();
        let path = studio.out.join(format!("{name}.rgba32f"));
        std::fs::write(&path, bytes).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    }
    if studio.mode == Mode::Split {
        let eye = studio.camera.translation;
        let results = serde_json::json!({
            "results": {
                HDRI: {
                    "sphereCamera": {
                        "eye": [eye.x, eye.y, eye.z],
                        "fov": view_geometry().sphere_fov.to_degrees(),
                        "size": SIZE,
                    },
                    "areaLights": studio.lamps.len(),
                    "directionalLights": studio.directional,
                    "path": format!("{} RectLight(s) as the README's recipe spawns them", studio.lamps.len()),
                }
            }
        });
        let path = studio.out.join("results.json");
        std::fs::write(&path, serde_json::to_string_pretty(&results).unwrap())
            .unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    }
}
