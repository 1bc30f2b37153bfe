//! `splitsum preview` and `bake --preview`: the seed materials rendered under a bake two
//! ways, and how far apart the two are.
//!
//! - **split-sum** ([`crate::cpu::preview_split_sum`]): each sphere pixel shaded from the
//!   bake's files exactly as the README tells engines to (prefiltered specular at the
//!   documented lod blended toward the irradiance by r⁴, the LUT, irradiance × albedo ×
//!   kD);
//! - **ground truth** ([`crate::cpu::preview_truth`]): the full reflectance integral of the
//!   same BRDF per pixel, with the real view direction, over the environment as read
//!   ([`BakedEnvironment::seen`]: lights included, at the input's own resolution): the
//!   same truth whatever the sun mode, so a light taken out wrongly (moved, too strong,
//!   too wide) shows as an error instead of being measured against itself.
//!
//! Both run as GPU kernels with CPU references beside them (`Backend::preview_split_sum`,
//! `Backend::preview_truth`). The picture ([`picture`]) shows them tone-mapped beside a
//! heat map of their relative difference; [`SphereStats`] gives per material and
//! roughness the mean and worst relative difference of the luminance
//! ([`RELATIVE_DIFFERENCE_DEFINITION`]).

pub mod lights;
pub mod picture;

pub use lights::{add_sun_light, LightPass};

use std::time::Instant;

use serde::Serialize;
use glam::Vec3;

use crate::backend::{shared_ltc_table, Backend};
use std::borrow::Cow;

use crate::environment::sun::Sun;
use crate::environment::Cubemap;
use crate::plan::chain::SpecularChain;
use crate::plan::lut::{BrdfLut, LutLayout, DEFAULT_LUT_SIZE};
use crate::plan::scene::{
    disk_points, material_table, pixel_geometry, PixelGeometry, Scene,
    SceneUniform, SplitSumInputs, SplitSumLight, TruthInputs, TruthLight, DEFAULT_CELL,
    DEFAULT_TRUTH_SAMPLES, MATERIALS, ROUGHNESS,
};
use crate::plan::shading::{
    env_brdf_approx_table, IrradianceSource, LightBrdf, ShaderLut, Shading,
};
use crate::plan::sources::{split_hot_texels, SampledSource};
use crate::stages::light::BakedEnvironment;
use crate::stages::preview::picture::{auto_exposure, compose, luminance, Caption, Comparison};
use crate::{Error, Result};

/// The roughness of each column of the preview's spheres.
pub const PREVIEW_ROUGHNESS: [f32; 5] = ROUGHNESS;

/// The baked light a preview renders with, in the generic orientation.
#[derive(Clone, Copy, Debug)]
pub struct BakedLight<'a> {
    /// What the picture's caption calls the environment (its file name).
    pub name: &'a str,
    /// The prefiltered specular chain (level 0 is the environment).
    pub specular: &'a Cubemap,
    /// Its layout: how many levels and which roughness each holds (the lod mapping).
    pub chain: SpecularChain,
    /// The irradiance cube (E/π).
    pub irradiance: &'a Cubemap,
    /// The split-sum LUT (scale, bias).
    pub lut: &'a BrdfLut,
    /// The lights taken out of the chain and the irradiance (`--sun split`, the sun
    /// first): the split-sum shades each with the preview's BRDF, as a directional light,
    /// or as an area light from the BRDF's LTC table where it has a shape.
    pub lights: &'a [Sun],
    /// The environment as read, lights included, in its level 0
    /// ([`BakedEnvironment::seen`]): what the truth integrates and the exposure is chosen
    /// from, whatever was taken out of the chain.
    pub seen: &'a Cubemap,
}

/// What the per-sphere figures are, as `preview --json` and the manifest state them.
pub const RELATIVE_DIFFERENCE_DEFINITION: &str = "per sphere, on each pixel's luminance Y: mean = sum |Y_split_sum - Y_truth| / sum Y_truth; worst = the largest |Y_split_sum - Y_truth| / max(Y_truth, 0.01 Y_ref) of one pixel, Y_ref the sphere's mean Y_truth (where that is 0, the mean Y_truth of every sphere; where that is 0 too, the sphere's mean Y_split_sum), which also floors the mean's denominator at 0.01 Y_ref per pixel; 0 where both renders are black; truth_luminance and split_sum_luminance = the sphere's mean Y";

