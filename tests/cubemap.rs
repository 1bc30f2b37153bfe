//! HDRI → cubemap: orientation, energy on real HDRIs for every pixel format, mips, GPU vs
//! CPU.
mod common;

use splitsum::backend::{Backend, CpuBackend, GpuBackend};
use splitsum::environment::walk::texel_centres;
use splitsum::environment::{Cubemap, Environment, Equirect};
use splitsum::io::cubemap::encode_texture;
use splitsum::io::input::{load_environment, InputOptions};
use splitsum::io::PixelFormat;
use splitsum::math::cubemap::{
    cube_face_coords, cube_face_direction, cube_texel_solid_angle, equirect_direction, normalize,
};
use splitsum::stages::convert::environment_to_cube;

/// An equirect whose radiance is its own direction + 1 (all channels positive).
fn direction_env(width: u32) -> Equirect {
    let h = width / 2;
    let data = (0..h)
        .flat_map(|y| (0..width).map(move |x| (x, y)))
        .map(|(x, y)| {
            let d =
                equirect_direction((x as f32 + 0.5) / width as f32, (y as f32 + 0.5) / h as f32);
            [d[0] + 1.0, d[1] + 1.0, d[2] + 1.0]
        })
        .collect();
    Equirect {
        width,
        height: h,
        data,
    }
}

/// docs/conventions.md, "Cube faces": a shader sampling the cube with direction d gets the radiance from d. With
/// L(d) = d + 1 stored in a 1024×512 RGBE file, every texel of a 32 cube must hold its
/// centre direction + 1. Tolerance 0.03: RGBE keeps 8 mantissa bits of
/// the largest channel (≤ 2/256 here) and the footprint mean of d over a 32² texel differs
/// from the centre direction by ≤ 0.01.
#[test]
fn every_texel_looks_the_right_way() {
    let dir = common::output_dir("cube-orientation");
    let path = dir.join("direction.hdr");
    let env = direction_env(1024);
    let rgb: Vec<[f32; 3]> = env.data.clone();
    std::fs::write(
        &path,
        splitsum::io::hdr::encode(env.width, env.height, &rgb),
    )
    .unwrap();
    let loaded = load_environment(&path, &InputOptions::default()).unwrap();
    assert!(matches!(loaded.env, Environment::Equirect(_)));
    for backend in common::backends() {
        let cube = environment_to_cube(backend.as_ref(), &loaded.env, 32, false, 0.0).unwrap();
        let mut worst = 0.0f32;
        for (face, i, j, _) in texel_centres(32) {
            let s = (i as f32 + 0.5) / 16.0 - 1.0;
            let t = (j as f32 + 0.5) / 16.0 - 1.0;
            let d = normalize(cube_face_direction(face, s, t));
            let got = cube.texel(0, face, i, j);
            for c in 0..3 {
                worst = worst.max((got[c] - (d[c] + 1.0)).abs());
            }
        }
        println!(
            "{}: worst orientation error {worst:.4}",
            backend.description()
        );
        assert!(worst <= 0.03, "{}: {worst}", backend.description());
    }
}

/// --rotate 90 turns what was at +X to −Z (right-handed about +Y).
#[test]
fn rotation_turns_x_towards_minus_z() {
    let env = Environment::Equirect(direction_env(256));
    let cube = environment_to_cube(&CpuBackend, &env, 16, false, 90.0).unwrap();
    // −Z (face 5) now shows what +X showed: texel (i, j) of −Z looks along
    // (−s, −t, −1), which the rotation maps back to (1, −t, −s) in the source.
    for (i, j) in [(8u32, 8u32), (2, 13), (15, 0)] {
        let (s, t) = ((i as f32 + 0.5) / 8.0 - 1.0, (j as f32 + 0.5) / 8.0 - 1.0);
        let d = normalize([1.0, -t, -s]);
        let got = cube.texel(0, 5, i, j);
        for c in 0..3 {
            assert!(
                (got[c] - (d[c] + 1.0)).abs() < 0.03,
                "texel ({i}, {j}): {got:?} vs {d:?} + 1"
            );
        }
    }
}

