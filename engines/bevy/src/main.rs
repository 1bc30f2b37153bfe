//! The Bevy engine check: bakes the bundled HDRIs with `splitsum bake --target bevy` (and a
//! 1024² skybox with `splitsum cubemap --target bevy`) in rgb9e5 + zstd, rgba16f and
//! rg11b10f, renders them headless with Bevy's own `EnvironmentMapLight` and `Skybox`
//! (lavapipe or any Vulkan adapter, into float image targets read back with Bevy's
//! screenshot API), and compares against the HDRI itself:
//!
//! - the skybox, looking at the sun, against a direct bilinear equirect lookup of each
//!   pixel's ray (mean |Δ ln(1 + L)|) and the sun's direction in both;
//! - a mirror sphere (metallic, roughness 0): the sun's reflected direction against the
//!   HDRI's sun;
//! - a white dielectric sphere at roughness 1 against E/π at each pixel's normal (a
//!   brute-force cosine sum over the HDRI box-reduced to 256×128, energy kept): Bevy's
//!   diffuse plus specular of a white rough dielectric sums to E/π when the roughest
//!   specular level is E/π, as splitsum bakes it.
//!
//! Bevy's default exposure (EV100 9.7) and `intensity = brightness = 1 / exposure`
//! (≈ 998, the README's advice) give radiance on screen as in the HDRI.
//!
//! - the sun as a light: quarry_01 baked with `--sun split`, its sun.json as a
//!   `DirectionalLight` (illuminance max(E) × the `EnvironmentMapLight` intensity, colour
//!   E / max(E)); a white Lambertian sphere (reflectance 0) under the residual IBL plus the
//!   light against the full IBL, on its lit and shaded sides, and a unit box above a floor
//!   lit by the light alone with its shadows, seen from above: the shadow where the sun's
//!   direction puts it;
//! - a studio's lamps as `RectLight`s (`studio.rs`): studio_small_03 baked and lit by the
//!   README's recipe, its spheres written as floats for tests/engine_renders.rs, which holds
//!   them against the truth.
//!
//! The README's Bevy recipe runs as written (`build.rs` copies it into the check): its
//! shell lines bake the bundled venice_sunset HDRI as `sky.hdr`, its `setup` spawns its
//! camera, and that camera, given an image target, the rough sphere's view and layer, is
//! held to the rough sphere's bars.
//!
//! Run from the repository root after `cargo build --release`:
//! `cargo run --manifest-path engines/bevy/Cargo.toml` (SPLITSUM names another binary;
//! SPLITSUM_TARGET=generic bakes without the target, the negative control: the check then
//! fails, the sun off by tens of degrees).
//! Writes renders (PNG, Reinhard-mapped) and results.txt to target/engines/bevy/; exits 1
//! when a bar is missed.

use std::collections::HashMap;
use std::f32::consts::PI;
use std::path::{Path, PathBuf};
use std::process::Command;
use std::time::Duration;

use bevy::app::ScheduleRunnerPlugin;
use bevy::camera::visibility::RenderLayers;
use bevy::camera::{Exposure, Hdr, RenderTarget};
use bevy::core_pipeline::tonemapping::Tonemapping;
use bevy::light::{EnvironmentMapLight, GlobalAmbientLight, Skybox};
use bevy::prelude::*;
use bevy::window::ExitCondition;

mod capture;
mod equirect;
mod evaluate;
/// The helper the README's recipe points to (`bevy/splitsum_bevy.rs`).
#[path = "../../../bevy/splitsum_bevy.rs"]
mod splitsum_bevy;
mod studio;
mod sun;

use capture::{capture_round, check_camera, float_target, Captures, CheckCamera, Progress};
use equirect::Equirect;
use evaluate::evaluate;
use sun::{sun_shots, SunLight};

/// The README's Bevy recipe (`build.rs`).
mod readme_recipe {
    include!(concat!(env!("OUT_DIR"), "/readme_recipe.rs"));
}

/// The HDRI the README's recipe bakes (as `sky.hdr`), and the label of its shot.
const RECIPE_HDRI: &str = "venice_sunset_1k";
const RECIPE_LABEL: &str = "readme_recipe";

