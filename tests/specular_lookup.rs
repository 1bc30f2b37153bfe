//! The lookup the README's recipe, the preview and the viewer make
//! (`SpecularLookup::GENERIC`: R bent toward n as the GGX lobe leans, Frostbite's dominant
//! direction, read as two sharper taps along the plane of incidence toward grazing views)
//! against plain R, through what a user sees: the preview's figure per sphere
//! (the energy-weighted relative difference from the full reflectance integral), both
//! lookups against the same ground truth of the same bake.
//!
//! 32-pixel cells and 1024 truth points (the lookup study's: a quarter of the preview's
//! pixels and half its points; figures to a tenth of a per cent, docs/accuracy.md).

mod common;

use splitsum::backend::{Backend, CpuBackend, GpuBackend};
use splitsum::bake::{bake_environment, BakeOptions};
use splitsum::environment::Environment;
use splitsum::plan::scene::Scene;
use splitsum::stages::preview::{compare, render_preview, BakedLight, PreviewOptions};
use splitsum::{Shading, SpecularLookup, SphereStats, SunMode, DEFAULT_LUT_SIZE};

/// Each sphere's figure with R and with the generic lookup.
struct Figures {
    reflect: Vec<SphereStats>,
    generic: Vec<SphereStats>,
}

/// The figures of bundled HDRI `name` baked with `sun`: baked on the CPU (faster than
/// lavapipe), previewed on the GPU when there is one (the truth's integral is the cost).
fn figures(name: &str, sun: SunMode) -> Figures {
    let backend: Box<dyn Backend> = match common::gpu() {
        Some(ctx) => Box::new(GpuBackend { ctx }),
        None => Box::new(CpuBackend),
    };
    let env = Environment::Equirect(common::test_equirect(name));
    let opts = BakeOptions {
        sun,
        ..BakeOptions::default()
    };
    let baked = bake_environment(&CpuBackend, env, &opts, &mut |_| {}, &mut Vec::new()).unwrap();
    let lut = CpuBackend
        .brdf_lut(DEFAULT_LUT_SIZE, DEFAULT_LUT_SIZE)
        .unwrap();
    let light = BakedLight::of(name, &baked, &lut);
    let popts = PreviewOptions {
        cell: 32,
        truth_samples: 1024,
        shading: Shading::GENERIC.with_lookup(SpecularLookup::Reflect),
        ..PreviewOptions::default()
    };
    let reflect = render_preview(&*backend, &light, &popts).unwrap();
    let generic = render_preview(
        &*backend,
        &light,
        &PreviewOptions {
            truth_samples: 0,
            shading: Shading::GENERIC,
            ..popts
        },
    )
    .unwrap();
    let scene = Scene { cell: popts.cell }.uniform();
    Figures {
        generic: compare(&scene, &generic.split_sum, &reflect.truth).1,
        reflect: reflect.stats,
    }
}

/// The metals' spheres with r ≥ `from`: (R's, the generic lookup's).
fn metals(f: &Figures, from: f32) -> Vec<(&SphereStats, &SphereStats)> {
    f.reflect
        .iter()
        .zip(&f.generic)
        .filter(|(r, _)| r.material != "dielectric" && r.roughness >= from)
        .collect()
}

fn describe(name: &str, r: &SphereStats, g: &SphereStats) -> String {
    format!(
        "{name} {} r = {}: generic {:.2} %, R {:.2} %",
        r.material,
        r.roughness,
        100.0 * g.mean_relative,
        100.0 * r.mean_relative
    )
}

/// Every metal at r ≥ 0.5: the generic lookup's figure below R's, and at r = 1 (where it
/// reads along n) at most half of it.
fn bent_beats_r_on_rough_metals(name: &str, f: &Figures) {
    for (r, g) in metals(f, 0.5) {
        assert!(
            g.mean_relative < r.mean_relative,
            "{}",
            describe(name, r, g)
        );
        if r.roughness == 1.0 {
            let half = 0.5 * r.mean_relative;
            assert!(g.mean_relative <= half, "{}", describe(name, r, g));
        }
    }
}

#[test]
fn bent_lookup_closes_the_gap_with_the_sun_split() {
    // With the sun split, the bent lookup at r ≥ 0.5 is below R on every metal, and at
    // r = 1 (where it reads along n) at most half of R's figure (measured: a fifteenth
    // on quarry_01, a quarter on royal_esplanade). At r = 0.25 it is not everywhere: on
    // royal_esplanade it is 5.1 against R's 4.9 % (a narrow lobe wants R), so r = 0.25
    // is held only by the bar below.
    //
    // Every sphere at r ≥ 0.25 within 7 %: not the 5 % a person should see (here
    // quarry_01 measures 3.4 / 5.3 / 6.6 / 2.6 % at r = 0.25 / 0.5 / 0.75 / 1,
    // royal_esplanade 5.1 / 3.0 / 2.3 / 2.5 %, docs/accuracy.md), but today's worst with
    // under half a point of margin for the truth's sampling noise at 1024 points, so that
    // a change losing what the split sun and the lookup bought fails here (Frostbite's
    // single tap is 8.5 % at r = 0.5 on quarry_01).
    for name in ["quarry_01_1k.hdr", "royal_esplanade_1k.hdr"] {
        let f = figures(name, SunMode::Split);
        bent_beats_r_on_rough_metals(name, &f);
        for (r, g) in f.reflect.iter().zip(&f.generic) {
            if r.roughness >= 0.25 {
                assert!(g.mean_relative <= 0.07, "{}", describe(name, r, g));
            }
        }
    }
}

#[test]
fn bent_lookup_on_sunless_hdris() {
    // On the bundled HDRIs without a sun: every metal at r ≥ 0.5 below R and at r = 1 at
    // most half of R's figure (measured: a twentieth on venice_sunset, a fifth on
    // pedestrian_overpass, a third on studio_small_03's soft boxes). What it does not do
    // (docs/accuracy.md): at r = 0.25 it is 0.6 points above R on studio_small_03 in this
    // view (below it over four views), and there the dielectric's figure rises by up to
    // 0.35 points at r = 0.25–0.5 (it falls on the other two).
    for name in [
        "venice_sunset_1k.hdr",
        "pedestrian_overpass_1k.hdr",
        "studio_small_03_1k.hdr",
    ] {
        let f = figures(name, SunMode::Keep);
        bent_beats_r_on_rough_metals(name, &f);
    }
}
