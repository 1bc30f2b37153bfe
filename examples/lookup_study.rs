//! The lookup study: where should a shader read the prefiltered chain? For each bundled
//! HDRI, with the sun kept and split (`--sun`), and the environment turned to four azimuths
//! (four views of it), the preview's spheres are shaded with each [`SpecularLookup`] and
//! the fitted blend ([`FITTED`]), each read plainly, and with the README's recipe (the
//! stretched lookup blended toward E/π by α²), and
//! compared with the preview's ground truth (the full reflectance integral, which does not
//! depend on the lookup), sphere by sphere: the energy-weighted relative difference of the
//! light each sends to the camera (`preview --json`'s `mean`). Prints a Markdown table per
//! HDRI and mode: for each lookup and roughness, the mean over the six materials and four
//! views, and the worst sphere.
//!
//! `cargo run --release --example lookup_study [-- fit]`: with `fit`, instead, the
//! [`BlendFit`] family on a grid against FIT_HDRIS with the sun split (what a person
//! should use: the kept sun's tens of per cent are the split-sum's own, no lookup mends
//! them), minimising the mean figure of the spheres with r ≥ 0.25 (what
//! `math::lookup::FITTED` holds). With `lod`, whether the chain suits the lookup:
//! Frostbite's lookup reading each roughness at a scaled lod. With `grazing`, what the
//! README's recipe reads (`SpecularLookup::Stretched`): Frostbite's direction at a lod
//! narrowed toward grazing views and as two taps along the plane of incidence, on a grid
//! and then on every bundled HDRI. With `high`, both lookups at r = 0.8 … 0.99, where the
//! taps fade out. With `fresnel`, the Fresnel scale of the recipe's bend against the lobe
//! it is fitted to (no HDRI). 32-pixel cells and 1024
//! truth points: a quarter of the preview's pixels and half its points, enough for figures
//! to the tenth of a per cent. docs/accuracy.md holds the output.

use splitsum::backend::CpuBackend;
use splitsum::bake::{bake_environment, BakeOptions};
use splitsum::cpu::preview_split_sum::{
    render_split_sum_shaded, split_sum_shade, split_sum_shade_along,
};
use splitsum::math::lookup::{BlendFit, SpecularLookup, FITTED};
use splitsum::plan::lut::BrdfLut;
use splitsum::plan::material::ShadeMaterial;
use splitsum::plan::scene::{material_table, Scene, SplitSumInputs, SplitSumLight, ROUGHNESS};
use splitsum::plan::shading::{LightBrdf, RadianceBlend, Shading, ShadingTerms};
use splitsum::stages::preview::{
    add_sun_light, compare, render_truth, sphere_table, sphere_table_at, BakedLight, LightPass,
    PreviewOptions,
};
use splitsum::{BakedEnvironment, SunMode};

/// The bundled HDRIs (venice_sunset once: its EXR is the same picture).
const HDRIS: [&str; 6] = [
    "quarry_01_1k.hdr",
    "royal_esplanade_1k.hdr",
    "venice_sunset_1k.hdr",
    "pedestrian_overpass_1k.hdr",
    "studio_small_03_1k.hdr",
    "blender_studiolight_interior.exr",
];
/// What the blend is fitted on: a hard low sun and a sunset without one; the other four
/// HDRIs check it.
const FIT_HDRIS: [&str; 2] = ["quarry_01_1k.hdr", "venice_sunset_1k.hdr"];
/// What the lod studies measure on, with the sun split: the two sunny HDRIs and a sunset.
const LOD_HDRIS: [&str; 3] = [
    "quarry_01_1k.hdr",
    "royal_esplanade_1k.hdr",
    "venice_sunset_1k.hdr",
];
/// The table's rows: every [`SpecularLookup`], then the fitted blend, then the README's
/// recipe (the stretched lookup blended toward E/π by α²).
const ROWS: usize = SpecularLookup::ALL.len() + 2;
/// The four views: the environment turned about +Y.
const AZIMUTHS: [f32; 4] = [0.0, 90.0, 180.0, 270.0];
/// The preview's pixels and truth points the study renders with.
const OPTS: PreviewOptions = PreviewOptions {
    cell: 32,
    exposure_ev: None,
    truth_samples: 1024,
    shading: Shading::GENERIC,
};

