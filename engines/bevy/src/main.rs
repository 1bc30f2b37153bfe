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
//!   direction puts it.
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
use bevy::asset::UntypedAssetId;
use bevy::camera::visibility::RenderLayers;
use bevy::camera::{Exposure, Hdr, RenderTarget};
use bevy::core_pipeline::tonemapping::Tonemapping;
use bevy::light::{EnvironmentMapLight, GlobalAmbientLight, Skybox};
use bevy::prelude::*;
use bevy::window::ExitCondition;

mod capture;
/// The helper the README's recipe points to (`bevy/splitsum_bevy.rs`).
#[path = "../../../bevy/splitsum_bevy.rs"]
mod splitsum_bevy;
mod studio;

use capture::{check_camera, float_target, save_png, Captures, CheckCamera, Progress, Step};

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

/// An equirect in splitsum's convention (u = 0.5 + atan2(z, x)/2π, v = acos(y)/π).
#[derive(Clone)]
struct Equirect {
    width: usize,
    height: usize,
    data: Vec<[f32; 3]>,
}

impl Equirect {
    fn load(path: &Path) -> Equirect {
        let img = image::open(path)
            .unwrap_or_else(|e| panic!("{}: {e}", path.display()))
            .into_rgb32f();
        Equirect {
            width: img.width() as usize,
            height: img.height() as usize,
            data: img.pixels().map(|p| p.0).collect(),
        }
    }

    /// Bilinear lookup (wrapping in u, clamped in v) of direction `d`.
    fn lookup(&self, d: Vec3) -> [f32; 3] {
        let u = 0.5 + d.z.atan2(d.x) / (2.0 * PI);
        let v = d.y.clamp(-1.0, 1.0).acos() / PI;
        let x = u * self.width as f32 - 0.5;
        let y = (v * self.height as f32 - 0.5).clamp(0.0, (self.height - 1) as f32);
        let (x0, y0) = (x.floor(), y.floor());
        let (fx, fy) = (x - x0, y - y0);
        let at = |xi: i64, yi: usize| {
            let xi = xi.rem_euclid(self.width as i64) as usize;
            self.data[yi.min(self.height - 1) * self.width + xi]
        };
        let (xi, yi) = (x0 as i64, y0 as usize);
        let mut out = [0.0; 3];
        for c in 0..3 {
            let top = at(xi, yi)[c] * (1.0 - fx) + at(xi + 1, yi)[c] * fx;
            let bottom = at(xi, yi + 1)[c] * (1.0 - fx) + at(xi + 1, yi + 1)[c] * fx;
            out[c] = top * (1.0 - fy) + bottom * fy;
        }
        out
    }

    /// Direction and solid angle of texel (x, y).
    fn texel(&self, x: usize, y: usize) -> (Vec3, f32) {
        let (t0, t1) = (
            PI * y as f32 / self.height as f32,
            PI * (y + 1) as f32 / self.height as f32,
        );
        let theta = 0.5 * (t0 + t1);
        let phi = 2.0 * PI * ((x as f32 + 0.5) / self.width as f32 - 0.5);
        let omega = 2.0 * PI / self.width as f32 * (t0.cos() - t1.cos());
        (
            Vec3::new(
                theta.sin() * phi.cos(),
                theta.cos(),
                theta.sin() * phi.sin(),
            ),
            omega,
        )
    }

    /// The sun: luminance-weighted mean direction of the texels above half the maximum.
    fn sun(&self) -> Vec3 {
        let max = self.data.iter().map(|&p| luminance(p)).fold(0.0, f32::max);
        let mut d = Vec3::ZERO;
        for y in 0..self.height {
            for x in 0..self.width {
                let l = luminance(self.data[y * self.width + x]);
                if l >= 0.5 * max {
                    let (dir, omega) = self.texel(x, y);
                    d += dir * l * omega;
                }
            }
        }
        d.normalize()
    }

    /// The solid-angle-weighted box reduction by `k` in each axis (energy kept).
    fn reduce(&self, k: usize) -> Equirect {
        let (w, h) = (self.width / k, self.height / k);
        let mut data = vec![[0.0; 3]; w * h];
        for y in 0..h {
            for x in 0..w {
                let (mut sum, mut weight) = ([0.0f32; 3], 0.0);
                for yy in y * k..(y + 1) * k {
                    let omega = self.texel(0, yy).1;
                    for xx in x * k..(x + 1) * k {
                        let p = self.data[yy * self.width + xx];
                        for c in 0..3 {
                            sum[c] += p[c] * omega;
                        }
                        weight += omega;
                    }
                }
                data[y * w + x] = sum.map(|s| s / weight);
            }
        }
        Equirect {
            width: w,
            height: h,
            data,
        }
    }