/// What the ground truth integrates, as the manifest states it.
pub const TRUTH_DEFINITION: &str = "the integral of the same BRDF with the real view direction over the environment as read (lights included, whatever the sun mode, at the input's own resolution: a cube of edge width / 4 for an equirect, at most 1024; a bake folder's background.ktx2, or its chain's level 0 where nothing was taken out), hot texels summed exactly, the rest by GGX visible-normal and cosine quasi-Monte Carlo";

/// The floor of a pixel's luminance in the worst relative difference, as a fraction of
/// its sphere's mean ([`RELATIVE_DIFFERENCE_DEFINITION`]): a pixel darker than 1 % of the
/// light its sphere sends (a silhouette, a side turned from a lamp on black) is measured
/// against that 1 %, not against its own near-zero luminance.
pub const WORST_FLOOR: f64 = 0.01;

/// How the preview is made.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PreviewOptions {
    /// Cell edge in pixels (8 ..= 512).
    pub cell: u32,
    /// Exposure in stops (a scale 2^EV); `None` picks it from the environment
    /// (the exposure that maps its solid-angle log-average luminance to 0.18).
    pub exposure_ev: Option<f32>,
    /// Quasi-Monte Carlo points per lobe and pixel of the ground truth (0 ..= 65536; 0
    /// renders the split-sum alone, without the truth, the heat map or the stats).
    pub truth_samples: u32,
    /// How the split-sum shades the spheres and which BRDF the truth integrates
    /// ([`Shading::GENERIC`], the README's recipe, by default; an engine target's own
    /// shows what that engine's shader makes of its files).
    pub shading: Shading,
}

impl Default for PreviewOptions {
    fn default() -> Self {
        PreviewOptions {
            cell: DEFAULT_CELL,
            exposure_ev: None,
            truth_samples: DEFAULT_TRUTH_SAMPLES,
            shading: Shading::GENERIC,
        }
    }
}

/// Split-sum against truth for one sphere, on each pixel's luminance Y.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct SphereStats {
    /// The material's name.
    pub material: &'static str,
    /// The roughness.
    pub roughness: f32,
    /// Σ |Y_split-sum − Y_truth| / Σ Y_truth over the sphere's pixels: the relative
    /// difference of the light the sphere sends to the camera (near the silhouette, where
    /// the truth goes dark, a pixel's relative difference can be large while its light is
    /// small). Always finite ([`RELATIVE_DIFFERENCE_DEFINITION`]).
    pub mean_relative: f32,
    /// The largest |Y_split-sum − Y_truth| / max(Y_truth, 0.01 (`WORST_FLOOR`) × the sphere's
    /// mean Y_truth) of one pixel.
    pub worst_relative: f32,
    /// The sphere's mean Y_truth: the same in every sun mode, so two modes' figures can
    /// be compared.
    pub truth_luminance: f32,
    /// The sphere's mean Y_split-sum.
    pub split_sum_luminance: f32,
}

/// A rendered preview.
#[derive(Clone, Debug)]
pub struct Preview {
    /// The picture, PNG-encoded (8-bit sRGB).
    pub png: Vec<u8>,
    /// Its width in pixels.
    pub width: u32,
    /// Its height in pixels.
    pub height: u32,
    /// The linear exposure scale applied before tone mapping.
    pub exposure: f32,
    /// One entry per sphere, materials in row order, roughness in column order (empty
    /// without the truth).
    pub stats: Vec<SphereStats>,
    /// The split-sum panel, row-major linear RGB (before exposure).
    pub split_sum: Vec<[f32; 3]>,
    /// The ground-truth panel (empty with `truth_samples` 0).
    pub truth: Vec<[f32; 3]>,
    /// Wall-clock seconds of the split-sum render.
    pub split_sum_seconds: f64,
    /// Wall-clock seconds of the ground-truth render.
    pub truth_seconds: f64,
    /// The lights shaded beside the IBL (`--sun split`), the sun first.
    pub lights: Vec<Sun>,
    /// How the split-sum shaded and the truth's BRDF.
    pub shading: Shading,
}

impl PreviewOptions {
    /// Checks the options' ranges (an [`Error::InvalidOption`] names the field as
    /// `preview.<field>`).
    pub fn validate(&self) -> Result<()> {
        validate_options(self)
    }
}