/// Per-face ∫ L dω taken directly over the equirect: 8×8 sub-samples per texel, each
/// assigned to the face its own direction lands on.
fn face_integrals_from_equirect(e: &Equirect) -> [[f64; 3]; 6] {
    let mut out = [[0.0f64; 3]; 6];
    const SUB: u32 = 8;
    for y in 0..e.height {
        let omega = e.row_solid_angle(y) / (SUB * SUB) as f64;
        for x in 0..e.width {
            let l = e.get(x, y);
            for sy in 0..SUB {
                for sx in 0..SUB {
                    let u = (x as f32 + (sx as f32 + 0.5) / SUB as f32) / e.width as f32;
                    let v = (y as f32 + (sy as f32 + 0.5) / SUB as f32) / e.height as f32;
                    let (face, _, _) = cube_face_coords(equirect_direction(u, v));
                    for c in 0..3 {
                        out[face as usize][c] += l[c] as f64 * omega;
                    }
                }
            }
        }
    }
    out
}

/// Per-face ∫ L dω of cube level `m`.
fn face_integrals_from_cube(cube: &Cubemap, m: usize) -> [[f64; 3]; 6] {
    let n = cube.level_size(m);
    let mut out = [[0.0f64; 3]; 6];
    for (face, i, j, _) in texel_centres(n) {
        let w = cube_texel_solid_angle(i, j, n) as f64;
        let t = cube.texel(m, face, i, j);
        for c in 0..3 {
            out[face as usize][c] += t[c] as f64 * w;
        }
    }
    out
}

fn luminance(c: [f64; 3]) -> f64 {
    0.2126 * c[0] + 0.7152 * c[1] + 0.0722 * c[2]
}

/// Every face's solid-angle-weighted mean radiance equals the integral taken directly over
/// the equirect within 2 %, for every pixel format, on every real test HDRI; the 1×1 mip
/// keeps the mean of level 0 within 5 % (the reduction conserves it exactly up to
/// rounding).
#[test]
fn real_hdris_keep_their_energy_in_every_format() {
    let dir = std::path::Path::new("tests/data");
    if !dir.exists() {
        panic!("test data missing: {} (see README)", dir.display());
    }
    let backend: Box<dyn Backend> = match common::gpu() {
        Some(ctx) => Box::new(GpuBackend { ctx }),
        None => Box::new(CpuBackend),
    };
    for name in common::BUNDLED_HDRIS {
        let loaded = load_environment(&dir.join(name), &InputOptions::default()).unwrap();
        let Environment::Equirect(e) = &loaded.env else {
            panic!("{name} is not an equirect")
        };
        let reference = face_integrals_from_equirect(e);
        let cube = environment_to_cube(backend.as_ref(), &loaded.env, 256, true, 0.0).unwrap();
        for format in [
            PixelFormat::Rgba32f,
            PixelFormat::Rgba16f,
            PixelFormat::Rg11b10f,
            PixelFormat::Rgb9e5,
        ] {
            let enc = encode_texture(&cube, format, &Default::default()).unwrap();
            let decoded = Cubemap {
                size: cube.size,
                levels: enc.levels.iter().map(|l| format.decode(l)).collect(),
            };
            let got = face_integrals_from_cube(&decoded, 0);
            for face in 0..6 {
                let (r, g) = (luminance(reference[face]), luminance(got[face]));
                let rel = (g - r).abs() / r;
                assert!(
                    rel <= 0.02,
                    "{name} {format:?} face {face}: {g} vs {r} ({:.2} %)",
                    rel * 100.0
                );
            }
            let total = |f: [[f64; 3]; 6]| f.iter().map(|&c| luminance(c)).sum::<f64>();
            let last = decoded.levels.len() - 1;
            let rel =
                (total(face_integrals_from_cube(&decoded, last)) - total(got)).abs() / total(got);
            assert!(
                rel <= 0.05,
                "{name} {format:?}: coarsest mip off by {:.2} %",
                rel * 100.0
            );
        }
    }
}

