//! The area-light study: what shading the lights `--sun split` takes out as area lights
//! buys. For each bundled HDRI with an area source (`find_sources`), the preview's spheres
//! three ways against the same ground truth (the full reflectance integral over the
//! environment as read):
//!
//! - **kept**: everything in the IBL (`--sun keep`);
//! - **directional**: the lights `--sun split` takes out (the sun-sized ones, then the
//!   area sources of what they leave) each shaded as a directional light of its E⊥;
//! - **split**: as `--sun split` shades them, the area sources from the LTC table fitted
//!   to the recipe's BRDF (`plan::ltc`), the residual through the recipe.
//!
//! Prints a Markdown table per HDRI: per roughness the metals' range and the dielectric
//! of the preview's figure (`preview --json`'s `mean`). 32-pixel cells and 1024 truth
//! points: a quarter of the preview's pixels and half its points.
//! `cargo run --release --example area_study`; docs/sun.md holds the output.

use splitsum::backend::CpuBackend;
use splitsum::bake::{bake_environment, BakeOptions};
use splitsum::plan::scene::ROUGHNESS;
use splitsum::stages::preview::{render_preview, BakedLight, PreviewOptions};
use splitsum::{find_sources, BrdfLut, Environment, SphereStats, Sun, SunMode};

const HDRIS: [&str; 6] = [
    "studio_small_03_1k.hdr",
    "blender_studiolight_studio.exr",
    "blender_studiolight_interior.exr",
    "quarry_01_1k.hdr",
    "royal_esplanade_1k.hdr",
    "venice_sunset_1k_f32_piz.exr",
];

fn bake(env: Environment, sun: SunMode) -> Result<splitsum::BakedEnvironment, splitsum::Error> {
    let opts = BakeOptions {
        sun,
        ground_truth: true,
        ..BakeOptions::default()
    };
    bake_environment(&CpuBackend, env, &opts, &mut |_| {}, &mut Vec::new())
}

/// "a–b (c)": the metals' range and the dielectric, in per cent, for roughness `r`.
fn cell(stats: &[SphereStats], r: f32) -> String {
    let at: Vec<&SphereStats> = stats.iter().filter(|s| s.roughness == r).collect();
    let metals: Vec<f32> = at
        .iter()
        .filter(|s| s.material != "dielectric")
        .map(|s| 100.0 * s.mean_relative)
        .collect();
    let lo = metals.iter().copied().fold(f32::INFINITY, f32::min);
    let hi = metals.iter().copied().fold(0.0, f32::max);
    let dielectric = at
        .iter()
        .find(|s| s.material == "dielectric")
        .map_or(0.0, |s| 100.0 * s.mean_relative);
    format!("{lo:.1}–{hi:.1} ({dielectric:.2})")
}

fn main() -> Result<(), splitsum::Error> {
    let cpu = CpuBackend;
    let lut: BrdfLut = splitsum::backend::Backend::brdf_lut(&cpu, 512, 512)?;
    let opts = PreviewOptions {
        cell: 32,
        truth_samples: 1024,
        ..PreviewOptions::default()
    };
    for name in HDRIS {
        let path = std::path::Path::new("tests/data").join(name);
        let env = splitsum::io::input::load_input(&path, &Default::default())?.env;
        let sources = find_sources(&env);
        if sources.is_empty() {
            continue;
        }
        let kept = bake(env.clone(), SunMode::Keep)?;
        let split = bake(env, SunMode::Split)?;
        let directional: Vec<Sun> = split
            .split_lights()
            .iter()
            .map(|l| Sun { shape: None, ..*l })
            .collect();
        let rows = [
            ("kept", BakedLight::of(name, &kept, &lut)),
            (
                "directional",
                BakedLight {
                    lights: &directional,
                    ..BakedLight::of(name, &split, &lut)
                },
            ),
            ("split", BakedLight::of(name, &split, &lut)),
        ];
        println!(
            "\n#### {name}: {} light(s) split\n",
            split.split_lights().len()
        );
        for l in split.split_lights() {
            let shape = l.shape.map_or(
                format!("sun-sized, radius {:.2}°", l.angular_radius_deg),
                |s| s.to_string(),
            );
            println!("- {shape}, {:.1} % of the light", 100.0 * l.share);
        }
        print!("\n| | ");
        ROUGHNESS[1..].iter().for_each(|r| print!("r = {r} | "));
        println!("\n|---|{}", "---|".repeat(ROUGHNESS.len() - 1));
        for (what, light) in rows {
            let p = render_preview(&cpu, &light, &opts)?;
            print!("| {what} | ");
            ROUGHNESS[1..]
                .iter()
                .for_each(|&r| print!("{} | ", cell(&p.stats, r)));
            println!();
        }
    }
    Ok(())
}