/// Checks the options' ranges.
pub fn validate_options(opts: &PreviewOptions) -> Result<()> {
    if !(8..=512).contains(&opts.cell) {
        return Err(Error::InvalidOption {
            option: "preview.cell",
            message: format!("{} pixels is not from 8 to 512", opts.cell),
        });
    }
    if opts.truth_samples > 65536 {
        return Err(Error::InvalidOption {
            option: "preview.truth_samples",
            message: format!("{} is not from 0 to 65536", opts.truth_samples),
        });
    }
    if let Some(ev) = opts.exposure_ev {
        if !ev.is_finite() || ev.abs() > 64.0 {
            return Err(Error::InvalidOption {
                option: "preview.exposure_ev",
                message: format!("{ev} is not a number of stops from -64 to 64"),
            });
        }
    }
    Ok(())
}

/// The per-sphere table of the kernels, row by row (each material's spheres left to
/// right): (the roughness `shading` uses, the chain's lod for it, its lookup's bend for
/// it and the row's F0, its stretch).
pub fn sphere_table(chain: SpecularChain, shading: &Shading) -> Vec<[f32; 4]> {
    sphere_table_at(&ROUGHNESS, chain, shading)
}

/// [`sphere_table`] for the columns' roughness `roughness` (one per column of the
/// scene; a study of other roughness than the preview's).
pub fn sphere_table_at(
    roughness: &[f32],
    chain: SpecularChain,
    shading: &Shading,
) -> Vec<[f32; 4]> {
    let lookup = shading.lookup;
    MATERIALS
        .iter()
        .flat_map(|m| {
            roughness.iter().map(move |&r| {
                let r = shading.roughness(r);
                let lod = chain.roughness.lod(r, chain.levels);
                [r, lod, lookup.bend(r, Vec3::from(m.f0)), lookup.stretch()]
            })
        })
        .collect()
}

/// Each sphere pixel's relative difference (None elsewhere) and the per-sphere stats
/// ([`RELATIVE_DIFFERENCE_DEFINITION`]: finite for any finite renders).
pub fn compare(
    scene: &SceneUniform,
    split_sum: &[[f32; 3]],
    truth: &[[f32; 3]],
) -> (Vec<Option<f32>>, Vec<SphereStats>) {
    let spheres = MATERIALS.len() * ROUGHNESS.len();
    // Per sphere: pixel count, Σ |ΔY|, Σ Y_truth, Σ Y_split-sum; then each pixel's sphere.
    let mut sums = vec![(0usize, 0.0f64, 0.0f64, 0.0f64); spheres];
    let mut owner = vec![None; split_sum.len()];
    for y in 0..scene.height {
        for x in 0..scene.width {
            if let PixelGeometry::Sphere {
                material, column, ..
            } = pixel_geometry(scene, x, y)
            {
                let k = (y * scene.width + x) as usize;
                let sphere = material * ROUGHNESS.len() + column;
                let (t, ss) = (luminance(truth[k]) as f64, luminance(split_sum[k]) as f64);
                let s = &mut sums[sphere];
                *s = (s.0 + 1, s.1 + (ss - t).abs(), s.2 + t, s.3 + ss);
                owner[k] = Some(sphere);
            }
        }
    }
    let mean = |sum: f64, count: usize| sum / count.max(1) as f64;
    let all_truth = mean(
        sums.iter().map(|s| s.2).sum(),
        sums.iter().map(|s| s.0).sum(),
    );
    // Each sphere's floor: WORST_FLOOR of its reference luminance.
    let floors: Vec<f64> = sums
        .iter()
        .map(|&(count, _, truth, split)| {
            let reference = [mean(truth, count), all_truth, mean(split, count)]
                .into_iter()
                .find(|&y| y > 0.0)
                .unwrap_or(0.0);
            WORST_FLOOR * reference
        })
        .collect();
    let ratio = |diff: f64, floored: f64| match diff > 0.0 {
        true => (diff / floored).min(f64::from(f32::MAX)) as f32,
        false => 0.0,
    };
    let mut worst = vec![0.0f32; spheres];
    let relative = owner
        .iter()
        .enumerate()
        .map(|(k, sphere)| {
            let sphere = (*sphere)?;
            let t = luminance(truth[k]) as f64;
            let d = ratio(
                (luminance(split_sum[k]) as f64 - t).abs(),
                t.max(floors[sphere]),
            );
            worst[sphere] = worst[sphere].max(d);
            Some(d)
        })
        .collect();
    let stats = sums
        .iter()
        .enumerate()
        .map(|(i, &(count, diff, truth, split))| SphereStats {
            material: MATERIALS[i / ROUGHNESS.len()].name,
            roughness: ROUGHNESS[i % ROUGHNESS.len()],
            mean_relative: ratio(diff, truth.max(count as f64 * floors[i])),
            worst_relative: worst[i],
            truth_luminance: mean(truth, count) as f32,
            split_sum_luminance: mean(split, count) as f32,
        })
        .collect();
    (relative, stats)
}