/// The bars: sun within 1°, skybox mean |Δ ln(1 + L)| ≤ 0.01, the rough sphere
/// within 2 % of E/π in mean with correlation ≥ 0.99.
const SUN_DEGREES: f32 = 1.0;
const SKY_LOG_DIFF: f32 = 0.01;
const DIFFUSE_BRIGHTNESS: f32 = 0.02;
const DIFFUSE_CORRELATION: f32 = 0.99;
/// The sun bars (docs/engines.md, "Bevy"): the diffuse sphere under the residual IBL plus
/// the light within 3 % of the full IBL on its lit side (n·s ≥ SUN_SIDE_EDGE) and its
/// shaded side (n·s ≤ −SUN_SIDE_EDGE; the pixels near the terminator, where a light and a
/// blurred lobe differ most in shape, are left out), the shadow's centre within 2° of the
/// azimuth the sun puts it at.
const SUN_SIDES: f32 = 0.03;
const SUN_SIDE_EDGE: f32 = 0.2;
const SHADOW_DEGREES: f32 = 2.0;
/// The HDRI the sun case bakes with `--sun split`, and the label of its shots.
const SUN_HDRI: &str = "quarry_01_1k";
const SUN_LABEL: &str = "sun_split";
/// The shadow scene: a unit box centred SHADOW_HEIGHT above the floor y = 0, seen from
/// SHADOW_CAMERA_HEIGHT straight above, ±SHADOW_EXTENT of floor in view.
const SHADOW_HEIGHT: f32 = 1.0;
const SHADOW_EXTENT: f32 = 10.0;
const SHADOW_CAMERA_HEIGHT: f32 = 40.0;

const HDRIS: [&str; 2] = ["quarry_01_1k", "venice_sunset_1k"];
/// (pixel format, extra bake arguments): the target's default and the others Bevy reads:
/// BC6H (`Bc6hRgbUfloat`, with the device's TEXTURE_COMPRESSION_BC, which lavapipe has).
const FORMATS: [(&str, &[&str]); 4] = [
    ("rgb9e5_zstd", &[]),
    ("rgba16f", &["--pixel-format", "rgba16f"]),
    ("rg11b10f", &["--pixel-format", "rg11b10f"]),
    ("bc6h_zstd", &["--pixel-format", "bc6h"]),
];
/// The views' geometry, the same as the browser checks': SIZE² images (MIRROR_SIZE² for the
/// mirror sphere, one pixel of which turns the reflected direction by twice the normal's
/// change), spheres seen from SPHERE_DISTANCE with a SPHERE_FOV° vertical field of view,
/// the sky in SKY_FOV° views.
struct ViewGeometry {
    size: u32,
    mirror_size: u32,
    sphere_distance: f32,
    /// Radians.
    sphere_fov: f32,
    /// Radians.
    sky_fov: f32,
}

/// [`ViewGeometry`] as `engines/measure.js` (the browser checks' module) defines it, read
/// from its `export const NAME = value;` lines so that the numbers live in one place.
fn view_geometry() -> ViewGeometry {
    const MEASURE_JS: &str = include_str!("../../measure.js");
    let number = |name: &str| -> f32 {
        let key = format!("export const {name} = ");
        MEASURE_JS
            .lines()
            .find_map(|l| l.strip_prefix(key.as_str()))
            .and_then(|v| v.trim().trim_end_matches(';').parse().ok())
            .unwrap_or_else(|| panic!("engines/measure.js has no number {name}"))
    };
    ViewGeometry {
        size: number("SIZE") as u32,
        mirror_size: number("MIRROR_SIZE") as u32,
        sphere_distance: number("SPHERE_DISTANCE"),
        sphere_fov: number("SPHERE_FOV") * PI / 180.0,
        sky_fov: number("SKY_FOV") * PI / 180.0,
    }
}

/// What one camera renders.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
enum View {
    Sky,
    Mirror,
    Rough,
    /// The diffuse sphere under the full IBL (the sun kept).
    SunFull,
    /// The diffuse sphere under the residual IBL and the sun's light.
    SunSplit,
    /// The box above the floor, the sun's light alone, from above.
    SunShadow,
}

/// One camera of the scene: which bake it shows, how, and where it looks from.
#[derive(Clone)]
struct Shot {
    hdri: &'static str,
    format: &'static str,
    view: View,
    size: u32,
    transform: Transform,
    fov: f32,
    target: Handle<Image>,
}

impl Shot {
    fn name(&self) -> String {
        format!("{}_{}_{:?}", self.hdri, self.format, self.view).to_lowercase()
    }

