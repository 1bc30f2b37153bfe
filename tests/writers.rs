//! LUT writers round-trip: what splitsum writes is read back with independent readers
//! (image for PNG, exr for OpenEXR, ktx2 for KTX2, ddsfile for DDS).
mod common;

use splitsum::io::lut::{encode_lut, write_lut, LutWriteOptions};
use splitsum::lut::{BrdfLut, LutQuadrature};

/// A small non-square LUT, so a transposed writer would show.
fn small_lut() -> BrdfLut {
    splitsum::cpu::brdf_lut::brdf_lut(24, 10, &LutQuadrature::default(), Default::default())
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