/// What the truth integrates, from the environment as read (`seen`, its level 0 alone is
/// read): that level with every mip (as the hot/cold split needs it) and the split into
/// hot texels and the cold rest.
pub fn truth_environment(seen: &Cubemap) -> (Cubemap, SampledSource) {
    let mut env = Cubemap {
        size: seen.size,
        levels: vec![seen.levels[0].clone()],
    };
    let mips = Cubemap::full_mip_count(env.size);
    crate::environment::mips::build_mips(&mut env, mips);
    let split = split_hot_texels(&env);
    (env, split)
}

/// The ground-truth panel of `light` on `backend` for the kernels' tables (of the spheres
/// only each one's roughness is read) with `samples` quasi-Monte Carlo points per lobe and
/// pixel and the BRDF `brdf` (compensated with `light`'s LUT where it is): the
/// environment as read (`light.seen`, lights included) split into its hot texels and the
/// cold rest ([`truth_environment`]).
pub fn render_truth(
    backend: &dyn Backend,
    scene: &SceneUniform,
    light: &BakedLight,
    spheres: &[[f32; 4]],
    materials: &[[f32; 4]],
    samples: u32,
    brdf: LightBrdf,
) -> Result<Vec<[f32; 3]>> {
    let (env, split) = truth_environment(light.seen);
    let points = disk_points(samples);
    backend.preview_truth(
        scene,
        &TruthInputs {
            light: TruthLight {
                env: &env,
                cold: &split.rest,
                hot: &split.hot,
                points: &points,
                brdf,
            },
            spheres,
            materials,
            lut: light.lut,
        },
    )
}

/// Renders the preview of `light` with `backend`.
pub fn render_preview(
    backend: &dyn Backend,
    light: &BakedLight,
    opts: &PreviewOptions,
) -> Result<Preview> {
    validate_options(opts)?;
    let scene = Scene { cell: opts.cell };
    let uniform = scene.uniform();
    let shading = &opts.shading;
    let spheres = sphere_table(light.chain, shading);
    let materials = material_table();

    let t = Instant::now();
    let mut split_sum = backend.preview_split_sum(
        &uniform,
        &SplitSumInputs {
            light: SplitSumLight {
                specular: light.specular,
                irradiance: light.irradiance,
                lut: light.lut,
                terms: shading.terms,
                filtered: shading
                    .lookup
                    .filtered()
                    .then_some(light.chain.roughness),
            },
            spheres: &spheres,
            materials: &materials,
        },
    )?;
    let pass = LightPass {
        scene: &uniform,
        spheres: &spheres,
        materials: &materials,
        brdf: shading.light,
        lut: light.lut,
    };
    let table = light
        .lights
        .iter()
        .any(|l| l.shape.is_some())
        .then(|| shared_ltc_table(backend, shading.light))
        .transpose()?;
    for sun in light.lights {
        match (sun.shape, &table) {
            (Some(shape), Some(table)) => {
                lights::add_area_light(&pass, sun, shape, table, &mut split_sum)
            }
            _ => add_sun_light(&pass, sun, &mut split_sum),
        }
    }
    let split_sum_seconds = t.elapsed().as_secs_f64();

    let t = Instant::now();
    let truth = if opts.truth_samples == 0 {
        Vec::new()
    } else {
        render_truth(
            backend,
            &uniform,
            light,
            &spheres,
            &materials,
            opts.truth_samples,
            shading.light,
        )?
    };
    let truth_seconds = t.elapsed().as_secs_f64();

    let exposure = match opts.exposure_ev {
        Some(ev) => 2f32.powf(ev),
        None => auto_exposure(light.seen),
    };
    let (relative, stats) = if truth.is_empty() {
        (Vec::new(), Vec::new())
    } else {
        compare(&uniform, &split_sum, &truth)
    };
    let comparison = (!truth.is_empty()).then_some(Comparison {
        truth: &truth,
        relative: &relative,
    });
    let encode_error = |message: String| Error::Encode {
        path: "preview.png".into(),
        format: "PNG",
        message,
    };
    let caption = Caption {
        name: light.name,
        exposure_ev: exposure.log2(),
        truth_samples: opts.truth_samples,
    };
    let img = compose(&scene, &split_sum, comparison, exposure, &caption).map_err(encode_error)?;
    let mut png = std::io::Cursor::new(Vec::new());
    img.write_to(&mut png, image::ImageFormat::Png)
        .map_err(|e| encode_error(e.to_string()))?;
    Ok(Preview {
        png: png.into_inner(),
        width: img.width(),
        height: img.height(),
        exposure,
        stats,
        split_sum,
        truth,
        split_sum_seconds,
        truth_seconds,
        lights: light.lights.to_vec(),
        shading: opts.shading,
    })
}