    /// The world ray through the centre of pixel (x, y), row 0 at the top.
    fn ray(&self, x: f32, y: f32) -> Vec3 {
        let t = (0.5 * self.fov).tan();
        let ndc_x = 2.0 * (x + 0.5) / self.size as f32 - 1.0;
        let ndc_y = 1.0 - 2.0 * (y + 0.5) / self.size as f32;
        (self.transform.rotation * Vec3::new(ndc_x * t, ndc_y * t, -1.0)).normalize()
    }

    /// Where the ray through pixel (x, y) meets the unit sphere at the origin, if it does.
    fn sphere_hit(&self, x: f32, y: f32) -> Option<(Vec3, Vec3)> {
        let o = self.transform.translation;
        let d = self.ray(x, y);
        let b = o.dot(d);
        let disc = b * b - (o.length_squared() - 1.0);
        (disc > 0.0).then(|| (o + d * (-b - disc.sqrt()), d))
    }
}

#[derive(Resource)]
struct Check {
    shots: Vec<Shot>,
    progress: Progress,
    out: PathBuf,
    equirects: HashMap<&'static str, Equirect>,
    /// Each HDRI's sun ([`Equirect::sun`]), found once.
    suns: HashMap<&'static str, Vec3>,
    /// The sun of the split bake's sun.json.
    sun_light: SunLight,
}

fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..")
}

fn run(cmd: &mut Command) {
    let status = cmd.status().unwrap_or_else(|e| panic!("{cmd:?}: {e}"));
    assert!(status.success(), "{cmd:?} failed");
}

fn bake_everything(splitsum: &Path, bakes: &Path) {
    let target = std::env::var("SPLITSUM_TARGET").unwrap_or_else(|_| "bevy".into());
    for (format, extra) in FORMATS {
        let dir = bakes.join(format);
        let inputs: Vec<String> = HDRIS
            .iter()
            .map(|h| format!("tests/data/{h}.hdr"))
            .collect();
        run(Command::new(splitsum)
            .current_dir(root())
            .arg("bake")
            .args(&inputs)
            .args(["--target", &target, "-q", "--no-sh", "--no-lut", "-o"])
            .arg(&dir)
            .args(extra));
        for h in HDRIS {
            run(Command::new(splitsum)
                .current_dir(root())
                .args([
                    "cubemap",
                    &format!("tests/data/{h}.hdr"),
                    "--target",
                    &target,
                ])
                .args(["--size", "1024", "-o"])
                .arg(dir.join(format!("{h}_sky.ktx2")))
                .args(extra));
        }
    }
}

/// Bakes [`SUN_HDRI`] with `--sun split` into `bakes/split/`.
fn bake_split(splitsum: &Path, bakes: &Path) {
    run(Command::new(splitsum)
        .current_dir(root())
        .args([
            "bake",
            &format!("tests/data/{SUN_HDRI}.hdr"),
            "--target",
            "bevy",
            "--sun",
            "split",
        ])
        .args(["-q", "--no-sh", "--no-lut", "-o"])
        .arg(bakes.join("split")));
}

fn main() -> AppExit {
    let root = root();
    let out = root.join("target/engines/bevy");
    let args: Vec<String> = std::env::args().skip(1).collect();
    if let [command, mode] = args.as_slice() {
        if command == "studio" {
            return studio::main(mode, &out);
        }
    }
    // The asset folder: the README's recipe writes `assets/sky/` in `out`, the check's
    // bakes go beside it.
    let bakes = out.join("assets");
    let splitsum = std::env::var_os("SPLITSUM")
        .map(PathBuf::from)
        .unwrap_or_else(|| root.join("target/release/splitsum"));
    assert!(
        splitsum.exists(),
        "{} not found: build splitsum first (cargo build --release) or set SPLITSUM",
        splitsum.display()
    );
    std::fs::create_dir_all(&out).unwrap();
    bake_everything(&splitsum, &bakes);
    bake_split(&splitsum, &bakes);
    studio::bake(&splitsum, &out);
    let sun_light = SunLight::read(&bakes.join(format!("split/{SUN_HDRI}/sun.json")));
    run_recipe_commands(&splitsum, &out, RECIPE_HDRI);
    let equirects: HashMap<&'static str, Equirect> = HDRIS
        .iter()
        .map(|&h| (h, Equirect::load(&root.join(format!("tests/data/{h}.hdr")))))
        .collect();
    let suns = equirects.iter().map(|(&h, e)| (h, e.sun())).collect();

    let mut app = headless_app(&bakes);
    app.insert_resource(Captures::default())
        .insert_resource(Check {
            shots: Vec::new(),
            progress: Progress::default(),
            out: out.clone(),
            equirects,
            suns,
            sun_light,
        })
        .add_systems(Startup, setup)
        .add_systems(PostStartup, aim_recipe_camera)
        .add_systems(Update, capture);
    readme_recipe::add(&mut app);
    let checked = app.run();
    // The studio's RectLights would light every view above: its renders come from processes
    // of their own.
    let studio = studio::render_all(&out);
    if checked.is_success() && studio {
        AppExit::Success
    } else {
        AppExit::error()
    }
}