/// GPU and CPU conversions agree. Both run the same footprint estimator on the same
/// pyramid in f32 with the same polynomial atan (`math::trig`), so what remains is the few
/// ULP Vulkan allows for sqrt, division and log2 (and FMA contraction), which move sample
/// positions and filter weights by ~1e-7. Where the image is smooth that is a relative
/// difference; next to a light 10⁵× brighter than its surroundings the same shift moves a
/// dark texel by a fraction of the light's radiance. Tolerance: 1e-4 of the texel plus
/// 1e-6 of the image's maximum. Measured on lavapipe: 3e-7 relative.
#[test]
fn gpu_conversion_matches_cpu() {
    let Some(ctx) = common::gpu() else { return };
    let gpu = GpuBackend { ctx };
    let env = Environment::Equirect(
        load_environment(
            std::path::Path::new("tests/data/studio_small_03_1k.hdr"),
            &InputOptions::default(),
        )
        .map(|l| match l.env {
            Environment::Equirect(e) => e,
            _ => unreachable!(),
        })
        .unwrap(),
    );
    for (size, rotate) in [(64u32, 0.0f32), (128, 33.0)] {
        let a = environment_to_cube(&gpu, &env, size, true, rotate).unwrap();
        let b = environment_to_cube(&CpuBackend, &env, size, true, rotate).unwrap();
        assert_eq!(a.levels.len(), b.levels.len());
        let max = b.levels[0]
            .iter()
            .flat_map(|t| t[..3].to_vec())
            .fold(0.0f32, f32::max);
        let (mut worst_rel, mut worst_abs) = (0.0f32, 0.0f32);
        for (m, (la, lb)) in a.levels.iter().zip(&b.levels).enumerate() {
            let mut level_worst = 0.0f32;
            for (ta, tb) in la.iter().zip(lb) {
                for c in 0..3 {
                    level_worst = level_worst.max((ta[c] - tb[c]).abs() / tb[c].abs().max(1e-6));
                }
                for c in 0..3 {
                    let d = (ta[c] - tb[c]).abs();
                    worst_rel = worst_rel.max(d / tb[c].abs().max(1e-6));
                    worst_abs = worst_abs.max(d / max);
                    assert!(
                        d <= 1e-4 * tb[c].abs() + 1e-6 * max,
                        "{} vs {} (max {max})",
                        ta[c],
                        tb[c]
                    );
                }
            }
            println!("  level {m}: worst relative {level_worst:.2e}");
        }
        println!("size {size}: worst |gpu - cpu| relative {worst_rel:.2e}, relative to the max {worst_abs:.2e}");
    }
}

/// Downsizing a high-frequency HDRI does not alias: a fine checkerboard averages to its mean.
#[test]
fn downsizing_does_not_alias() {
    let (w, h) = (2048u32, 1024u32);
    let data = (0..h)
        .flat_map(|y| (0..w).map(move |x| (x, y)))
        .map(|(x, y)| if (x + y) % 2 == 0 { [2.0; 3] } else { [0.0; 3] })
        .collect();
    let env = Environment::Equirect(Equirect {
        width: w,
        height: h,
        data,
    });
    for backend in common::backends() {
        let cube = environment_to_cube(backend.as_ref(), &env, 16, false, 0.0).unwrap();
        for t in &cube.levels[0] {
            assert!(
                (t[0] - 1.0).abs() < 0.02,
                "{}: {}",
                backend.description(),
                t[0]
            );
        }
    }
}

/// An input wider than the device's max_texture_dimension_2d is read from its first level
/// that fits instead of failing wgpu validation.
#[test]
fn inputs_beyond_the_texture_limit_are_reduced() {
    if common::gpu().is_none() {
        return;
    }
    let instance =
        wgpu::Instance::new(wgpu::InstanceDescriptor::new_without_display_handle_from_env());
    let adapter = pollster::block_on(instance.request_adapter(&Default::default())).unwrap();
    let limits = wgpu::Limits {
        max_texture_dimension_2d: 1024,
        ..adapter.limits()
    };
    let (device, queue) = pollster::block_on(adapter.request_device(&wgpu::DeviceDescriptor {
        required_limits: limits,
        ..Default::default()
    }))
    .unwrap();
    let env = direction_env(2048);
    let params =
        splitsum::plan::convert::EquirectToCubeParams::new(512, env.width, env.height, 0.0);
    assert_eq!(
        params.base_level, 0,
        "a 512 cube reads level 0 of a 2048-wide input"
    );
    let source = splitsum::environment::EquirectIntegral::new(env);
    let cube =
        splitsum::gpu::equirect_to_cube::equirect_to_cube(&device, &queue, &source, &params, 1)
            .unwrap();
    // Still the right picture: texel (i, j) of +X looks along its own direction.
    for (i, j) in [(0u32, 0u32), (256, 100), (511, 511)] {
        let d = splitsum::math::cubemap::cube_texel_direction(0, i as i32, j as i32, 512);
        let t = cube.texel(0, 0, i, j);
        for c in 0..3 {
            assert!((t[c] - (d[c] + 1.0)).abs() < 0.03, "{t:?} vs {d:?}");
        }
    }
}