impl<'a> BakedLight<'a> {
    /// What the preview reads of `baked` (called `name` in the caption), with `lut`.
    pub fn of(name: &'a str, baked: &'a BakedEnvironment, lut: &'a BrdfLut) -> Self {
        BakedLight {
            name,
            specular: &baked.specular,
            chain: baked.chain,
            irradiance: &baked.irradiance,
            lut,
            lights: baked.split_lights(),
            seen: baked.seen(),
        }
    }
}

/// The diffuse light E/π `shading` reads from `baked`: the irradiance cube, or a cube of
/// the chain's last level alone (which the bake fits to E/π).
pub fn shading_irradiance<'a>(shading: &Shading, baked: &'a BakedEnvironment) -> Cow<'a, Cubemap> {
    match shading.irradiance {
        IrradianceSource::Cube => Cow::Borrowed(&baked.irradiance),
        IrradianceSource::LastLevel => Cow::Owned(last_level(&baked.specular)),
    }
}

/// A chain's last level alone, as a one-level cube (what three.js and Filament read E/π
/// from).
pub fn last_level(chain: &Cubemap) -> Cubemap {
    let last = chain.levels.len() - 1;
    Cubemap {
        size: chain.level_size(last),
        levels: vec![chain.levels[last].clone()],
    }
}

/// Whether `lut` is the table `shading`'s shader reads: its model, and its engine's own
/// size where the engine ships one.
pub fn is_shading_lut(shading: &Shading, lut: &BrdfLut) -> bool {
    match shading.lut {
        ShaderLut::Table { model, size } => {
            lut.model == model && size.is_none_or(|n| lut.width == n && lut.height == n)
        }
        ShaderLut::EnvBrdfApprox => false,
    }
}

/// The split-sum's (A, B) table of `shading`'s LUT: `lut` where it is that table
/// ([`is_shading_lut`]), otherwise computed on `backend` (its engine's size, or
/// [`DEFAULT_LUT_SIZE`]²); a model stored as (B, A + B) (Filament's) is rearranged.
pub fn shading_lut(backend: &dyn Backend, shading: &Shading, lut: Option<&BrdfLut>) -> Result<BrdfLut> {
    let model = match shading.lut {
        ShaderLut::Table { model, .. } => model,
        ShaderLut::EnvBrdfApprox => {
            return Ok(env_brdf_approx_table(DEFAULT_LUT_SIZE, DEFAULT_LUT_SIZE))
        }
    };
    let table = match lut.filter(|l| is_shading_lut(shading, l)) {
        Some(l) => l.clone(),
        None => {
            let n = match shading.lut {
                ShaderLut::Table { size: Some(n), .. } => n,
                _ => DEFAULT_LUT_SIZE,
            };
            backend.brdf_lut_model(n, n, model)?
        }
    };
    let layout = model.layout();
    if layout == LutLayout::ScaleBias {
        return Ok(table);
    }
    let data = table
        .data
        .iter()
        .map(|&t| {
            layout.scale_bias(t).ok_or_else(|| Error::InvalidOption {
                option: "preview.shading",
                message: format!(
                    "the {} LUT holds no (A, B) for the split-sum",
                    model.name()
                ),
            })
        })
        .collect::<Result<Vec<_>>>()?;
    Ok(BrdfLut {
        data,
        ..table
    })
}

/// The preview of `baked` with its shading's LUT (`lut` where it is that table,
/// [`shading_lut`]) and diffuse light ([`shading_irradiance`]).
pub fn preview_baked(
    backend: &dyn Backend,
    name: &str,
    baked: &BakedEnvironment,
    lut: Option<&BrdfLut>,
    opts: &PreviewOptions,
) -> Result<Preview> {
    let lut = shading_lut(backend, &opts.shading, lut)?;
    let irradiance = shading_irradiance(&opts.shading, baked);
    let light = BakedLight {
        irradiance: &irradiance,
        ..BakedLight::of(name, baked, &lut)
    };
    render_preview(backend, &light, opts)
}