/// A windowless Bevy app reading its assets from `assets`, with no ambient light.
fn headless_app(assets: &Path) -> App {
    let mut app = App::new();
    app.add_plugins(
        DefaultPlugins
            .set(WindowPlugin {
                primary_window: None,
                exit_condition: ExitCondition::DontExit,
                ..default()
            })
            .set(AssetPlugin {
                file_path: assets.to_string_lossy().into_owned(),
                ..default()
            }),
    )
    .add_plugins(ScheduleRunnerPlugin::run_loop(Duration::from_millis(5)))
    .insert_resource(GlobalAmbientLight::NONE);
    app
}

fn setup(
    mut commands: Commands,
    assets: Res<AssetServer>,
    mut images: ResMut<Assets<Image>>,
    mut meshes: ResMut<Assets<Mesh>>,
    mut materials: ResMut<Assets<StandardMaterial>>,
    mut check: ResMut<Check>,
) {
    let sphere = meshes.add(Sphere::new(1.0).mesh().uv(128, 64));
    let mirror = materials.add(StandardMaterial {
        base_color: Color::WHITE,
        metallic: 1.0,
        perceptual_roughness: 0.0,
        ..default()
    });
    let rough = materials.add(StandardMaterial {
        base_color: Color::WHITE,
        metallic: 0.0,
        perceptual_roughness: 1.0,
        ..default()
    });
    // Render layer 1: the mirror sphere, 2: the rough sphere, 0 (default): nothing but
    // the skybox.
    commands.spawn((
        Mesh3d(sphere.clone()),
        MeshMaterial3d(mirror),
        RenderLayers::layer(1),
    ));
    commands.spawn((
        Mesh3d(sphere),
        MeshMaterial3d(rough),
        RenderLayers::layer(2),
    ));

    // Raw HDRI radiance at Bevy's default exposure: intensity = 1 / exposure (≈ 998).
    let intensity = 1.0 / Exposure::default().exposure();
    let mut shots = Vec::new();
    let mut handles = Vec::new();
    for hdri in HDRIS {
        let sun = check.suns[hdri];
        // The sphere cameras sit 40° from the sun so each sphere shows its lit and shaded
        // side; the sky camera is at the origin looking at the sun.
        let axis = Vec3::Y.cross(sun).normalize();
        let view_dir = Quat::from_axis_angle(axis, 40f32.to_radians()) * sun;
        for (format, _) in FORMATS {
            let specular: Handle<Image> = assets.load(format!("{format}/{hdri}/specular.ktx2"));
            let diffuse: Handle<Image> = assets.load(format!("{format}/{hdri}/irradiance.ktx2"));
            let sky: Handle<Image> = assets.load(format!("{format}/{hdri}_sky.ktx2"));
            handles.extend([
                specular.id().untyped(),
                diffuse.id().untyped(),
                sky.id().untyped(),
            ]);
            let geometry = view_geometry();
            for view in [View::Sky, View::Mirror, View::Rough] {
                let size = if view == View::Mirror {
                    geometry.mirror_size
                } else {
                    geometry.size
                };
                let target = float_target(&mut images, size);
                let (transform, fov) = match view {
                    View::Sky => (
                        Transform::IDENTITY.looking_to(sun, Vec3::Y),
                        geometry.sky_fov,
                    ),
                    _ => (
                        Transform::from_translation(view_dir * geometry.sphere_distance)
                            .looking_at(Vec3::ZERO, Vec3::Y),
                        geometry.sphere_fov,
                    ),
                };
                let mut camera = commands.spawn(check_camera(shots.len(), &target, fov, transform));
                match view {
                    View::Sky => {
                        camera.insert((
                            Skybox {
                                image: Some(sky.clone()),
                                brightness: intensity,
                                ..default()
                            },
                            RenderLayers::layer(0),
                        ));
                    }
                    // The sun views are spawned by sun_shots.
                    _ => {
                        camera.insert((
                            EnvironmentMapLight {
                                diffuse_map: diffuse.clone(),
                                specular_map: specular.clone(),
                                intensity,
                                ..default()
                            },
                            RenderLayers::layer(if view == View::Mirror { 1 } else { 2 }),
                        ));
                    }
                }
                shots.push(Shot {
                    hdri,
                    format,
                    view,
                    size,
                    transform,
                    fov,
                    target,
                });
            }
        }
    }
    sun_shots(
        &mut commands,
        &assets,
        &mut images,
        &mut meshes,
        &mut materials,
        &check,
        intensity,
        &mut shots,
        &mut handles,
    );
    check.shots = shots;
    check.progress.assets = handles;
}