/// With `InputOptions::cube_size` an equirect is reduced while it is read (row by row for
/// .hdr, right after decoding for .exr) to the pyramid level the conversion integrates.
/// The cube must be the one converted from the full-size image: the level is
/// bit-identical (tested in `environment::pyramid`) and so is the integral over it.
#[test]
fn reducing_on_load_gives_the_same_cube() {
    let inputs = [
        std::path::PathBuf::from("tests/data/venice_sunset_1k.hdr"),
        std::path::PathBuf::from("tests/data/venice_sunset_1k_f32_piz.exr"),
    ];
    let backend = CpuBackend;
    for path in inputs.iter().filter(|p| p.exists()) {
        let full = load_environment(path, &InputOptions::default()).unwrap();
        // Tiny cubes: a 1k input is integrated at full resolution from 4² up.
        for size in [1u32, 2] {
            let opts = InputOptions {
                cube_size: Some(size),
                ..Default::default()
            };
            let reduced = load_environment(path, &opts).unwrap();
            let (Environment::Equirect(f), Environment::Equirect(r)) = (&full.env, &reduced.env)
            else {
                panic!("{} is not an equirect", path.display());
            };
            let levels = splitsum::io::input::reduction_levels(f.height, size);
            assert!(levels >= 1, "{size}: only {levels} halvings");
            assert_eq!(r.height, f.height >> levels, "{}", path.display());
            let a = environment_to_cube(&backend, &full.env, size, true, 30.0).unwrap();
            let b = environment_to_cube(&backend, &reduced.env, size, true, 30.0).unwrap();
            let mut worst = 0.0f32;
            for (la, lb) in a.levels.iter().zip(&b.levels) {
                for (ta, tb) in la.iter().zip(lb) {
                    for c in 0..3 {
                        worst = worst.max((ta[c] - tb[c]).abs() / ta[c].abs().max(1e-6));
                    }
                }
            }
            assert!(worst == 0.0, "{} at {size}: {worst}", path.display());
            eprintln!(
                "{} at {size}: worst relative difference {worst:.2e}",
                path.display()
            );
        }
    }
}

/// Converting an owned environment (no copy of the finest level) gives exactly what
/// converting a borrowed one gives, for an equirect read whole or reduced and for a cube
/// kept as it is or resampled.
#[test]
fn owned_and_borrowed_conversions_agree() {
    use splitsum::stages::convert::environment_into_cube;
    let path = std::path::Path::new("tests/data/venice_sunset_1k.hdr");
    for cube_size in [None, Some(16)] {
        let opts = InputOptions {
            cube_size,
            ..Default::default()
        };
        let env = load_environment(path, &opts).unwrap().env;
        let a = environment_to_cube(&CpuBackend, &env, 16, true, 0.0).unwrap();
        let b = environment_into_cube(&CpuBackend, env, 16, true, 0.0).unwrap();
        assert_eq!(a, b, "equirect, reduced on load: {cube_size:?}");
    }
    let env = load_environment(path, &InputOptions::default())
        .unwrap()
        .env;
    let cube = Environment::Cube(environment_to_cube(&CpuBackend, &env, 32, true, 0.0).unwrap());
    for (size, rotate) in [(32, 0.0), (16, 0.0), (32, 90.0)] {
        let a = environment_to_cube(&CpuBackend, &cube, size, true, rotate).unwrap();
        let b = environment_into_cube(&CpuBackend, cube.clone(), size, true, rotate).unwrap();
        assert_eq!(a, b, "cube {size} rotated {rotate}");
    }
}
