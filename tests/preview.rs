//! The preview renders (`splitsum preview`, `bake --preview`): white-furnace values of both
//! renders against their analytic values, the mirror case on a real HDRI (where the
//! split-sum is exact), GPU against CPU, and the command line.

mod common;

use std::f64::consts::PI;

use common::{adaptive, reference_lut, reference_lut_model};
use splitsum::backend::{Backend, CpuBackend};
use splitsum::bake::{bake_environment, BakeOptions};
use splitsum::cpu::preview_split_sum::sample_lut;
use splitsum::environment::{Environment, Equirect};
use splitsum::plan::scene::{pixel_geometry, PixelGeometry, Scene, MATERIALS, ROUGHNESS};
use splitsum::stages::preview::{
    render_preview, shading_irradiance, shading_lut, BakedLight, Preview, PreviewOptions,
};
use splitsum::targets::babylon::BABYLON_SHADING;
use splitsum::targets::bevy::BEVY_SHADING;
use splitsum::targets::filament::FILAMENT_SHADING;
use splitsum::targets::gltf::GLTF_SHADING;
use splitsum::targets::three::THREE_SHADING;
use splitsum::BakedEnvironment;
use splitsum::BrdfLut;
use splitsum::{DiffuseLobe, IblTerms, LutModel, Shading, SpecularLookup};

/// A bake of `env` with `specular_size`, in memory.
fn baked(backend: &dyn Backend, env: Environment, specular_size: u32) -> BakedEnvironment {
    let opts = BakeOptions {
        specular_size,
        ..BakeOptions::default()
    };
    bake_environment(backend, env, &opts, &mut |_| {}, &mut Vec::new()).unwrap()
}

fn white_furnace() -> Environment {
    Environment::Equirect(Equirect {
        width: 64,
        height: 32,
        data: vec![[1.0; 3]; 64 * 32],
    })
}

/// W(n·v) = ∫ (1 − v·h)⁵ (n·l)/π dl over the hemisphere, h = normalize(v + l): the
/// Fresnel weight the truth's diffuse lobe loses, kD(h) = (1 − F0)(1 − W-integrand).
fn diffuse_fresnel_weight(n_dot_v: f64) -> f64 {
    cosine_mean(n_dot_v, |_, v_dot_h| (1.0 - v_dot_h).powi(5))
}

/// ∫ g(n·l, v·h) (n·l)/π dl over the hemisphere, h = normalize(v + l) (v·h = l·h): the
/// cosine-weighted mean of g, by nested adaptive Gauss-Kronrod over θ and φ.
fn cosine_mean(n_dot_v: f64, g: impl Fn(f64, f64) -> f64) -> f64 {
    let sv = (1.0 - n_dot_v * n_dot_v).max(0.0).sqrt();
    let mut outer = |theta: f64| {
        let (st, ct) = theta.sin_cos();
        let mut inner = |phi: f64| {
            let v_dot_l = sv * st * phi.cos() + n_dot_v * ct;
            g(ct, (0.5 * (1.0 + v_dot_l)).max(0.0).sqrt())
        };
        // Symmetric in φ: twice the integral over [0, π].
        2.0 * adaptive(&mut inner, 0.0, PI, 1e-10) * ct * st / PI
    };
    adaptive(&mut outer, 0.0, 0.5 * PI, 1e-7)
}

/// Burley's diffuse albedo over Lambert's, ∫ (1 + (f90 − 1)(1 − n·l)⁵)(1 + (f90 − 1)(1 − n·v)⁵)
/// (n·l)/π dl with f90 = 1/2 + 2 α (l·h)² (Burley 2012), written here from the paper.
fn burley_albedo(n_dot_v: f64, alpha: f64) -> f64 {
    cosine_mean(n_dot_v, |n_dot_l, l_dot_h| {
        let f90 = 0.5 + 2.0 * alpha * l_dot_h * l_dot_h;
        (1.0 + (f90 - 1.0) * (1.0 - n_dot_l).powi(5))
            * (1.0 + (f90 - 1.0) * (1.0 - n_dot_v).powi(5))
    })
}

