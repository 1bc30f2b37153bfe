//! LUT writers round-trip: what splitsum writes is read back with independent readers
//! (image for PNG, exr for OpenEXR, ktx2 for KTX2, ddsfile for DDS).
mod common;

use splitsum::io::lut::{encode_lut, write_lut, LutWriteOptions};
use splitsum::plan::lut::{BrdfLut, LutQuadrature};

/// A small non-square LUT, so a transposed writer would show.
fn small_lut() -> BrdfLut {
    splitsum::backend::cpu::lut_interpolation::brdf_lut(
        24,
        10,
        &LutQuadrature::default(),
        Default::default(),
    )
}

/// A file in a folder of its own (tests run in parallel and each clears its folder).
fn path(name: &str) -> std::path::PathBuf {
    common::output_dir(&format!("writers-{name}")).join(name)
}

#[test]
fn png_is_16_bit_rgb_with_row_0_at_roughness_0() {
    let lut = small_lut();
    let p = path("lut.png");
    write_lut(&p, &lut, LutWriteOptions::default()).unwrap();
    let img = image::open(&p).unwrap();
    let img = match img {
        image::DynamicImage::ImageRgb16(i) => i,
        other => panic!("expected 16-bit RGB, got {:?}", other.color()),
    };
    assert_eq!(img.dimensions(), (24, 10));
    for j in 0..10 {
        for i in 0..24 {
            let px = img.get_pixel(i, j).0;
            let [a, b] = lut.get(i, j);
            // 16-bit quantisation: within half a step of 1/65535.
            assert!((px[0] as f32 / 65535.0 - a).abs() <= 0.5 / 65535.0 + 1e-7);
            assert!((px[1] as f32 / 65535.0 - b).abs() <= 0.5 / 65535.0 + 1e-7);
            assert_eq!(px[2], 0);
        }
    }
    // Row 0 is roughness ≈ 0: a mirror, A + B ≈ 1 at n·v ≈ 1 (no energy lost).
    let [a, b] = lut.get(23, 0);
    assert!((a + b - 1.0).abs() < 1e-3, "{a} + {b}");
}

#[test]
fn exr_has_float32_r_and_g() {
    use exr::prelude::*;
    let lut = small_lut();
    let p = path("lut.exr");
    write_lut(&p, &lut, LutWriteOptions::default()).unwrap();
    let image = read_first_flat_layer_from_file(&p).unwrap();
    let layer = &image.layer_data;
    assert_eq!(layer.size, Vec2(24, 10));
    let names: Vec<String> = layer
        .channel_data
        .list
        .iter()
        .map(|c| c.name.to_string())
        .collect();
    assert_eq!(names, ["G", "R"]);
    for (ch, c) in layer.channel_data.list.iter().enumerate() {
        let FlatSamples::F32(values) = &c.sample_data else {
            panic!("channel {} is not float32", c.name)
        };
        let comp = 1 - ch; // sorted: G first
        for (k, v) in values.iter().enumerate() {
            assert_eq!(*v, lut.data[k][comp]);
        }
    }
}

#[test]
fn ktx2_is_valid_rg16f_and_rg32f() {
    let lut = small_lut();
    for (f32_out, format, type_size) in [
        (false, ktx2::Format::R16G16_SFLOAT, 2),
        (true, ktx2::Format::R32G32_SFLOAT, 4),
    ] {
        let p = path(if f32_out { "lut32.ktx2" } else { "lut16.ktx2" });
        let bytes = encode_lut(&p, &lut, LutWriteOptions { f32: f32_out }).unwrap();
        let reader = ktx2::Reader::new(&bytes[..]).unwrap();
        let h = reader.header();
        assert_eq!(h.format, Some(format));
        assert_eq!(h.type_size, type_size);
        assert_eq!((h.pixel_width, h.pixel_height, h.pixel_depth), (24, 10, 0));
        assert_eq!((h.layer_count, h.face_count, h.level_count), (0, 1, 1));
        assert_eq!(h.supercompression_scheme, None);
        // Our DFD is the canonical one for the format.
        let (expected, expected_type_size) = ktx2::dfd::Basic::from_format(format).unwrap();
        assert_eq!(reader.basic_dfd(), Some(&expected));
        assert_eq!(expected_type_size, type_size);
        assert!(reader.writer().unwrap().starts_with("splitsum "));
        let level = reader.levels().next().unwrap();
        let values: Vec<f32> = if f32_out {
            level
                .data
                .chunks_exact(4)
                .map(|c| f32::from_le_bytes(c.try_into().unwrap()))
                .collect()
        } else {
            level
                .data
                .chunks_exact(2)
                .map(|c| half::f16::from_le_bytes(c.try_into().unwrap()).to_f32())
                .collect()
        };
        let expected: Vec<f32> = lut.data.iter().flatten().copied().collect();
        let tol = if f32_out { 0.0 } else { 4.9e-4 }; // half: 11-bit significand
        for (v, e) in values.iter().zip(&expected) {
            assert!((v - e).abs() <= tol, "{v} vs {e}");
        }
    }
}