/// One view of one HDRI in one mode: its bake and the preview's ground truth.
struct View {
    baked: BakedEnvironment,
    truth: Vec<[f32; 3]>,
}

/// The views of `name` with `sun`.
fn views(name: &str, sun: SunMode, lut: &BrdfLut) -> Result<Vec<View>, splitsum::Error> {
    let cpu = CpuBackend;
    let path = std::path::Path::new("tests/data").join(name);
    let env = splitsum::io::input::load_input(&path, &Default::default())?.env;
    AZIMUTHS
        .iter()
        .map(|&azimuth| {
            let opts = BakeOptions {
                sun,
                rotate_degrees: azimuth,
                ..BakeOptions::default()
            };
            let baked = bake_environment(&cpu, env.clone(), &opts, &mut |_| {}, &mut Vec::new())?;
            let truth = render_truth(
                &cpu,
                &Scene { cell: OPTS.cell }.uniform(),
                &BakedLight::of(name, &baked, lut),
                &sphere_table(baked.chain, &OPTS.shading),
                &material_table(),
                OPTS.truth_samples,
                LightBrdf::GENERIC,
            )?;
            Ok(View { baked, truth })
        })
        .collect()
}

/// Each sphere's figure (materials in row order, roughness in column order) of `view`
/// shaded with the chain looked up along `lookup`, stretched by `stretch`
/// (`SpecularLookup::stretch`).
fn figures(
    view: &View,
    lut: &BrdfLut,
    lookup: impl Fn(glam::Vec3, glam::Vec3, f32, glam::Vec3) -> glam::Vec3 + Sync,
    stretch: f32,
) -> Vec<f32> {
    figures_at(view, lut, lookup, stretch, 1.0, RadianceBlend::None)
}

/// As [`figures`], each roughness read at `lod_scale` × the chain's lod for it, the read
/// blended toward E/π as `blend` says.
fn figures_at(
    view: &View,
    lut: &BrdfLut,
    lookup: impl Fn(glam::Vec3, glam::Vec3, f32, glam::Vec3) -> glam::Vec3 + Sync,
    stretch: f32,
    lod_scale: f32,
    blend: RadianceBlend,
) -> Vec<f32> {
    let mut spheres = sphere_table(
        view.baked.chain,
        &Shading::GENERIC.with_lookup(SpecularLookup::Reflect),
    );
    spheres.iter_mut().for_each(|c| {
        c[1] *= lod_scale;
        c[3] = stretch;
    });
    figures_with(
        &view.baked,
        lut,
        &spheres,
        &view.truth,
        blend,
        |light, n, v, n_dot_v, m| {
            split_sum_shade_along(light, n, lookup(n, v, m.roughness, m.f0), n_dot_v, m)
        },
    )
}

/// Each sphere's figure of `baked` against `truth` (materials in row order, columns in
/// order), its spheres shaded by `shade(light, n, v, n·v, material)` with the kernels'
/// per-sphere table `spheres` and the read blended toward E/π as `blend` says, and the
/// lights taken out of it shaded as the preview shades them.
fn figures_with(
    baked: &BakedEnvironment,
    lut: &BrdfLut,
    spheres: &[[f32; 4]],
    truth: &[[f32; 3]],
    blend: RadianceBlend,
    shade: impl Fn(&SplitSumLight, glam::Vec3, glam::Vec3, f32, &ShadeMaterial) -> glam::Vec3 + Sync,
) -> Vec<f32> {
    let scene = Scene { cell: OPTS.cell }.uniform();
    let light = BakedLight::of("", baked, lut);
    let materials = material_table();
    let inputs = SplitSumInputs {
        light: SplitSumLight {
            specular: light.specular,
            irradiance: light.irradiance,
            lut,
            // The lookups alone unless `blend` (the recipe's row).
            terms: ShadingTerms {
                radiance_blend: blend,
                ..ShadingTerms::GENERIC
            },
            filtered: None,
        },
        spheres,
        materials: &materials,
    };
    let mut panel = render_split_sum_shaded(&scene, &inputs, |n, v, n_dot_v, m| {
        shade(&inputs.light, n, v, n_dot_v, m)
    });
    let pass = LightPass {
        scene: &scene,
        spheres,
        materials: &materials,
        brdf: LightBrdf::GENERIC,
        lut,
    };
    for sun in light.lights {
        add_sun_light(&pass, sun, &mut panel);
    }
    compare(&scene, &panel, truth)
        .1
        .iter()
        .map(|s| s.mean_relative)
        .collect()
}