/// Each sphere pixel's n·v, material and column, with its index in the panel.
fn sphere_pixels(scene: &Scene) -> Vec<(usize, f64, usize, usize)> {
    let s = scene.uniform();
    let mut out = Vec::new();
    for y in 0..s.height {
        for x in 0..s.width {
            if let PixelGeometry::Sphere {
                n,
                v,
                material,
                column,
            } = pixel_geometry(&s, x, y)
            {
                let nv = (n.dot(v) as f64).max(s.min_n_dot_v as f64);
                out.push(((y * s.width + x) as usize, nv, material, column));
            }
        }
    }
    out
}

fn preview(
    backend: &dyn Backend,
    bake: &BakedEnvironment,
    lut: &BrdfLut,
    opts: PreviewOptions,
) -> Preview {
    render_preview(
        backend,
        &splitsum::stages::preview::BakedLight::of("test", bake, lut),
        &opts,
    )
    .unwrap()
}

/// In a white furnace (L = 1 everywhere) every sphere pixel of the split-sum render and of
/// the truth is the BRDF's directional albedo F0·A + B + c (1 − metallic)(1 − F0)
/// (1 − W(n·v)), with (A, B) the converged LUT integrals at its n·v and roughness and W
/// the integral above (the split-sum reads a fit of it, `brdf::diffuse_fresnel_weight`).
/// Both within 1e-3 (absolute, the environment being 1) on both backends. The split-sum's
/// worst, 9.1e-4, is at r = 1: the LUT's last row holds r = 1 − 1/(2·512), and a
/// clamp-to-edge lookup at r = 1 reads it (A changes by 9e-4 over that half texel), as it
/// does in an engine; the fit of W is within 5.4e-4 of it (4.1e-4 of the dielectric's
/// c (1 − F0) = 0.77 times it); the chain and the irradiance are within 1.5e-5 of 1. The
/// truth's is its cold part's quadrature: 6.9e-4 at the default 2048 points (1.35e-3 at
/// 1024, 3.5e-4 at 4096).
#[test]
fn white_furnace_matches_analytic_values() {
    let scene = Scene { cell: 32 };
    let pixels = sphere_pixels(&scene);
    // References per distinct (n·v, roughness): every cell has the same geometry, and n·v
    // depends only on the distance from the cell's centre.
    let refs: Vec<((f64, f64), f64)> = {
        use rayon::prelude::*;
        use std::collections::BTreeMap;
        let keys: BTreeMap<(u64, usize), ()> = pixels
            .iter()
            .map(|&(_, nv, _, c)| ((nv.to_bits(), c), ()))
            .collect();
        let table: BTreeMap<(u64, usize), ((f64, f64), f64)> = keys
            .into_keys()
            .collect::<Vec<_>>()
            .par_iter()
            .map(|&(bits, c)| {
                let nv = f64::from_bits(bits);
                // At r = 0 D is a delta and G = 1: A = 1 − (1 − n·v)⁵, B = (1 − n·v)⁵.
                let ab = match ROUGHNESS[c] {
                    0.0 => (1.0 - (1.0 - nv).powi(5), (1.0 - nv).powi(5)),
                    r => reference_lut(nv, r as f64),
                };
                ((bits, c), (ab, diffuse_fresnel_weight(nv)))
            })
            .collect();
        pixels
            .iter()
            .map(|&(_, nv, _, c)| table[&(nv.to_bits(), c)])
            .collect()
    };
    for backend in common::backends() {
        let bake = baked(backend.as_ref(), white_furnace(), 32);
        let lut = backend.brdf_lut(512, 512).unwrap();
        let p = preview(
            backend.as_ref(),
            &bake,
            &lut,
            PreviewOptions {
                cell: scene.cell,
                ..PreviewOptions::default()
            },
        );
        let (mut worst_ss, mut worst_t) = ((0.0f64, 0usize), (0.0f64, 0usize));
        for (&(k, _, m, _), &((a, b), w)) in pixels.iter().zip(&refs) {
            let mat = MATERIALS[m];
            for ch in 0..3 {
                let f0 = mat.f0[ch] as f64;
                let (albedo, metallic) = (mat.albedo[ch] as f64, mat.metallic as f64);
                let spec = f0 * a + b;
                let want = spec + albedo * (1.0 - metallic) * (1.0 - f0) * (1.0 - w);
                let e_ss = (p.split_sum[k][ch] as f64 - want).abs();
                let e_t = (p.truth[k][ch] as f64 - want).abs();
                if e_ss > worst_ss.0 {
                    worst_ss = (e_ss, k);
                }
                if e_t > worst_t.0 {
                    worst_t = (e_t, k);
                }
            }
        }
        let at = |k: usize| pixels.iter().find(|p| p.0 == k).copied().unwrap();
        eprintln!(
            "{}: split-sum worst {:.2e} at {:?}, truth worst {:.2e} at {:?}",
            backend.description(),
            worst_ss.0,
            at(worst_ss.1),
            worst_t.0,
            at(worst_t.1)
        );
        assert!(worst_ss.0 <= 1e-3, "split-sum {:?}", at(worst_ss.1));
        assert!(worst_t.0 <= 1e-3, "truth {:?}", at(worst_t.1));
    }
}

