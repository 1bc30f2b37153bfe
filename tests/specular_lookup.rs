//! The lookup the README's recipe, the preview and the viewer make
//! (`SpecularLookup::GENERIC`: R bent toward n as the GGX lobe leans, Frostbite's dominant
//! direction, read as two sharper taps along the plane of incidence toward grazing views,
//! the read blended toward E/π by α², `RadianceBlend::AlphaSquared`) against plain R (the
//! chain along R as read, no blend), through what a user sees: the preview's figure per sphere
//! (the energy-weighted relative difference from the full reflectance integral), both
//! lookups against the same ground truth of the same bake.
//!
//! The preview's own cells and truth points (`PreviewOptions::default()`: what
//! `splitsum preview --json` prints, what a user reads). The lookup study's
//! smaller spheres (32-pixel cells, 1024 points) rank the lookups alike but for a few
//! tenths of a point: at 32 pixels a sphere is mostly its grazing rim.

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

/// The figures of bundled HDRI `name` baked with `sun`, in the default preview: baked on
/// the CPU (faster than lavapipe), previewed on the GPU when there is one (the truth's
/// integral is the cost).
fn figures(name: &str, sun: SunMode) -> Figures {
    figures_in(name, sun, PreviewOptions::default())
}

/// [`figures`] in a preview of `cell` and `truth_samples` from `preview`.
fn figures_in(name: &str, sun: SunMode, preview: PreviewOptions) -> Figures {
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
        // Plain R: `with_lookup` drops the recipe's blend with its lookup.
        shading: Shading::GENERIC.with_lookup(SpecularLookup::Reflect),
        ..preview
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

/// Every sphere with r ≥ `from`: (R's, the generic lookup's).
fn spheres(f: &Figures, from: f32) -> Vec<(&SphereStats, &SphereStats)> {
    f.reflect
        .iter()
        .zip(&f.generic)
        .filter(|(r, _)| r.roughness >= from)
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

/// How far above R's figure the generic lookup's may be on a sphere, in the figure's units:
/// none. Both are measured against the same truth (its noise is shared, not a margin),
/// and the generic lookup is below R on every sphere at every r ≥ 0.25 of the five HDRIs.
/// The closest are royal_esplanade's dielectric at r = 0.5, 0.02 points under, and
/// studio_small_03's, 0.06 under (it was 0.38 above before the bend took F0 into account,
/// `math::lookup::fresnel_bend_scale`); among the metals royal_esplanade's at r = 0.5, 0.6
/// to 0.7 points under, and studio_small_03's, 0.8 to 0.9 under (where its soft boxes'
/// edges sit in the lobe; at r = 0.25 they were 0.7 above R before the recipe's bend faded
/// in below r = 0.5, `math::lookup::BEND_FADE_ROUGHNESS`). So a lookup or blend that loses
/// to R anywhere fails.
const SLACK: f32 = 0.0;

/// Every sphere at r ≥ 0.25: the generic lookup's figure at most R's (within [`SLACK`]),
/// and every metal's at r = 1 (where it reads E/π) at most half of it. The dielectric's
/// half at r = 1 is held at more truth points
/// ([`dielectric_at_r_1_halves_r_beyond_the_truths_noise`]): at the preview's 2048 its
/// figures are the truth's noise (0.17 against 0.20 % on pedestrian_overpass).
fn bent_beats_r(name: &str, f: &Figures) {
    for (r, g) in spheres(f, 0.25) {
        assert!(
            g.mean_relative <= r.mean_relative + SLACK,
            "{}",
            describe(name, r, g)
        );
        if r.roughness == 1.0 && r.material != "dielectric" {
            let half = 0.5 * r.mean_relative;
            assert!(g.mean_relative <= half, "{}", describe(name, r, g));
        }
    }
}

#[test]
fn bent_lookup_closes_the_gap_with_the_sun_split() {
    // With the sun split, the generic lookup is at most R's figure on every sphere at
    // r ≥ 0.25, and on every metal at r = 1 (where it reads E/π) at most half of it (measured: a
    // fourteenth on quarry_01, a quarter on royal_esplanade).
    //
    // Every sphere at r ≥ 0.25 within 5 %, what a person should see: quarry_01's worst
    // sphere measures 2.7 / 4.4 / 3.8 / 2.5 % at r = 0.25 / 0.5 / 0.75 / 1 here,
    // royal_esplanade's 2.5 / 3.1 / 2.0 / 2.0 % (docs/accuracy.md), half a point under the
    // bar at its closest, several times the truth's sampling noise (0.1 point at 1024
    // points, less at the preview's 2048), so that a change losing what the split sun, the lookup, the chain's layout and
    // the blend toward E/π bought fails here (with the previous layout, r·(M − 1), and no
    // blend quarry_01 was 6.6 % at r = 0.75; Frostbite's single tap 8.5 % at r = 0.5).
    for name in ["quarry_01_1k.hdr", "royal_esplanade_1k.hdr"] {
        let f = figures(name, SunMode::Split);
        bent_beats_r(name, &f);
        for rough in [0.25, 0.5, 0.75, 1.0] {
            let worst = f
                .generic
                .iter()
                .filter(|g| g.roughness == rough)
                .map(|g| g.mean_relative)
                .fold(0.0f32, f32::max);
            eprintln!("{name} r = {rough}: worst sphere {:.2} %", 100.0 * worst);
        }
        for (r, g) in f.reflect.iter().zip(&f.generic) {
            if r.roughness >= 0.25 {
                assert!(g.mean_relative <= 0.05, "{}", describe(name, r, g));
            }
        }
    }
}

#[test]
fn bent_lookup_on_sunless_hdris() {
    // On the bundled HDRIs without a sun: every sphere at r ≥ 0.25 at most R's figure,
    // and every metal at r = 1 at most half of it (measured: a nineteenth on
    // venice_sunset, a quarter on pedestrian_overpass, a third on studio_small_03's soft
    // boxes).
    for name in [
        "venice_sunset_1k.hdr",
        "pedestrian_overpass_1k.hdr",
        "studio_small_03_1k.hdr",
    ] {
        let f = figures(name, SunMode::Keep);
        bent_beats_r(name, &f);
    }
}

#[test]
fn dielectric_at_r_1_halves_r_beyond_the_truths_noise() {
    // The dielectric at r = 1 on the sunless HDRIs: R's figure is 0.1–1.2 % and the
    // generic lookup's (its read all E/π) is mostly the truth's noise at the preview's
    // 2048 points. At 16384 points (32-pixel cells, to keep the cost of two default
    // previews) the noise is under a third and the figures are 0.068 against 0.66 %
    // (venice_sunset), 0.049 against 0.105 % (pedestrian_overpass) and 0.31 against
    // 1.15 % (studio_small_03): at most half of R's, the closest 0.004 points under.
    // Deterministic (the same quasi-Monte Carlo points), so no margin beyond it.
    let preview = PreviewOptions {
        cell: 32,
        truth_samples: 16384,
        ..PreviewOptions::default()
    };
    for name in [
        "venice_sunset_1k.hdr",
        "pedestrian_overpass_1k.hdr",
        "studio_small_03_1k.hdr",
    ] {
        let f = figures_in(name, SunMode::Keep, preview);
        for (r, g) in spheres(&f, 1.0) {
            if r.material == "dielectric" {
                eprintln!("{}", describe(name, r, g));
                assert!(
                    g.mean_relative <= 0.5 * r.mean_relative,
                    "{}",
                    describe(name, r, g)
                );
            }
        }
    }
}