/// The mean figure of the spheres with r ≥ 0.25 over `views` with `fit`.
fn fit_objective(views: &[View], lut: &BrdfLut, fit: BlendFit) -> f32 {
    let mut sum = 0.0;
    let mut count = 0;
    for view in views {
        for (i, e) in figures(view, lut, |n, v, r, _| fit.direction(n, v, r), 0.0)
            .iter()
            .enumerate()
        {
            if ROUGHNESS[i % ROUGHNESS.len()] >= 0.25 {
                sum += e;
                count += 1;
            }
        }
    }
    sum / count as f32
}

fn fit(lut: &BrdfLut) -> Result<(), splitsum::Error> {
    let mut all = Vec::new();
    for name in FIT_HDRIS {
        all.extend(views(name, SunMode::Split, lut)?);
    }
    let mut best = (f32::INFINITY, None);
    for a in [0.8, 0.9, 1.0, 1.1, 1.2, 1.3, 1.4, 1.5] {
        for p in [1.0, 1.25, 1.5, 1.75, 2.0, 2.5] {
            for b in [0.0, 0.25, 0.5, 1.0] {
                let f = BlendFit { a, p, b };
                let e = fit_objective(&all, lut, f);
                if e < best.0 {
                    best = (e, Some(f));
                }
            }
        }
    }
    println!(
        "best on {FIT_HDRIS:?}: {:?}, mean {:.2} % over the spheres with r >= 0.25",
        best.1,
        100.0 * best.0
    );
    Ok(())
}

/// Whether the chain's levels suit the lookup: Frostbite's lookup with each roughness read
/// at a scaled lod (a level of another lobe width), mean figure per roughness over
/// LOD_HDRIS with the sun split.
fn lod(lut: &BrdfLut) -> Result<(), splitsum::Error> {
    const SCALES: [f32; 6] = [0.7, 0.8, 0.9, 1.0, 1.1, 1.2];
    let mut all = Vec::new();
    for name in LOD_HDRIS {
        all.extend(views(name, SunMode::Split, lut)?);
    }
    print!("| lod × |");
    ROUGHNESS[1..].iter().for_each(|r| print!(" r = {r} |"));
    println!("\n|---|{}", "---|".repeat(ROUGHNESS.len() - 1));
    for scale in SCALES {
        let mut sums = vec![(0.0f32, 0u32); ROUGHNESS.len()];
        for view in &all {
            let lookup = |n, v, r, f0| SpecularLookup::Frostbite.direction(n, v, r, f0);
            for (i, e) in figures_at(view, lut, lookup, 0.0, scale, RadianceBlend::None)
                .iter()
                .enumerate()
            {
                let s = &mut sums[i % ROUGHNESS.len()];
                *s = (s.0 + e, s.1 + 1);
            }
        }
        print!("| {scale} |");
        sums[1..]
            .iter()
            .for_each(|(e, n)| print!(" {:.2} % |", 100.0 * e / *n as f32));
        println!();
    }
    Ok(())
}

/// A lookup that changes toward grazing views, where the true lobe narrows across the
/// plane of incidence and stretches along it: Frostbite's direction d read at
/// lod(r) × (1 − c (1 − n·v)² (1 − r)) (narrower toward grazing, less so as r grows), as
/// the mean of two taps d ± s·t with t the plane of incidence's direction across d and
/// s = a α (1 − n·v) (a stretched lobe as two narrower ones). The power 2 and the (1 − r)
/// factor were the best of (1 − n·v)^p (1 − r)^q, p ∈ {1, 2}, q ∈ {0, 1, 2}, on
/// LOD_HDRIS.
#[derive(Clone, Copy, Debug)]
struct Grazing {
    /// The two taps' spread (0: one tap).
    a: f32,
    /// How much narrower the lod gets toward grazing (0: the chain's own lod).
    c: f32,
}