/// The preview BRDF times n·l, in f64, written from docs/conventions.md's formulas independently of
/// the library: kD(h) c/π + D G F / (4 n·l n·v), all times n·l.
fn brdf_cos(
    n: [f64; 3],
    v: [f64; 3],
    l: [f64; 3],
    r: f64,
    f0: f64,
    albedo: f64,
    metallic: f64,
) -> f64 {
    let dot = |a: [f64; 3], b: [f64; 3]| a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
    let nl = dot(n, l);
    if nl <= 0.0 {
        return 0.0;
    }
    let nv = dot(n, v).max(1e-4);
    let hs = [v[0] + l[0], v[1] + l[1], v[2] + l[2]];
    let len = dot(hs, hs).sqrt();
    let h = hs.map(|c| c / len);
    let (nh, vh) = (dot(n, h).max(0.0), dot(v, h).max(0.0));
    let f = f0 + (1.0 - f0) * (1.0 - vh).powi(5);
    let diffuse = (1.0 - f) * (1.0 - metallic) * albedo / PI;
    if r == 0.0 {
        return diffuse * nl;
    }
    let a2 = (r * r).powi(2);
    let d = a2 / (PI * (nh * nh * (a2 - 1.0) + 1.0).powi(2));
    let k = 0.5 * r * r;
    let g = nl / (nl * (1.0 - k) + k) * nv / (nv * (1.0 - k) + k);
    (diffuse + d * g * f / (4.0 * nl * nv)) * nl
}

/// The ground truth at chosen pixels of a real HDRI's bake against a brute-force sum over
/// every texel of the same environment (the chain's level 0, 256²: 393 216 texels, each
/// at its centre with its exact solid angle), in f64: within 2 % at r ≥ 0.5 and 5 % at
/// r = 0.25, energy-weighted over the pixels. The differences are the truth's quadrature
/// (2048 points) and the hot texels taken at the 64² mip's centroids, against the brute
/// force's own texel-centre rule, which is coarse for the r = 0.25 lobe over a sun.
#[test]
fn truth_matches_brute_force_on_a_real_hdri() {
    use splitsum::math::cubemap::{cube_texel_direction, cube_texel_solid_angle};
    let env = Environment::Equirect(common::test_equirect("quarry_01_1k.hdr"));
    let bake = baked(&CpuBackend, env, 256);
    let lut = CpuBackend.brdf_lut(128, 128).unwrap();
    let scene = Scene { cell: 32 };
    let p = preview(
        &CpuBackend,
        &bake,
        &lut,
        PreviewOptions {
            cell: scene.cell,
            ..PreviewOptions::default()
        },
    );
    let level = &bake.specular.levels[0];
    let n0 = bake.specular.size;
    let texels: Vec<([f64; 3], [f64; 3])> = (0..6 * n0 * n0)
        .map(|k| {
            let (face, j, i) = (k / (n0 * n0), (k / n0) % n0, k % n0);
            let d = cube_texel_direction(face, i as i32, j as i32, n0).map(|c| c as f64);
            let w = cube_texel_solid_angle(i, j, n0) as f64;
            let t = level[k as usize];
            (d, [t[0] as f64 * w, t[1] as f64 * w, t[2] as f64 * w])
        })
        .collect();
    let s = scene.uniform();
    // Along the horizontal diameter of each sphere, every 3rd pixel.
    for (m, mat) in MATERIALS
        .iter()
        .enumerate()
        .filter(|(m, _)| [0usize, 5].contains(m))
    {
        for (c, &r) in ROUGHNESS.iter().enumerate().skip(1) {
            let (mut sum_err, mut sum_ref) = (0.0f64, 0.0f64);
            let y = m as u32 * s.cell + s.cell / 2;
            for x in (c as u32 * s.cell..(c as u32 + 1) * s.cell).step_by(3) {
                let PixelGeometry::Sphere { n, v, .. } = pixel_geometry(&s, x, y) else {
                    continue;
                };
                let (n, v) = (
                    n.to_array().map(|c| c as f64),
                    v.to_array().map(|c| c as f64),
                );
                let mut want = [0.0f64; 3];
                for (d, lw) in &texels {
                    for ch in 0..3 {
                        let f = brdf_cos(
                            n,
                            v,
                            *d,
                            r as f64,
                            mat.f0[ch] as f64,
                            mat.albedo[ch] as f64,
                            mat.metallic as f64,
                        );
                        want[ch] += f * lw[ch];
                    }
                }
                let got = p.truth[(y * s.width + x) as usize];
                for ch in 0..3 {
                    sum_err += (got[ch] as f64 - want[ch]).abs();
                    sum_ref += want[ch];
                }
            }
            let rel = sum_err / sum_ref;
            eprintln!(
                "{} r = {r}: truth vs brute force {:.3} %",
                mat.name,
                100.0 * rel
            );
            let bar = if r < 0.5 { 0.05 } else { 0.02 };
            assert!(rel <= bar, "{} r = {r}: {rel}", mat.name);
        }
    }
}

