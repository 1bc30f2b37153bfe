//! The lookup study: where should a shader read the prefiltered chain? For each bundled
//! HDRI, with the sun kept and split (`--sun`), and the environment turned to four azimuths
//! (four views of it), the preview's spheres are shaded with each
//! [`SpecularLookup`] and compared with the preview's ground truth (the full reflectance
//! integral, which does not depend on the lookup), sphere by sphere: the energy-weighted
//! relative difference of the light each sends to the camera (`preview --json`'s `mean`).
//! Prints a Markdown table per HDRI and mode: for each lookup and roughness, the mean over
//! the six materials and four views, and the worst sphere.
//!
//! `cargo run --release --example lookup_study [-- CELL TRUTH_SAMPLES]` (defaults 32 and
//! 1024: a quarter of the preview's pixels and half its points, enough for figures to the
//! tenth of a per cent); docs/accuracy.md holds its output.

use splitsum::backend::CpuBackend;
use splitsum::bake::{bake_environment, BakeOptions};
use splitsum::cpu::preview_split_sum::render_split_sum_along;
use splitsum::math::lookup::SpecularLookup;
use splitsum::plan::scene::{material_table, Scene, SplitSumInputs, SplitSumLight, ROUGHNESS};
use splitsum::stages::preview::{
    add_sun_light, column_table, compare, render_preview, BakedLight, PreviewOptions,
};
use splitsum::SunMode;

/// The bundled HDRIs (venice_sunset once: its EXR is the same picture).
const HDRIS: [&str; 6] = [
    "quarry_01_1k.hdr",
    "royal_esplanade_1k.hdr",
    "venice_sunset_1k.hdr",
    "pedestrian_overpass_1k.hdr",
    "studio_small_03_1k.hdr",
    "blender_studiolight_interior.exr",
];
/// The four views: the environment turned about +Y.
const AZIMUTHS: [f32; 4] = [0.0, 90.0, 180.0, 270.0];

fn main() -> Result<(), splitsum::Error> {
    let args: Vec<u32> = std::env::args()
        .skip(1)
        .filter_map(|a| a.parse().ok())
        .collect();
    let opts = PreviewOptions {
        cell: args.first().copied().unwrap_or(32),
        truth_samples: args.get(1).copied().unwrap_or(1024),
        ..PreviewOptions::default()
    };
    let cpu = CpuBackend;
    let lut = splitsum::backend::Backend::brdf_lut(&cpu, 512, 512)?;
    let scene = Scene { cell: opts.cell }.uniform();
    let materials = material_table();
    for name in HDRIS {
        let path = std::path::Path::new("tests/data").join(name);
        let env = splitsum::io::input::load_input(&path, &Default::default())?.env;
        for sun in [SunMode::Keep, SunMode::Split] {
            // errors[lookup][column]: every (material, view) sphere's figure.
            let mut errors = vec![vec![Vec::new(); ROUGHNESS.len()]; SpecularLookup::ALL.len()];
            let mut lights = 0;
            for azimuth in AZIMUTHS {
                let bake_opts = BakeOptions {
                    sun,
                    rotate_degrees: azimuth,
                    ..BakeOptions::default()
                };
                let baked =
                    bake_environment(&cpu, env.clone(), &bake_opts, &mut |_| {}, &mut Vec::new())?;
                let light = BakedLight::of(name, &baked, &lut);
                lights = light.lights.len();
                let truth = render_preview(&cpu, &light, &opts)?.truth;
                let columns = column_table(light.chain);
                for (k, lookup) in SpecularLookup::ALL.into_iter().enumerate() {
                    let inputs = SplitSumInputs {
                        light: SplitSumLight {
                            specular: light.specular,
                            irradiance: light.irradiance,
                            lut: light.lut,
                        },
                        columns: &columns,
                        materials: &materials,
                    };
                    let mut panel = render_split_sum_along(&scene, &inputs, lookup);
                    for sun in light.lights {
                        add_sun_light(&scene, &columns, &materials, sun, &mut panel);
                    }
                    for (i, s) in compare(&scene, &panel, &truth).1.iter().enumerate() {
                        errors[k][i % ROUGHNESS.len()].push(s.mean_relative);
                    }
                }
            }
            let mode = match (sun, lights) {
                (SunMode::Keep, _) => "sun kept".to_string(),
                (SunMode::Split, 0) => "split: no light found (as kept)".to_string(),
                (SunMode::Split, n) => {
                    format!("sun split ({n} light{})", if n > 1 { "s" } else { "" })
                }
            };
            println!("\n### {name}, {mode}\n");
            print!("| lookup |");
            ROUGHNESS.iter().for_each(|r| print!(" r = {r} |"));
            println!("\n|---|{}", "---|".repeat(ROUGHNESS.len()));
            for (k, lookup) in SpecularLookup::ALL.into_iter().enumerate() {
                print!("| {} |", lookup.name());
                for e in &errors[k] {
                    let mean = e.iter().sum::<f32>() / e.len() as f32;
                    let worst = e.iter().copied().fold(0.0f32, f32::max);
                    print!(" {:.1} % ({:.1}) |", 100.0 * mean, 100.0 * worst);
                }
                println!();
            }
        }
    }
    Ok(())
}