impl Grazing {
    /// The split-sum radiance of a sphere pixel read this way.
    fn shade(
        self,
        light: &SplitSumLight,
        max_lod: f32,
        n: glam::Vec3,
        v: glam::Vec3,
        n_dot_v: f32,
        m: &ShadeMaterial,
    ) -> glam::Vec3 {
        let mut m = *m;
        let grazing = 1.0 - n_dot_v;
        let narrowing = 1.0 - self.c * grazing * grazing * (1.0 - m.roughness);
        m.lod = (m.lod * narrowing).clamp(0.0, max_lod);
        let dir = SpecularLookup::Frostbite.direction(n, v, m.roughness, m.f0);
        if self.a == 0.0 {
            return split_sum_shade_along(light, n, dir, n_dot_v, &m);
        }
        let c = n - dir * n.dot(dir);
        let across = c / c.length().max(splitsum::math::lookup::STRETCH_EPSILON);
        let spread = across * self.a * m.roughness * m.roughness * grazing;
        0.5 * (split_sum_shade_along(light, n, (dir + spread).normalize(), n_dot_v, &m)
            + split_sum_shade_along(light, n, (dir - spread).normalize(), n_dot_v, &m))
    }
}

/// Each sphere's figure of `view` shaded with `g`.
fn grazing_figures(view: &View, lut: &BrdfLut, g: Grazing) -> Vec<f32> {
    let spheres = sphere_table(
        view.baked.chain,
        &Shading::GENERIC.with_lookup(SpecularLookup::Frostbite),
    );
    let max_lod = (view.baked.chain.levels - 1) as f32;
    figures_with(
        &view.baked,
        lut,
        &spheres,
        &view.truth,
        RadianceBlend::None,
        |light, n, v, n_dot_v, m| g.shade(light, max_lod, n, v, n_dot_v, m),
    )
}

/// Prints a table row: per roughness, the mean figure over `views` and the worst sphere.
fn grazing_row(label: &str, views: &[View], lut: &BrdfLut, g: Grazing) {
    let mut sums = vec![(0.0f32, 0u32, 0.0f32); ROUGHNESS.len()];
    for view in views {
        for (i, e) in grazing_figures(view, lut, g).iter().enumerate() {
            let s = &mut sums[i % ROUGHNESS.len()];
            *s = (s.0 + e, s.1 + 1, s.2.max(*e));
        }
    }
    print!("| {label} | {} | {} |", g.a, g.c);
    sums.iter()
        .for_each(|(e, n, w)| print!(" {:.2} % ({:.1}) |", 100.0 * e / *n as f32, 100.0 * w));
    println!();
}

/// Whether the lookup should change toward grazing views ([`Grazing`]): a grid on
/// LOD_HDRIS with the sun split, then the plain lookup against the best narrowing and the
/// best two taps on every bundled HDRI, the sun kept and split.
fn grazing(lut: &BrdfLut) -> Result<(), splitsum::Error> {
    let header = |first: &str| {
        print!("| {first} | a | c |");
        ROUGHNESS.iter().for_each(|r| print!(" r = {r} |"));
        println!("\n|---|---|---|{}", "---|".repeat(ROUGHNESS.len()));
    };
    let mut fit_views = Vec::new();
    for name in LOD_HDRIS {
        fit_views.extend(views(name, SunMode::Split, lut)?);
    }
    header("fitted on");
    for a in [0.0, 0.5, 1.0, 1.25, 1.5] {
        for c in [0.0, 0.4, 0.8, 1.0, 1.2] {
            grazing_row("LOD_HDRIS, split", &fit_views, lut, Grazing { a, c });
        }
    }
    println!();
    header("HDRI");
    for name in HDRIS {
        for sun in [SunMode::Keep, SunMode::Split] {
            let views = views(name, sun, lut)?;
            for g in GRAZING_CANDIDATES {
                grazing_row(&format!("{name}, {}", sun.name()), &views, lut, g);
            }
        }
    }
    Ok(())
}

/// The plain lookup, the narrowing best at r = 0.5 on LOD_HDRIS, and the two taps best at
/// r = 0.25 and 0.5 there.
const GRAZING_CANDIDATES: [Grazing; 3] = [
    Grazing { a: 0.0, c: 0.0 },
    Grazing { a: 0.0, c: 0.8 },
    Grazing { a: 1.0, c: 1.0 },
];