/// At r = 0 a metal's split-sum is exact (the mirror lookup times the LUT's Fresnel at
/// n·v, for any v): on a real HDRI every metal pixel of the r = 0 column agrees with the
/// truth within 1e-3 (the LUT's bilinear interpolation of 1 − (1 − n·v)⁵ and its f32
/// texels). The dielectric's diffuse term is not exact (the irradiance cube, and kD
/// averaged over the light directions against the truth's kD(h) per direction) and is not
/// checked here.
#[test]
fn mirror_metals_agree_with_truth_on_a_real_hdri() {
    let env = Environment::Equirect(common::test_equirect("quarry_01_1k.hdr"));
    let bake = baked(&CpuBackend, env, 128);
    let lut = CpuBackend.brdf_lut(512, 512).unwrap();
    let p = preview(
        &CpuBackend,
        &bake,
        &lut,
        PreviewOptions {
            cell: 32,
            truth_samples: 16,
            ..PreviewOptions::default()
        },
    );
    for s in p
        .stats
        .iter()
        .filter(|s| s.roughness == 0.0 && s.material != "dielectric")
    {
        assert!(s.worst_relative <= 1e-3, "{s:?}");
    }
}

/// GPU against CPU for both renders on a real HDRI's bake. Split-sum within 1e-5
/// relative (the same lookups; the drivers' normalize and sqrt differ by an ULP or two);
/// truth within 1e-3 of each pixel's luminance: the quadrature points are the same (integer
/// hashes, a table of disk points), but a direction that differs by an ULP can fall on the
/// other side of a texel edge in a bilinear lookup of a hot texel's blacked-out block.
#[test]
fn gpu_renders_match_cpu() {
    let Some(ctx) = common::gpu() else {
        return;
    };
    let gpu = splitsum::backend::GpuBackend { ctx };
    let env = Environment::Equirect(common::test_equirect("venice_sunset_1k.hdr"));
    let bake = baked(&CpuBackend, env, 64);
    let lut = CpuBackend.brdf_lut(128, 128).unwrap();
    let opts = PreviewOptions {
        cell: 16,
        truth_samples: 64,
        ..PreviewOptions::default()
    };
    let worst = |a: &[[f32; 3]], b: &[[f32; 3]]| {
        a.iter()
            .zip(b)
            .map(|(x, y)| {
                let (lx, ly) = (
                    splitsum::stages::preview::picture::luminance(*x),
                    splitsum::stages::preview::picture::luminance(*y),
                );
                ((lx - ly).abs() / ly.abs().max(1e-6)) as f64
            })
            .fold(0.0, f64::max)
    };
    // The recipe, and each engine's shading (its LUT computed once, on the CPU, so both
    // backends read the same table; its diffuse light read from the same bake).
    for shading in [
        Shading::GENERIC,
        Shading::GENERIC.with_lookup(SpecularLookup::Filtered),
        THREE_SHADING,
        FILAMENT_SHADING,
        GLTF_SHADING,
        BEVY_SHADING,
        BABYLON_SHADING,
    ] {
        let table = match shading == Shading::GENERIC {
            true => lut.clone(),
            false => shading_lut(&CpuBackend, &shading, None).unwrap(),
        };
        let irradiance = shading_irradiance(&shading, &bake);
        let light = BakedLight {
            irradiance: &irradiance,
            ..BakedLight::of("test", &bake, &table)
        };
        let opts = PreviewOptions { shading, ..opts };
        let cpu = render_preview(&CpuBackend, &light, &opts).unwrap();
        let gpu = render_preview(&gpu, &light, &opts).unwrap();
        let (ss, t) = (
            worst(&gpu.split_sum, &cpu.split_sum),
            worst(&gpu.truth, &cpu.truth),
        );
        eprintln!(
            "{}: GPU vs CPU: split-sum {ss:.2e}, truth {t:.2e}",
            shading.name
        );
        assert!(ss <= 1e-5, "{}: split-sum {ss}", shading.name);
        assert!(t <= 1e-3, "{}: truth {t}", shading.name);
    }
}