/// Copies the bundled `hdri` into `dir` (made where missing) as `sky.hdr`, the name the
/// README's shell lines bake.
fn copy_as_sky(dir: &Path, hdri: &str) {
    std::fs::create_dir_all(dir).unwrap();
    let from = root().join(format!("tests/data/{hdri}.hdr"));
    std::fs::copy(&from, dir.join("sky.hdr")).unwrap_or_else(|e| panic!("{}: {e}", from.display()));
}

/// Runs the README recipe's shell lines in `out` on the bundled `hdri`, copied there as
/// `sky.hdr`, with `splitsum` the binary under test.
fn run_recipe_commands(splitsum: &Path, out: &Path, hdri: &str) {
    copy_as_sky(out, hdri);
    for command in readme_recipe::COMMANDS {
        let mut words = command.split_whitespace();
        assert_eq!(
            words.next(),
            Some("splitsum"),
            "the README's Bevy line '{command}' does not run splitsum"
        );
        run(Command::new(splitsum).current_dir(out).args(words));
    }
}

/// Gives the camera the README's recipe spawned an image target, the rough sphere's view of
/// the recipe's HDRI and its render layer, and adds it to the shots; waits for the images
/// it loads.
fn aim_recipe_camera(
    mut commands: Commands,
    cameras: Query<(Entity, &EnvironmentMapLight, &Skybox), (With<Camera3d>, Without<CheckCamera>)>,
    mut images: ResMut<Assets<Image>>,
    mut check: ResMut<Check>,
) {
    let found: Vec<_> = cameras.iter().collect();
    assert_eq!(
        found.len(),
        1,
        "the README's recipe spawns {} cameras with an EnvironmentMapLight and a Skybox, not one",
        found.len()
    );
    let (entity, light, skybox) = found[0];
    let geometry = view_geometry();
    let sun = check.suns[RECIPE_HDRI];
    let axis = Vec3::Y.cross(sun).normalize();
    let view_dir = Quat::from_axis_angle(axis, 40f32.to_radians()) * sun;
    let transform = Transform::from_translation(view_dir * geometry.sphere_distance)
        .looking_at(Vec3::ZERO, Vec3::Y);
    let size = geometry.size;
    let target = float_target(&mut images, size);
    commands.entity(entity).insert((
        Camera {
            order: check.shots.len() as isize,
            clear_color: ClearColorConfig::Custom(Color::NONE),
            ..default()
        },
        RenderTarget::Image(target.clone().into()),
        Projection::Perspective(PerspectiveProjection {
            fov: geometry.sphere_fov,
            ..default()
        }),
        transform,
        Hdr,
        Tonemapping::None,
        Msaa::Off,
        RenderLayers::layer(2),
    ));
    let mut loads = vec![
        light.diffuse_map.id().untyped(),
        light.specular_map.id().untyped(),
    ];
    loads.extend(skybox.image.as_ref().map(|i| i.id().untyped()));
    check.progress.assets.extend(loads);
    check.shots.push(Shot {
        hdri: RECIPE_HDRI,
        format: RECIPE_LABEL,
        view: View::Rough,
        size,
        transform,
        fov: geometry.sphere_fov,
        target,
    });
}

fn capture(
    mut commands: Commands,
    assets: Res<AssetServer>,
    captures: Res<Captures>,
    mut check: ResMut<Check>,
    mut exit: MessageWriter<AppExit>,
) {
    let check = &mut *check;
    let targets = check.shots.iter().map(|s| &s.target);
    let label = "the check";
    if capture_round(
        &mut check.progress,
        &assets,
        &captures,
        &mut commands,
        &mut exit,
        label,
        targets,
    ) {
        let code = evaluate(check, &captures.0.lock().unwrap());
        exit.write(AppExit::from_code(code));
    }
}
