//! `splitsum inspect`: what is in an environment (size, radiance, bad texels, the sun and
//! further compact lights), for a person or, with `--json`, for a script.

use splitsum::{BakeOptions, Baker, MIN_SUN_SHARE};

use super::args::InspectArgs;
use super::for_user;
use super::shared::warn;

/// `splitsum inspect`.
pub fn inspect(args: InspectArgs) -> anyhow::Result<()> {
    let opts = BakeOptions {
        rotate_degrees: args.input_opts.rotate,
        exposure_ev: args.input_opts.exposure,
        backend: splitsum::BackendChoice::Cpu,
        ..BakeOptions::default()
    };
    let baker = Baker::new(opts).map_err(|e| for_user("inspect", e))?;
    let loaded = baker.load(&args.input, None)?;
    let inventory = splitsum::inventory(&loaded.env);
    let lights: Vec<splitsum::Sun> = splitsum::find_lights(&loaded.env)
        .into_iter()
        .map(|s| s.rotated(args.input_opts.rotate))
        .collect();
    let sources: Vec<splitsum::Source> = splitsum::find_sources(&loaded.env)
        .into_iter()
        .map(|s| s.rotated(args.input_opts.rotate))
        .collect();
    let source_out = |s: &splitsum::Source| SourceOut {
        source: *s,
        illuminance: s.illuminance(),
        azimuth_deg: s.azimuth_deg(),
        elevation_deg: s.elevation_deg(),
    };
    let light_out = |sun: &splitsum::Sun| LightOut {
        sun: *sun,
        illuminance: sun.illuminance(),
        azimuth_deg: sun.azimuth_deg(),
        elevation_deg: sun.elevation_deg(),
    };
    if args.json {
        #[derive(serde::Serialize)]
        struct Out<'a> {
            input: String,
            #[serde(flatten)]
            inventory: &'a splitsum::Inventory,
            sun: Option<LightOut>,
            additional_lights: Vec<LightOut>,
            sources: Vec<SourceOut>,
            warnings: &'a [String],
        }
        let out = Out {
            input: args.input.display().to_string(),
            inventory: &inventory,
            sun: lights.first().map(light_out),
            additional_lights: lights.iter().skip(1).map(light_out).collect(),
            sources: sources.iter().map(source_out).collect(),
            warnings: &loaded.warnings,
        };
        println!("{}", serde_json::to_string_pretty(&out)?);
        return Ok(());
    }
    warn(loaded.warnings);
    let i = &inventory;
    println!("{}", args.input.display());
    match i.layout {
        "cube" => println!("  size          cube, 6 × {0}×{0} texels", i.width),
        _ => println!("  size          {}×{} {}", i.width, i.height, i.layout),
    }
    println!(
        "  mean          {:.4} (R {:.4}, G {:.4}, B {:.4}); peak {:.4}",
        i.mean_luminance, i.mean[0], i.mean[1], i.mean[2], i.peak_luminance
    );
    println!("  dynamic range {}", dynamic_range(i));
    if i.non_finite + i.negative > 0 {
        println!(
            "  bad texels    {} non-finite, {} negative",
            i.non_finite, i.negative
        );
    }
    if lights.is_empty() {
        println!(
            "  sun           none (no compact source holds {:.0} % of the light)",
            100.0 * MIN_SUN_SHARE
        );
    }
    for (k, s) in lights.iter().enumerate() {
        let label = match (k, s.shape) {
            (0, None) => "sun".to_string(),
            (_, None) => format!("light {}", k + 1),
            (_, Some(_)) => format!("light {} area", k + 1),
        };
        println!(
            "  {label:<14}azimuth {:.2}°, elevation {:.2}°, direction ({:.5}, {:.5}, {:.5})",
            s.azimuth_deg(),
            s.elevation_deg(),
            s.direction[0],
            s.direction[1],
            s.direction[2]
        );
        println!(
            "                irradiance E (facing it) {:.4} (R {:.4}, G {:.4}, B {:.4}), {:.1} % of the light",
            s.illuminance(),
            s.irradiance[0],
            s.irradiance[1],
            s.irradiance[2],
            100.0 * s.share
        );
        if let Some(shape) = s.shape {
            println!("                {shape}: shaded as an area light with --sun split");
        }
        println!(
            "                angular radius {:.3}°, solid angle {:.3e} sr, {} texels{}",
            s.angular_radius_deg,
            s.solid_angle_sr,
            s.texels,
            if s.clipped {
                "; clipped (its core is a plateau: the camera saturated, so E is a lower bound)"
            } else {
                ""
            }
        );
    }
    if sources.is_empty() {
        println!(
            "  area sources  none (no connected bright region holds {:.0} % of the light)",
            100.0 * MIN_SUN_SHARE
        );
    }
    for (k, s) in sources.iter().enumerate() {
        println!(
            "  {:<14}{}, azimuth {:.2}°, elevation {:.2}°, {:.1} % of the light, E {:.4}",
            format!("source {}", k + 1),
            s.shape,
            s.azimuth_deg(),
            s.elevation_deg(),
            100.0 * s.share,
            s.illuminance()
        );
        println!(
            "                solid angle {:.3e} sr, {} texels; the uniform shape leaves {:.1} % of its light",
            s.solid_angle_sr,
            s.texels,
            100.0 * s.shape_residual
        );
    }
    Ok(())
}