#[test]
fn dds_is_dx10_r16g16_or_r32g32() {
    let lut = small_lut();
    for (f32_out, format) in [
        (false, ddsfile::DxgiFormat::R16G16_Float),
        (true, ddsfile::DxgiFormat::R32G32_Float),
    ] {
        let p = path(if f32_out { "lut32.dds" } else { "lut16.dds" });
        write_lut(&p, &lut, LutWriteOptions { f32: f32_out }).unwrap();
        let dds = ddsfile::Dds::read(std::fs::File::open(&p).unwrap()).unwrap();
        assert_eq!(dds.get_dxgi_format(), Some(format));
        assert_eq!((dds.get_width(), dds.get_height()), (24, 10));
        assert_eq!(dds.get_num_mipmap_levels(), 1);
        let data = dds.get_data(0).unwrap();
        let texel = if f32_out { 8 } else { 4 };
        assert_eq!(data.len(), 24 * 10 * texel);
        let first = if f32_out {
            f32::from_le_bytes(data[0..4].try_into().unwrap())
        } else {
            half::f16::from_le_bytes(data[0..2].try_into().unwrap()).to_f32()
        };
        assert!((first - lut.data[0][0]).abs() <= 4.9e-4);
    }
}

#[test]
fn unknown_extension_is_refused_without_output() {
    let lut = small_lut();
    let p = path("lut.tga");
    let err = write_lut(&p, &lut, LutWriteOptions::default()).unwrap_err();
    let msg = err.to_string();
    assert!(
        msg.contains("lut.tga") && msg.contains("png, exr, ktx2, dds"),
        "{msg}"
    );
    assert!(!p.exists());
}

/// Every LUT model, as written to PNG (16-bit), OpenEXR (f32) and KTX2 (`--f32`: R32G32),
/// read back by the independent readers and held to 1e-4 (relative to max(1, reference))
/// against the converged reference at the spread check texels of a 64² table. PNG stores
/// [0, 1] only, so texels of the sheen models above 1 are left to the float formats; RG16F
/// (the KTX2/DDS default) quantises to 2.4e-4 near 1 and needs `--f32` for this bar.
#[test]
fn every_model_keeps_1e4_in_every_float_file() {
    use exr::prelude::*;
    use splitsum::plan::lut::LutModel;
    let n = 64u32;
    let texels = common::check_texels(n, n);
    for model in LutModel::singles() {
        let lut = splitsum::backend::cpu::lut_interpolation::brdf_lut(
            n,
            n,
            &LutQuadrature::for_model(model),
            model,
        );
        let dir = common::output_dir(&format!("writers-models-{}", model.name()));
        // PNG, R and G in 16 bits.
        let png = dir.join("lut.png");
        write_lut(&png, &lut, LutWriteOptions::default()).unwrap();
        let img = image::open(&png).unwrap().into_rgb16();
        // OpenEXR, float32 R and G.
        let exr_path = dir.join("lut.exr");
        write_lut(&exr_path, &lut, LutWriteOptions::default()).unwrap();
        let exr_image = read_first_flat_layer_from_file(&exr_path).unwrap();
        let mut exr_data = vec![[0f32; 2]; (n * n) as usize];
        for (ch, c) in exr_image.layer_data.channel_data.list.iter().enumerate() {
            let FlatSamples::F32(values) = &c.sample_data else {
                panic!("channel {} is not float32", c.name)
            };
            for (k, v) in values.iter().enumerate() {
                exr_data[k][1 - ch] = *v; // sorted: G first
            }
        }
        // KTX2, R32G32_SFLOAT.
        let ktx_bytes =
            encode_lut(&dir.join("lut.ktx2"), &lut, LutWriteOptions { f32: true }).unwrap();
        let reader = ktx2::Reader::new(&ktx_bytes[..]).unwrap();
        let level = reader.levels().next().unwrap();
        let ktx: Vec<f32> = level
            .data
            .chunks_exact(4)
            .map(|c| f32::from_le_bytes(c.try_into().unwrap()))
            .collect();
        for &(i, j) in &texels {
            let (nv, r) = splitsum::plan::lut::lut_texel_coords(i, j, n, n);
            let (ra, rb) = common::reference_lut_model(nv as f64, r as f64, model);
            let k = (j * n + i) as usize;
            let files: [(&str, [f32; 2]); 3] = [
                (
                    "png",
                    img.get_pixel(i, j).0[..2]
                        .iter()
                        .map(|&v| v as f32 / 65535.0)
                        .collect::<Vec<_>>()
                        .try_into()
                        .unwrap(),
                ),
                ("exr", exr_data[k]),
                ("ktx2", [ktx[2 * k], ktx[2 * k + 1]]),
            ];
            for (format, got) in files {
                for (g, want) in got.iter().zip([ra, rb]) {
                    if format == "png" && want > 1.0 {
                        continue; // clipped, with a warning from `splitsum lut`
                    }
                    let err = (*g as f64 - want).abs() / want.abs().max(1.0);
                    assert!(
                        err <= 1e-4,
                        "{} {format} ({i}, {j}): {g} vs {want}",
                        model.name()
                    );
                }
            }
        }
    }
}