/// Each engine's mode in a white furnace (L = 1 everywhere), at r ≥ 0.25 (at r = 0 the
/// engines' minimum roughness makes the truth's lobe a few texels wide):
/// - the truth is the directional albedo of the engine's own BRDF: (F0 A_c + B_c) times
///   its compensation 1 + F0 (1/(A + B) − 1) where it has one ((A, B) the engine's table
///   as the kernel reads it), plus c (1 − m) times (1 − F0)(1 − W(n·v)) for a
///   Fresnel-weighted Lambert, 1 for a plain one, 1 − F0 for Babylon's or Burley's albedo
///   (`burley_albedo`),
///   (A_c, B_c) the converged height-correlated integrals (`reference_lut_model`) and W the
///   integral above: within
///   1.5e-3, the quadrature's 6.9e-4 at 2048 points times the compensation (up to 1.6 on a
///   rough metal) and the dielectric's c = 0.8;
/// - the split-sum is the engine's combination of S = 1, E = 1 and its table's (A, B),
///   written here from `plan::shading`'s formulas: FssEss = kS A + B, Ems = 1 − A − B,
///   Favg = F0 + (1 − F0)/21, FmsEms = Ems FssEss Favg / (1 − Ems Favg) (a blend of S
///   toward E is the furnace's 1); within 1e-4 (the
///   furnace chain's levels and irradiance are within 1.5e-5 of 1, the rest is f32).
#[test]
fn engine_modes_in_a_white_furnace() {
    let scene = Scene { cell: 32 };
    let pixels: Vec<_> = sphere_pixels(&scene)
        .into_iter()
        .filter(|&(_, _, _, c)| ROUGHNESS[c] >= 0.25)
        .collect();
    type Refs = std::collections::BTreeMap<(u64, usize), ((f64, f64), f64, f64)>;
    let refs: Refs = {
        use rayon::prelude::*;
        let keys: std::collections::BTreeSet<(u64, usize)> = pixels
            .iter()
            .map(|&(_, nv, _, c)| (nv.to_bits(), c))
            .collect();
        keys.into_iter()
            .collect::<Vec<_>>()
            .par_iter()
            .map(|&(bits, c)| {
                let nv = f64::from_bits(bits);
                let r = ROUGHNESS[c] as f64;
                let ab = reference_lut_model(nv, r, LutModel::SmithCorrelated);
                (
                    (bits, c),
                    (ab, diffuse_fresnel_weight(nv), burley_albedo(nv, r * r)),
                )
            })
            .collect()
    };
    for backend in common::backends() {
        let bake = baked(backend.as_ref(), white_furnace(), 32);
        for shading in [
            THREE_SHADING,
            FILAMENT_SHADING,
            GLTF_SHADING,
            BEVY_SHADING,
            BABYLON_SHADING,
        ] {
            let table = shading_lut(&CpuBackend, &shading, None).unwrap();
            let irradiance = shading_irradiance(&shading, &bake);
            let light = BakedLight {
                irradiance: &irradiance,
                ..BakedLight::of("test", &bake, &table)
            };
            let opts = PreviewOptions {
                cell: scene.cell,
                shading,
                ..PreviewOptions::default()
            };
            let p = render_preview(backend.as_ref(), &light, &opts).unwrap();
            let (mut worst_ss, mut worst_t) = (0.0f64, 0.0f64);
            for &(k, nv, m, c) in &pixels {
                let ((ac, bc), w, burley) = refs[&(nv.to_bits(), c)];
                let r = ROUGHNESS[c] as f64;
                let [a, b] = sample_lut(&table, nv as f32, r as f32).map(|x| x as f64);
                let mat = MATERIALS[m];
                for ch in 0..3 {
                    let f0 = mat.f0[ch] as f64;
                    let (albedo, metallic) = (mat.albedo[ch] as f64, mat.metallic as f64);
                    let compensation = match shading.light.compensated {
                        true => 1.0 + f0 * (1.0 / (a + b) - 1.0),
                        false => 1.0,
                    };
                    let lambert = match shading.light.diffuse {
                        DiffuseLobe::FresnelWeighted => (1.0 - f0) * (1.0 - w),
                        DiffuseLobe::Lambert => 1.0,
                        DiffuseLobe::Burley => burley,
                        DiffuseLobe::DielectricLambert => 1.0 - f0,
                    };
                    let truth = (f0 * ac + bc) * compensation + albedo * (1.0 - metallic) * lambert;
                    let ks = match shading.terms.roughness_fresnel {
                        true => f0 + ((1.0 - r).max(f0) - f0) * (1.0 - nv).powi(5),
                        false => f0,
                    };
                    let fss = ks * a + b;
                    let ems = 1.0 - a - b;
                    let favg = f0 + (1.0 - f0) / 21.0;
                    let fms = ems * fss * favg / (1.0 - ems * favg);
                    let diffuse = albedo * (1.0 - metallic);
                    let split = match shading.terms.ibl {
                        IblTerms::EnergyCompensated => {
                            fss * (1.0 + f0 * (1.0 / (a + b) - 1.0)) + diffuse * (1.0 - fss)
                        }
                        IblTerms::MultiscatterIrradiance | IblTerms::MultiscatterRadiance => {
                            fss + fms + diffuse * (1.0 - fss - fms)
                        }
                        IblTerms::LegacyDiffuse => {
                            fss * (1.0 + f0 * (1.0 / (a + b) - 1.0)) + diffuse * (1.0 - f0)
                        }
                        IblTerms::Splitsum => unreachable!("engines only"),
                    };
                    worst_t = worst_t.max((p.truth[k][ch] as f64 - truth).abs());
                    worst_ss = worst_ss.max((p.split_sum[k][ch] as f64 - split).abs());
                }
            }
            eprintln!(
                "{} on {}: split-sum worst {worst_ss:.2e}, truth worst {worst_t:.2e}",
                shading.name,
                backend.description()
            );
            assert!(worst_ss <= 1e-4, "{}: split-sum {worst_ss}", shading.name);
            assert!(worst_t <= 1.5e-3, "{}: truth {worst_t}", shading.name);
        }
    }
}