    /// E(n)/π, the cosine-weighted sum over every texel.
    fn irradiance_over_pi(&self, n: Vec3) -> [f32; 3] {
        let mut e = [0.0f32; 3];
        for y in 0..self.height {
            for x in 0..self.width {
                let (d, omega) = self.texel(x, y);
                let c = n.dot(d);
                if c > 0.0 {
                    let p = self.data[y * self.width + x];
                    for k in 0..3 {
                        e[k] += p[k] * c * omega;
                    }
                }
            }
        }
        e.map(|v| v / PI)
    }
}

fn luminance(p: [f32; 3]) -> f32 {
    0.2126 * p[0] + 0.7152 * p[1] + 0.0722 * p[2]
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

/// The sun of a `--sun split` bake's sun.json: toward the sun, in Bevy's world, and E.
#[derive(Clone, Copy)]
struct SunLight {
    direction: Vec3,
    irradiance: Vec3,
}

impl SunLight {
    fn read(path: &Path) -> SunLight {
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
    fn bundle(&self, intensity: f32, shadows: bool) -> (DirectionalLight, Transform) {
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

/// The sun case's scene and cameras. Render layers keep it apart from the other shots and
/// give each light only the views it belongs to (Bevy skips a directional light in a view
/// whose layers it does not share, and casts its shadows from the meshes it shares a layer
/// with): 3 the diffuse sphere, seen by both sphere cameras; 4 the sun's light, in the
/// split camera's layers only; 5 the floor and box, seen from above; 6 a second light of
/// the same sun, casting shadows, sharing a layer with the floor, the box and the camera
/// above.
#[allow(clippy::too_many_arguments)]
fn sun_shots(
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

/// Runs the README recipe's shell lines in `out` on the bundled `hdri`, copied there as
/// `sky.hdr`, with `splitsum` the binary under test.
fn run_recipe_commands(splitsum: &Path, out: &Path, hdri: &str) {
    std::fs::create_dir_all(out).unwrap();
    std::fs::copy(
        root().join(format!("tests/data/{hdri}.hdr")),
        out.join("sky.hdr"),
    )
    .unwrap();
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
    match check.progress.step(&assets) {
        Step::Wait => return,
        Step::Fail(e) => {
            eprintln!("error: {e}");
            exit.write(AppExit::error());
            return;
        }
        Step::Capture => {}
    }
    if captures.stable(check.shots.len()) {
        let code = evaluate(&check, &captures.0.lock().unwrap());
        exit.write(AppExit::from_code(code));
        return;
    }
    captures.request(&mut commands, check.shots.iter().map(|s| &s.target));
}

/// Pixel (x, y) of an RGBA float capture.
fn pixel(data: &[f32], size: u32, x: u32, y: u32) -> [f32; 3] {
    let i = 4 * (y * size + x) as usize;
    [data[i], data[i + 1], data[i + 2]]
}

/// Centroid of the pixels above half the maximum luminance (of those `keep` accepts).
fn bright_centroid(data: &[f32], size: u32, keep: impl Fn(u32, u32) -> bool) -> (f32, f32) {
    let mut max = 0.0f32;
    for y in 0..size {
        for x in 0..size {
            if keep(x, y) {
                max = max.max(luminance(pixel(data, size, x, y)));
            }
        }
    }
    let (mut sx, mut sy, mut sw) = (0.0, 0.0, 0.0);
    for y in 0..size {
        for x in 0..size {
            let l = luminance(pixel(data, size, x, y));
            if keep(x, y) && l >= 0.5 * max {
                sx += l * x as f32;
                sy += l * y as f32;
                sw += l;
            }
        }
    }
    (sx / sw, sy / sw)
}

fn correlation(a: &[f32], b: &[f32]) -> f32 {
    let n = a.len() as f32;
    let (ma, mb) = (a.iter().sum::<f32>() / n, b.iter().sum::<f32>() / n);
    let (mut ab, mut aa, mut bb) = (0.0, 0.0, 0.0);
    for (x, y) in a.iter().zip(b) {
        ab += (x - ma) * (y - mb);
        aa += (x - ma) * (x - ma);
        bb += (y - mb) * (y - mb);
    }
    ab / (aa * bb).sqrt()
}

/// Measures every shot against the HDRI, prints and writes the results; the exit code.
fn evaluate(check: &Check, captures: &HashMap<usize, Vec<Vec<f32>>>) -> u8 {
    let mut lines = Vec::new();
    let mut failed = false;
    let mut report = |ok: bool, text: String| {
        let line = format!("{} {text}", if ok { "ok  " } else { "FAIL" });
        println!("{line}");
        lines.push(line);
        failed |= !ok;
    };
    let reduced: HashMap<&str, Equirect> = check
        .equirects
        .iter()
        .map(|(k, e)| (*k, e.reduce(4)))
        .collect();
    for (i, shot) in check.shots.iter().enumerate() {
        let data = captures[&i].last().unwrap();
        let e = &check.equirects[shot.hdri];
        let n = shot.size;
        save_png(&check.out.join(format!("{}.png", shot.name())), data, n);
        let label = format!("{} {}", shot.hdri, shot.format);
        match shot.view {
            View::Sky => {
                let mut want = vec![0.0f32; data.len()];
                let mut diff = 0.0;
                for y in 0..n {
                    for x in 0..n {
                        let w = e.lookup(shot.ray(x as f32, y as f32));
                        let g = pixel(data, n, x, y);
                        let k = 4 * (y * n + x) as usize;
                        want[k..k + 3].copy_from_slice(&w);
                        for c in 0..3 {
                            diff += ((1.0 + g[c]).ln() - (1.0 + w[c]).ln()).abs();
                        }
                    }
                }
                diff /= (3 * n * n) as f32;
                save_png(
                    &check.out.join(format!("{}_equirect.png", shot.name())),
                    &want,
                    n,
                );
                let (gx, gy) = bright_centroid(data, n, |_, _| true);
                let (wx, wy) = bright_centroid(&want, n, |_, _| true);
                let angle = shot
                    .ray(gx, gy)
                    .angle_between(shot.ray(wx, wy))
                    .to_degrees();
                report(
                    angle <= SUN_DEGREES && diff <= SKY_LOG_DIFF,
                    format!("{label}: skybox sun {angle:.2}° from the equirect lookup's (bar {SUN_DEGREES}°), mean |Δ ln(1+L)| {diff:.4} (bar {SKY_LOG_DIFF})"),
                );
            }
            View::Mirror => {
                let on = |x: u32, y: u32| {
                    shot.sphere_hit(x as f32, y as f32)
                        .is_some_and(|(p, d)| -d.dot(p) > 0.2)
                };
                let (cx, cy) = bright_centroid(data, n, on);
                let reflected = shot
                    .sphere_hit(cx, cy)
                    .map(|(p, d)| d - 2.0 * d.dot(p) * p)
                    .unwrap_or(Vec3::ZERO);
                let angle = reflected.angle_between(check.suns[shot.hdri]).to_degrees();
                report(
                    angle <= SUN_DEGREES,
                    format!("{label}: mirror sphere reflects the sun {angle:.2}° from the HDRI's sun (bar {SUN_DEGREES}°)"),
                );
            }
            // Measured together in evaluate_sun.
            View::SunFull | View::SunSplit | View::SunShadow => {}
            View::Rough => {
                let r = &reduced[shot.hdri];
                let (mut got, mut want) = (Vec::new(), Vec::new());
                for y in 0..n {
                    for x in 0..n {
                        if let Some((p, d)) = shot.sphere_hit(x as f32, y as f32) {
                            // Away from the silhouette, where a pixel straddles the edge.
                            if -d.dot(p) > 0.2 {
                                got.push(luminance(pixel(data, n, x, y)));
                                want.push(luminance(r.irradiance_over_pi(p)));
                            }
                        }
                    }
                }
                let ratio = got.iter().sum::<f32>() / want.iter().sum::<f32>();
                let corr = correlation(&got, &want);
                report(
                    (ratio - 1.0).abs() <= DIFFUSE_BRIGHTNESS && corr >= DIFFUSE_CORRELATION,
                    format!(
                        "{label}: white dielectric r = 1 is {:+.2} % from E/π (bar {:.0} %), correlation {corr:.4} (bar {DIFFUSE_CORRELATION}), {} pixels",
                        100.0 * (ratio - 1.0),
                        100.0 * DIFFUSE_BRIGHTNESS,
                        got.len()
                    ),
                );
            }
        }
    }
    evaluate_sun(check, captures, &reduced[SUN_HDRI], &mut report);
    let text = lines.join("\n") + "\n";
    std::fs::write(check.out.join("results.txt"), text).unwrap();
    println!("renders and results.txt in {}", check.out.display());
    u8::from(failed)
}

/// The sun case: the diffuse sphere's sides (the split render against the full one, and
/// each against E/π of the HDRI, `reduced`), sun.json's direction against the HDRI's own
/// sun, and the box's shadow.
fn evaluate_sun(
    check: &Check,
    captures: &HashMap<usize, Vec<Vec<f32>>>,
    reduced: &Equirect,
    report: &mut impl FnMut(bool, String),
) {
    let shot_of = |view: View| {
        let i = check
            .shots
            .iter()
            .position(|s| s.view == view)
            .expect("the sun shots");
        (&check.shots[i], captures[&i].last().unwrap())
    };
    let toward = check.sun_light.direction;
    let angle = toward.angle_between(check.suns[SUN_HDRI]).to_degrees();
    report(
        angle <= SUN_DEGREES,
        format!("{SUN_HDRI} {SUN_LABEL}: sun.json's direction {angle:.2}° from the HDRI's sun (bar {SUN_DEGREES}°)"),
    );
    // Mean luminance on the lit and the shaded side: the render's, and E/π's.
    let sides = |view: View| {
        let (shot, data) = shot_of(view);
        let n = shot.size;
        let (mut lit, mut shaded) = ([0.0f64; 3], [0.0f64; 3]);
        for y in 0..n {
            for x in 0..n {
                let Some((p, d)) = shot.sphere_hit(x as f32, y as f32) else {
                    continue;
                };
                if -d.dot(p) <= 0.2 {
                    continue;
                }
                let c = p.dot(toward);
                let side = match c {
                    c if c >= SUN_SIDE_EDGE => &mut lit,
                    c if c <= -SUN_SIDE_EDGE => &mut shaded,
                    _ => continue,
                };
                side[0] += luminance(pixel(data, n, x, y)) as f64;
                side[1] += luminance(reduced.irradiance_over_pi(p)) as f64;
                side[2] += 1.0;
            }
        }
        (lit, shaded)
    };
    let (full_lit, full_shaded) = sides(View::SunFull);
    let (split_lit, split_shaded) = sides(View::SunSplit);
    let pc = |a: f64, b: f64| 100.0 * (a / b - 1.0);
    let lit = split_lit[0] / full_lit[0];
    let shaded = split_shaded[0] / full_shaded[0];
    report(
        (lit as f32 - 1.0).abs() <= SUN_SIDES && (shaded as f32 - 1.0).abs() <= SUN_SIDES,
        format!(
            "{SUN_HDRI} {SUN_LABEL}: diffuse sphere under the residual IBL + DirectionalLight against the full IBL: lit side {:+.2} % ({} pixels), shaded side {:+.2} % ({} pixels) (bar {:.0} %); against E/π of the HDRI: split {:+.2} / {:+.2} %, full {:+.2} / {:+.2} %",
            100.0 * (lit - 1.0),
            split_lit[2],
            100.0 * (shaded - 1.0),
            split_shaded[2],
            100.0 * SUN_SIDES,
            pc(split_lit[0], split_lit[1]),
            pc(split_shaded[0], split_shaded[1]),
            pc(full_lit[0], full_lit[1]),
            pc(full_shaded[0], full_shaded[1]),
        ),
    );

    // The shadow: the floor's pixels darker than half the lit floor's median, their
    // centroid on the floor against the shadow of the box's centre (the shadow of a
    // centrally symmetric solid is centrally symmetric about it).
    let (shot, data) = shot_of(View::SunShadow);
    let n = shot.size;
    let lums: Vec<f32> = (0..n * n)
        .map(|i| luminance(pixel(data, n, i % n, i / n)))
        .collect();
    let mut lit: Vec<f32> = lums.iter().copied().filter(|&l| l > 0.0).collect();
    lit.sort_by(f32::total_cmp);
    let median = lit.get(lit.len() / 2).copied().unwrap_or(0.0);
    let (mut sum, mut count) = (Vec2::ZERO, 0u32);
    for y in 0..n {
        for x in 0..n {
            if lums[(y * n + x) as usize] < 0.5 * median {
                let d = shot.ray(x as f32, y as f32);
                let o = shot.transform.translation;
                let floor = o + d * (-o.y / d.y);
                sum += Vec2::new(floor.x, floor.z);
                count += 1;
            }
        }
    }
    let centre = sum / count.max(1) as f32;
    let expected = Vec2::new(-toward.x, -toward.z) * SHADOW_HEIGHT / toward.y;
    let azimuth = |v: Vec2| v.y.atan2(v.x).to_degrees();
    let mut error = (azimuth(centre) - azimuth(expected)).abs();
    error = error.min(360.0 - error);
    report(
        count > 100 && error <= SHADOW_DEGREES,
        format!(
            "{SUN_HDRI} {SUN_LABEL}: the box's shadow at azimuth {:.2}°, where the sun puts it {:.2}° ({error:.2}°, bar {SHADOW_DEGREES}°; {count} pixels)",
            azimuth(centre),
            azimuth(expected)
        ),
    );
}