/// The dynamic range in words: the ratio and what it is over, or, where the darkest
/// percentile is black and a ratio has no finite value, the peak on black; then how much of
/// the sphere is black.
fn dynamic_range(i: &splitsum::Inventory) -> String {
    let over = format!("{} percentile by solid angle", ordinal(i.low_percentile));
    let range = if i.peak_luminance == 0.0 {
        "none (every texel is black)".to_string()
    } else if i.dynamic_range > 0.0 {
        format!(
            "{:.1e} (peak over the {over}, {:.4})",
            i.dynamic_range, i.low_luminance
        )
    } else {
        format!("peak {:.4} on black (the {over} is 0)", i.peak_luminance)
    };
    match i.black_fraction {
        f if f > 0.0 => format!("{range}; {} of the sphere black", percent(f)),
        _ => range,
    }
}

/// "1st", "2nd", "3rd", "4th" … for a whole number, the number itself otherwise.
fn ordinal(x: f32) -> String {
    const TEENS: std::ops::RangeInclusive<u32> = 11..=13;
    const DECIMAL: u32 = 10;
    const HUNDRED: u32 = 100;
    if x.fract() != 0.0 || x < 0.0 {
        return format!("{x}");
    }
    let n = x as u32;
    let suffix = match (n % DECIMAL, TEENS.contains(&(n % HUNDRED))) {
        (1, false) => "st",
        (2, false) => "nd",
        (3, false) => "rd",
        _ => "th",
    };
    format!("{n}{suffix}")
}

/// A share (0 to 1) as a percentage to a tenth, never rounded to 0 or 100 where it is not.
fn percent(share: f32) -> String {
    const TENTH: f32 = 0.1;
    const WHOLE: f32 = 100.0;
    let p = WHOLE * share;
    match p {
        p if p > 0.0 && p < TENTH => format!("under {TENTH} %"),
        p if p < WHOLE && p > WHOLE - TENTH => format!("over {} %", WHOLE - TENTH),
        p => format!("{p:.1} %"),
    }
}

/// An area source as `inspect --json` writes it: its figures with its illuminance,
/// azimuth and elevation.
#[derive(serde::Serialize)]
struct SourceOut {
    #[serde(flatten)]
    source: splitsum::Source,
    illuminance: f32,
    azimuth_deg: f32,
    elevation_deg: f32,
}

/// A light as `inspect --json` writes it: its figures with its illuminance, azimuth and
/// elevation.
#[derive(serde::Serialize)]
struct LightOut {
    #[serde(flatten)]
    sun: splitsum::Sun,
    illuminance: f32,
    azimuth_deg: f32,
    elevation_deg: f32,
}