/// The roughness of the high-roughness check's five columns: between the table's 0.75
/// and 1, where Frostbite's direction reaches n.
const HIGH_ROUGHNESS: [f32; 5] = [0.8, 0.85, 0.9, 0.95, 0.99];

/// The spheres at HIGH_ROUGHNESS, between the table's columns, where the stretched taps
/// fade out (`math::lookup::STRETCH_FADE_ROUGHNESS`): each roughness's mean figure (worst
/// sphere) over every bundled HDRI with the sun split, four views, Frostbite's single tap
/// against the stretched lookup.
fn high(lut: &BrdfLut) -> Result<(), splitsum::Error> {
    print!("| lookup |");
    HIGH_ROUGHNESS.iter().for_each(|r| print!(" r = {r} |"));
    println!("\n|---|{}", "---|".repeat(HIGH_ROUGHNESS.len()));
    let lookups = [SpecularLookup::Frostbite, SpecularLookup::Stretched];
    let mut rows = vec![vec![Vec::new(); HIGH_ROUGHNESS.len()]; lookups.len()];
    for name in HDRIS {
        for view in views(name, SunMode::Split, lut)? {
            let chain = view.baked.chain;
            // The truth reads each column's roughness alone: one for both lookups.
            let truth = render_truth(
                &CpuBackend,
                &Scene { cell: OPTS.cell }.uniform(),
                &BakedLight::of(name, &view.baked, lut),
                &sphere_table_at(
                    &HIGH_ROUGHNESS,
                    chain,
                    &Shading::GENERIC.with_lookup(SpecularLookup::Frostbite),
                ),
                &material_table(),
                OPTS.truth_samples,
                LightBrdf::GENERIC,
            )?;
            for (row, lookup) in rows.iter_mut().zip(lookups) {
                let spheres = sphere_table_at(
                    &HIGH_ROUGHNESS,
                    chain,
                    &Shading::GENERIC.with_lookup(lookup),
                );
                let figures = figures_with(
                    &view.baked,
                    lut,
                    &spheres,
                    &truth,
                    RadianceBlend::None,
                    split_sum_shade,
                );
                for (i, e) in figures.into_iter().enumerate() {
                    row[i % HIGH_ROUGHNESS.len()].push(e);
                }
            }
        }
    }
    for (k, name) in ["Frostbite's dominant direction", "Frostbite's, stretched"]
        .iter()
        .enumerate()
    {
        print!("| {name} |");
        for e in &rows[k] {
            let mean = e.iter().sum::<f32>() / e.len() as f32;
            let worst = e.iter().copied().fold(0.0f32, f32::max);
            print!(" {:.2} % ({:.1}) |", 100.0 * mean, 100.0 * worst);
        }
        println!();
    }
    Ok(())
}

/// The roughness and F0 the Fresnel scale of the recipe's bend is fitted over
/// (`math::lookup::fresnel_bend_scale`): r where the bend is Frostbite's in full (from the
/// fade's 0.5) to 0.9; F0 from water's to a bright metal's.
const FRESNEL_ROUGHNESS: [f32; 5] = [0.5, 0.6, 0.7, 0.8, 0.9];
const FRESNEL_F0: [f32; 6] = [0.02, 0.04, 0.1, 0.2, 0.5, 0.8];