/// Fails the test with the command's stderr unless it exited 0.
fn assert_succeeded(out: &std::process::Output) {
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
}

/// The stderr of a command that must exit 1 (a job failed).
fn failure_message(out: &std::process::Output) -> String {
    assert_eq!(out.status.code(), Some(1));
    String::from_utf8_lossy(&out.stderr).into_owned()
}

/// `splitsum preview` of an environment and of a bake folder, and `bake --preview`: the
/// PNG exists with the picture's size, the table is printed, the manifest lists the preview
/// with its per-sphere numbers; a bake for another target is refused with a message; an
/// engine's mode names its shading.
#[test]
fn preview_command_line() {
    let dir = common::output_dir("preview_cli");
    let hdr = "tests/data/venice_sunset_1k.hdr";
    let png = dir.join("venice.png");
    let out = common::splitsum()
        .args(["preview", hdr, "-o"])
        .arg(&png)
        .args([
            "--specular-size",
            "64",
            "--preview-cell",
            "16",
            "--truth-samples",
            "16",
        ])
        .output()
        .unwrap();
    assert_succeeded(&out);
    let table = String::from_utf8_lossy(&out.stdout);
    assert!(
        table.contains("dielectric") && table.contains("r = 0.75"),
        "{table}"
    );
    let img = image::open(&png).unwrap();
    assert!(img.height() > 6 * 16);
    assert!(img.width() > 3 * 5 * 16);

    let out = common::splitsum()
        .args(["bake", hdr, "-o"])
        .arg(&dir)
        .args([
            // The input's own resolution (1024 / 4): the truth of the bake in memory reads
            // the chain's level 0 then, as the folder's does.
            "--specular-size",
            "256",
            "--preview",
            "--preview-cell",
            "16",
            "--truth-samples",
            "16",
            "--quiet",
        ])
        .output()
        .unwrap();
    assert_succeeded(&out);
    let bake_dir = dir.join("venice_sunset_1k");
    let manifest: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(bake_dir.join("manifest.json")).unwrap())
            .unwrap();
    assert_eq!(manifest["preview"]["spheres"].as_array().unwrap().len(), 30);
    assert!(manifest["outputs"]
        .as_array()
        .unwrap()
        .iter()
        .any(|o| o["file"] == "preview.png"));
    let baked_png = std::fs::read(bake_dir.join("preview.png")).unwrap();

    // The folder read back renders the picture the bake did in memory, up to the rgba16f
    // storage of the chain and irradiance and the 16-bit LUT (its truth reads the chain's
    // level 0, the input's own resolution here).
    let again = dir.join("again.png");
    let out = common::splitsum()
        .arg("preview")
        .arg(&bake_dir)
        .arg("-o")
        .arg(&again)
        .args(["--preview-cell", "16", "--truth-samples", "16"])
        .output()
        .unwrap();
    assert_succeeded(&out);
    let (a, b) = (
        image::load_from_memory(&baked_png).unwrap().to_rgb8(),
        image::open(&again).unwrap().to_rgb8(),
    );
    assert_eq!(a.dimensions(), b.dimensions());
    let total: i64 = a
        .pixels()
        .zip(b.pixels())
        .flat_map(|(p, q)| (0..3).map(move |c| (p.0[c] as i64 - q.0[c] as i64).abs()))
        .sum();
    let mean = total as f64 / (3 * a.width() * a.height()) as f64;
    // Mean over the picture: a few texels near the hot threshold may change side in
    // rgba16f, which moves the 16-point truth and its heat map locally.
    assert!(mean <= 0.5, "mean 8-bit difference {mean}");

    let out = common::splitsum()
        .args(["bake", hdr, "-o"])
        .arg(dir.join("bevy"))
        .args(["--specular-size", "64", "--target", "bevy", "--quiet"])
        .output()
        .unwrap();
    assert_succeeded(&out);
    let out = common::splitsum()
        .arg("preview")
        .arg(dir.join("bevy/venice_sunset_1k"))
        .output()
        .unwrap();
    let err = failure_message(&out);
    assert!(
        err.contains("target bevy") && err.contains("bake --preview"),
        "{err}"
    );

    // An engine's mode: the JSON names the shading and its lookup; Babylon.js's reads the
    // bake's SH.
    let small = [
        "--specular-size",
        "64",
        "--preview-cell",
        "16",
        "--truth-samples",
        "16",
    ];
    for (target, shading, lookup) in [
        ("three", "three.js r187", "alpha2"),
        ("babylon", "Babylon.js 9.35", "reflect"),
    ] {
        let json = dir.join(format!("{target}.json"));
        let out = common::splitsum()
            .args(["preview", hdr, "--target", target, "-o"])
            .arg(dir.join(format!("{target}.png")))
            .arg("--json")
            .arg(&json)
            .args(small)
            .output()
            .unwrap();
        assert_succeeded(&out);
        let figures: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(&json).unwrap()).unwrap();
        assert_eq!(figures["shading"], shading);
        assert_eq!(figures["lookup"], lookup);
    }

    // A folder that is not a bake, and a cell outside the range, are one clear line each.
    let empty = dir.join("empty");
    std::fs::create_dir_all(&empty).unwrap();
    let out = common::splitsum()
        .arg("preview")
        .arg(&empty)
        .output()
        .unwrap();
    let err = failure_message(&out);
    assert!(err.contains("no manifest.json"), "{err}");
    let out = common::splitsum()
        .args(["preview", hdr, "--preview-cell", "4"])
        .output()
        .unwrap();
    // A usage error, refused before the input is read.
    assert_eq!(out.status.code(), Some(2));
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains("invalid --preview-cell"), "{err}");
}