/// `filament-dfg` is its two parts in one file: R, G exactly the multiscatter
/// height-correlated table and B exactly the Charlie cloth albedo, and each format keeps
/// all three channels (PNG 16-bit RGB within 1/131070, OpenEXR R, G, B float32 and KTX2
/// `--f32` RGBA32F with A = 1, both exact).
#[test]
fn filament_dfg_holds_both_parts_in_every_file() {
    use exr::prelude::*;
    use splitsum::backend::Backend;
    use splitsum::plan::lut::LutModel;
    let n = 32u32;
    let cpu = splitsum::backend::CpuBackend;
    let lut = cpu.brdf_lut_model(n, n, LutModel::FilamentDfg).unwrap();
    let rg = cpu
        .brdf_lut_model(n, n, LutModel::MultiscatterSmithCorrelated)
        .unwrap();
    let cloth = cpu.brdf_lut_model(n, n, LutModel::Charlie).unwrap();
    assert_eq!(lut.data, rg.data);
    let b = lut.third.clone().expect("a third channel");
    assert!(b.iter().zip(&cloth.data).all(|(x, c)| *x == c[0]));
    assert!(rg.third.is_none() && cloth.third.is_none());
    let want = |k: usize| [lut.data[k][0], lut.data[k][1], b[k]];

    let dir = common::output_dir("writers-filament-dfg");
    let png = dir.join("dfg.png");
    write_lut(&png, &lut, LutWriteOptions::default()).unwrap();
    let img = image::open(&png).unwrap().into_rgb16();
    let exr_path = dir.join("dfg.exr");
    write_lut(&exr_path, &lut, LutWriteOptions::default()).unwrap();
    let exr_image = read_first_rgba_layer_from_file(
        &exr_path,
        |res, _| vec![[0f32; 3]; res.width() * res.height()],
        move |px: &mut Vec<[f32; 3]>, pos, (r, g, b, _a): (f32, f32, f32, f32)| {
            px[pos.y() * n as usize + pos.x()] = [r, g, b];
        },
    )
    .unwrap();
    let exr_data = exr_image.layer_data.channel_data.pixels;
    let ktx_bytes = encode_lut(&dir.join("dfg.ktx2"), &lut, LutWriteOptions { f32: true }).unwrap();
    let reader = ktx2::Reader::new(&ktx_bytes[..]).unwrap();
    assert_eq!(
        reader.header().format,
        Some(ktx2::Format::R32G32B32A32_SFLOAT)
    );
    let ktx: Vec<f32> = reader
        .levels()
        .next()
        .unwrap()
        .data
        .chunks_exact(4)
        .map(|c| f32::from_le_bytes(c.try_into().unwrap()))
        .collect();
    for k in 0..(n * n) as usize {
        let (i, j) = (k as u32 % n, k as u32 / n);
        let p = img.get_pixel(i, j).0;
        for c in 0..3 {
            let w = want(k)[c];
            if w <= 1.0 {
                assert!((p[c] as f32 / 65535.0 - w).abs() <= 0.5 / 65535.0 + 1e-7);
            }
            assert_eq!(exr_data[k][c], w);
            assert_eq!(ktx[4 * k + c], w);
        }
        assert_eq!(ktx[4 * k + 3], 1.0);
    }
}