/// The Fresnel scale of the recipe's bend against the lobe it is fitted to: for each r and
/// F0, the bend of the Fresnel-weighted GGX lobe's mean direction relative to F0 = 1's,
/// averaged over a sphere's views (`math::lookup::lobe_bend_ratio`: 12 views, a 256 × 512
/// grid), beside the model with the least-squares weight b over the grid (searched in steps
/// of 0.0001) and with `FRESNEL_BEND_WEIGHT`. No HDRI: the lobe alone.
fn fresnel() {
    use splitsum::math::lookup::{
        fresnel_bend_scale, fresnel_bend_share, lobe_bend_ratio, FRESNEL_BEND_WEIGHT,
    };
    let ratios: Vec<Vec<f32>> = FRESNEL_ROUGHNESS
        .iter()
        .map(|&r| {
            FRESNEL_F0
                .iter()
                .map(|&f0| lobe_bend_ratio(r, f0, 12, 256))
                .collect()
        })
        .collect();
    let residual = |b: f32| -> f32 {
        let mut sum = 0.0;
        for (i, &r) in FRESNEL_ROUGHNESS.iter().enumerate() {
            for (j, &f0) in FRESNEL_F0.iter().enumerate() {
                sum += (fresnel_bend_share(r, f0, b) - ratios[i][j]).powi(2);
            }
        }
        sum
    };
    let best = (40..=90)
        .map(|k| k as f32 * 1e-4)
        .min_by(|a, b| residual(*a).total_cmp(&residual(*b)))
        .unwrap();
    println!("least-squares b = {best:.4} (FRESNEL_BEND_WEIGHT = {FRESNEL_BEND_WEIGHT})\n");
    print!("| r |");
    FRESNEL_F0
        .iter()
        .for_each(|f| print!(" F0 = {f}: lobe / model |"));
    println!("\n|---|{}", "---|".repeat(FRESNEL_F0.len()));
    let mut worst = 0.0f32;
    for (i, &r) in FRESNEL_ROUGHNESS.iter().enumerate() {
        print!("| {r} |");
        for (j, &f0) in FRESNEL_F0.iter().enumerate() {
            let m = fresnel_bend_scale(r, glam::Vec3::splat(f0));
            worst = worst.max((m - ratios[i][j]).abs());
            print!(" {:.3} / {m:.3} |", ratios[i][j]);
        }
        println!();
    }
    println!("\nlargest |lobe - model|: {worst:.3}");
}

fn main() -> Result<(), splitsum::Error> {
    let lut = splitsum::backend::Backend::brdf_lut(&CpuBackend, 512, 512)?;
    if std::env::args().any(|a| a == "fresnel") {
        fresnel();
        return Ok(());
    }
    if std::env::args().any(|a| a == "fit") {
        return fit(&lut);
    }
    if std::env::args().any(|a| a == "high") {
        return high(&lut);
    }
    if std::env::args().any(|a| a == "grazing") {
        return grazing(&lut);
    }
    if std::env::args().any(|a| a == "lod") {
        return lod(&lut);
    }
    for name in HDRIS {
        for sun in [SunMode::Keep, SunMode::Split] {
            let views = views(name, sun, &lut)?;
            // errors[lookup][column]: every (material, view) sphere's figure.
            let mut errors = vec![vec![Vec::new(); ROUGHNESS.len()]; ROWS];
            for view in &views {
                for (k, errors) in errors.iter_mut().enumerate() {
                    let stretched = SpecularLookup::Stretched;
                    let f = match SpecularLookup::ALL.get(k) {
                        Some(lookup) => figures(
                            view,
                            &lut,
                            |n, v, r, f0| lookup.direction(n, v, r, f0),
                            lookup.stretch(),
                        ),
                        None if k == SpecularLookup::ALL.len() => {
                            figures(view, &lut, |n, v, r, _| FITTED.direction(n, v, r), 0.0)
                        }
                        None => figures_at(
                            view,
                            &lut,
                            |n, v, r, f0| stretched.direction(n, v, r, f0),
                            stretched.stretch(),
                            1.0,
                            RadianceBlend::AlphaSquared,
                        ),
                    };
                    for (i, e) in f.into_iter().enumerate() {
                        errors[i % ROUGHNESS.len()].push(e);
                    }
                }
            }
            let lights = views[0].baked.split_lights().len();
            let mode = match (sun, lights) {
                (SunMode::Keep, _) => "sun kept".to_string(),
                (SunMode::Split, 0) => "split: no light found (as kept)".to_string(),
                (SunMode::Split, n) => {
                    format!("sun split ({n} light{})", if n > 1 { "s" } else { "" })
                }
            };
            let fitted = if FIT_HDRIS.contains(&name) {
                ", fitted on"
            } else {
                ""
            };
            println!("\n### {name}, {mode}{fitted}\n");
            print!("| lookup |");
            ROUGHNESS.iter().for_each(|r| print!(" r = {r} |"));
            println!("\n|---|{}", "---|".repeat(ROUGHNESS.len()));
            for (k, errors) in errors.iter().enumerate() {
                let name = match SpecularLookup::ALL.get(k) {
                    Some(l) => l.name(),
                    None if k == SpecularLookup::ALL.len() => "fitted blend",
                    None => "the recipe: stretched, blended toward E/π by α²",
                };
                print!("| {name} |");
                for e in errors {
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
