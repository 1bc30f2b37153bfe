//! KTX2 and DDS cubemap outputs: a structural KTX 2.0 validator written from the
//! specification, the `ktx2` and `ddsfile` crates as independent readers, and round trips
//! through splitsum's own cube readers.
mod common;

use splitsum::environment::Cubemap;
use splitsum::io::cubemap::{write_cubemap, CubeLayout, CubeWriteOptions};
use splitsum::io::input::{load_environment, InputOptions};
use splitsum::io::PixelFormat;
use splitsum::Environment;

const FORMATS: [PixelFormat; 4] = [
    PixelFormat::Rgba16f,
    PixelFormat::Rgba32f,
    PixelFormat::Rgb9e5,
    PixelFormat::Rg11b10f,
];

/// A 16² cube with a full mip chain and distinct values per face, texel and level.
fn test_cube() -> Cubemap {
    let mut cube = Cubemap {
        size: 16,
        levels: vec![(0..6 * 256)
            .map(|k| [1.0 + k as f32 / 100.0, 0.5, (k % 16) as f32, 1.0])
            .collect()],
    };
    splitsum::environment::mips::build_mips(&mut cube, 5);
    cube
}

fn u32_at(b: &[u8], o: usize) -> u32 {
    u32::from_le_bytes(b[o..o + 4].try_into().unwrap())
}
fn u64_at(b: &[u8], o: usize) -> u64 {
    u64::from_le_bytes(b[o..o + 8].try_into().unwrap())
}

/// Checks a KTX2 file against the KTX 2.0 specification's structural rules (sections 3.1–3.12).
fn validate_ktx2(bytes: &[u8], format: PixelFormat, size: u32, levels: u32, zstd: bool) {
    // 3.1 identifier
    assert_eq!(
        &bytes[..12],
        &[0xAB, 0x4B, 0x54, 0x58, 0x20, 0x32, 0x30, 0xBB, 0x0D, 0x0A, 0x1A, 0x0A]
    );
    // 3.2 header
    assert_eq!(u32_at(bytes, 12), format.vk_format(), "vkFormat");
    assert_eq!(u32_at(bytes, 16), format.type_size(), "typeSize");
    assert_eq!(
        (u32_at(bytes, 20), u32_at(bytes, 24)),
        (size, size),
        "pixelWidth/Height"
    );
    assert_eq!(u32_at(bytes, 28), 0, "pixelDepth must be 0 for a cubemap");
    assert_eq!(u32_at(bytes, 32), 0, "layerCount 0: not an array");
    assert_eq!(u32_at(bytes, 36), 6, "faceCount");
    assert_eq!(u32_at(bytes, 40), levels, "levelCount");
    assert_eq!(
        u32_at(bytes, 44),
        if zstd { 2 } else { 0 },
        "supercompressionScheme"
    );
    // 3.3 index
    let (dfd_off, dfd_len) = (u32_at(bytes, 48) as usize, u32_at(bytes, 52) as usize);
    let (kvd_off, kvd_len) = (u32_at(bytes, 56) as usize, u32_at(bytes, 60) as usize);
    let (sgd_off, sgd_len) = (u64_at(bytes, 64), u64_at(bytes, 72));
    assert_eq!(
        (sgd_off, sgd_len),
        (0, 0),
        "no supercompression global data for zstd"
    );
    // 3.4 level index follows the header; DFD right after it, 4-aligned.
    let level_index = 80;
    assert_eq!(dfd_off, level_index + 24 * levels as usize);
    assert_eq!(dfd_off % 4, 0);
    // 3.10 DFD: total size word, one basic block.
    assert_eq!(u32_at(bytes, dfd_off) as usize, dfd_len, "dfdTotalSize");
    let block = dfd_off + 4;
    assert_eq!(
        u32_at(bytes, block),
        0,
        "vendorId/descriptorType: Khronos basic"
    );
    let ver = u32_at(bytes, block + 4);
    assert_eq!(ver & 0xffff, 2, "versionNumber");
    assert_eq!((ver >> 16) as usize, dfd_len - 4, "descriptorBlockSize");
    assert_eq!(
        (u32_at(bytes, block + 8) >> 16) & 0xff,
        1,
        "transferFunction linear"
    );
    assert_eq!(
        u32_at(bytes, block + 16),
        format.texel_bytes(),
        "bytesPlane0"
    );
    // 3.11 key/value data follows the DFD, entries 4-aligned.
    assert_eq!(kvd_off, dfd_off + dfd_len);
    let mut p = kvd_off;
    while p < kvd_off + kvd_len {
        let len = u32_at(bytes, p) as usize;
        let kv = &bytes[p + 4..p + 4 + len];
        let nul = kv
            .iter()
            .position(|&b| b == 0)
            .expect("key is NUL terminated");
        assert!(std::str::from_utf8(&kv[..nul]).is_ok());
        p = (p + 4 + len).next_multiple_of(4);
    }
    assert_eq!(p, kvd_off + kvd_len);
    // 3.4/3.12 levels: within the file, stored smallest first, aligned, lengths consistent.
    let align = if zstd {
        1
    } else {
        (format.texel_bytes() as usize).max(4)
    };
    let mut prev_offset = usize::MAX;
    for m in 0..levels as usize {
        let e = level_index + 24 * m;
        let (off, len, raw) = (
            u64_at(bytes, e) as usize,
            u64_at(bytes, e + 8) as usize,
            u64_at(bytes, e + 16) as usize,
        );
        let n = (size >> m).max(1) as usize;
        assert_eq!(
            raw,
            6 * format.image_bytes(n as u32, n as u32),
            "uncompressedByteLength of level {m}"
        );
        if !zstd {
            assert_eq!(len, raw);
        }
        assert_eq!(off % align, 0, "level {m} alignment");
        assert!(
            off >= kvd_off + kvd_len && off + len <= bytes.len(),
            "level {m} inside the file"
        );
        assert!(
            off < prev_offset,
            "level {m} must be stored before level {}",
            m.saturating_sub(1)
        );
        prev_offset = off;
    }
}

/// The block formats (BC6H, ASTC HDR 4×4 and 6×6) in KTX2, with and without zstd, through
/// the same structural checks, each level the size of its whole blocks (a 2² or 1² face one
/// block), the descriptor the `ktx2` crate generates for the format, and read back as an
/// input.
#[test]
fn ktx2_block_cubemaps_are_valid() {
    let cube = test_cube();
    let dir = common::output_dir("containers-ktx2-blocks");
    for format in [
        PixelFormat::Bc6h,
        PixelFormat::Astc4x4Hdr,
        PixelFormat::Astc6x6Hdr,
    ] {
        for zstd in [None, Some(10)] {
            let path = dir.join(format!("{}-{}.ktx2", format.name(), zstd.is_some()));
            let opts = CubeWriteOptions {
                format,
                zstd,
                ..Default::default()
            };
            write_cubemap(&path, &cube, &opts).unwrap();
            let bytes = std::fs::read(&path).unwrap();
            validate_ktx2(&bytes, format, 16, 5, zstd.is_some());
            let reader = ktx2::Reader::new(&bytes[..]).unwrap();
            let vk = ktx2::Format::new(format.vk_format()).unwrap();
            let (canonical, type_size) = ktx2::dfd::Basic::from_format(vk).unwrap();
            assert_eq!(reader.basic_dfd(), Some(&canonical), "{format:?} DFD");
            assert_eq!(type_size, format.type_size());
            let loaded = load_environment(&path, &InputOptions::default()).unwrap();
            let Environment::Cube(c) = loaded.env else {
                panic!("not a cube")
            };
            assert_eq!(c.size, 16);
        }
    }
}

#[test]
fn ktx2_cubemaps_are_valid_and_round_trip() {
    let cube = test_cube();
    let dir = common::output_dir("containers-ktx2");
    for format in FORMATS {
        for zstd in [None, Some(10)] {
            let path = dir.join(format!("{}-{}.ktx2", format.name(), zstd.is_some()));
            let opts = CubeWriteOptions {
                format,
                zstd,
                layout: CubeLayout::Faces,
                ..Default::default()
            };
            write_cubemap(&path, &cube, &opts).unwrap();
            let bytes = std::fs::read(&path).unwrap();
            validate_ktx2(&bytes, format, 16, 5, zstd.is_some());
            // The ktx2 crate reads it and agrees on the DFD for the format.
            let reader = ktx2::Reader::new(&bytes[..]).unwrap();
            let vk = ktx2::Format::new(format.vk_format()).unwrap();
            assert_eq!(reader.header().format, Some(vk));
            let (canonical, type_size) = ktx2::dfd::Basic::from_format(vk).unwrap();
            assert_eq!(reader.basic_dfd(), Some(&canonical), "{format:?} DFD");
            assert_eq!(type_size, format.type_size());
            // Level data decodes back to the cube within the format's precision.
            for (m, level) in reader.levels().enumerate() {
                let raw = match zstd {
                    Some(_) => {
                        zstd::bulk::decompress(level.data, level.uncompressed_byte_length as usize)
                            .unwrap()
                    }
                    None => level.data.to_vec(),
                };
                let back = format.decode(&raw);
                assert_eq!(back.len(), cube.levels[m].len());
                // Tolerance: rg11b10f keeps 6 (B: 5) mantissa bits, ≤ 1/64 relative; rgb9e5
                // shares one exponent, so every channel is within a 1/512 step of the
                // largest channel.
                for (b, c) in back.iter().zip(&cube.levels[m]) {
                    let largest = c[0].max(c[1]).max(c[2]);
                    for k in 0..3 {
                        let tol = c[k].abs() / 64.0 + largest / 512.0;
                        assert!(
                            (b[k] - c[k]).abs() <= tol,
                            "{format:?} level {m}: {b:?} vs {c:?}"
                        );
                    }
                }
            }
            // splitsum reads its own output as a cube input.
            let loaded = load_environment(&path, &InputOptions::default()).unwrap();
            let Environment::Cube(c) = loaded.env else {
                panic!("not a cube")
            };
            assert_eq!(c.size, 16);
        }
    }
}

#[test]
fn dds_cubemaps_load_with_ddsfile() {
    let cube = test_cube();
    let dir = common::output_dir("containers-dds");
    for format in FORMATS {
        let path = dir.join(format!("{}.dds", format.name()));
        let opts = CubeWriteOptions {
            format,
            zstd: None,
            layout: CubeLayout::Faces,
            ..Default::default()
        };
        write_cubemap(&path, &cube, &opts).unwrap();
        let dds = ddsfile::Dds::read(std::fs::File::open(&path).unwrap()).unwrap();
        assert_eq!(
            dds.get_dxgi_format().map(|f| f as u32),
            format.dxgi_format()
        );
        assert_eq!((dds.get_width(), dds.get_height()), (16, 16));
        assert_eq!(dds.get_num_mipmap_levels(), 5);
        assert!(dds.header.caps2.contains(ddsfile::Caps2::CUBEMAP));
        let h10 = dds.header10.as_ref().unwrap();
        assert!(h10.misc_flag.contains(ddsfile::MiscFlag::TEXTURECUBE));
        assert_eq!(dds.get_num_array_layers(), 6);
        // Face 2 (+Y), level 0 comes first in its layer, then its mips.
        let face = dds.get_data(2).unwrap();
        let level0 = format.decode(&face[..256 * format.texel_bytes() as usize]);
        for (b, c) in level0.iter().zip(cube.face(0, 2)) {
            assert!((b[0] - c[0]).abs() <= 0.04 * c[0]);
        }
        let loaded = load_environment(&path, &InputOptions::default()).unwrap();
        let Environment::Cube(c) = loaded.env else {
            panic!("not a cube")
        };
        assert_eq!(c.size, 16);
        for (b, a) in c.levels[0].iter().zip(&cube.levels[0]) {
            assert!((b[0] - a[0]).abs() <= 0.04 * a[0]);
        }
    }
}

/// Face files, crosses (horizontal and vertical) written by splitsum read back as the same
/// cube; the horizontal cross written is continuous across its face edges.
#[test]
fn face_files_and_crosses_round_trip() {
    let cube = test_cube();
    let dir = common::output_dir("containers-faces");
    let exr = dir.join("env.exr");
    let written = write_cubemap(
        &exr,
        &cube,
        &CubeWriteOptions {
            layout: CubeLayout::Faces,
            ..Default::default()
        },
    )
    .unwrap();
    let names: Vec<String> = written
        .iter()
        .map(|p| p.file_name().unwrap().to_string_lossy().into_owned())
        .collect();
    assert_eq!(
        names,
        [
            "env_px.exr",
            "env_nx.exr",
            "env_py.exr",
            "env_ny.exr",
            "env_pz.exr",
            "env_nz.exr"
        ]
    );
    let loaded = splitsum::io::input::load_faces(&written, &InputOptions::default()).unwrap();
    let Environment::Cube(c) = loaded.env else {
        panic!()
    };
    assert_eq!(c.levels[0], cube.levels[0]);

    let cross = dir.join("cross.exr");
    write_cubemap(
        &cross,
        &cube,
        &CubeWriteOptions {
            layout: CubeLayout::Cross,
            ..Default::default()
        },
    )
    .unwrap();
    let loaded = load_environment(&cross, &InputOptions::default()).unwrap();
    let Environment::Cube(c) = loaded.env else {
        panic!("a 4:3 image is a horizontal cross")
    };
    assert_eq!(c.levels[0], cube.levels[0]);

    // A vertical cross built by hand (−Z rotated 180°) reads back the same.
    let n = 16u32;
    let (w, h) = (3 * n, 4 * n);
    let mut img = vec![[0.0f32; 3]; (w * h) as usize];
    for (face, &(col, row)) in splitsum::io::input::VERTICAL_CROSS.iter().enumerate() {
        for j in 0..n {
            for i in 0..n {
                let (fi, fj) = if face == 5 {
                    (n - 1 - i, n - 1 - j)
                } else {
                    (i, j)
                };
                let t = cube.texel(0, face as u32, fi, fj);
                img[((row * n + j) * w + col * n + i) as usize] = [t[0], t[1], t[2]];
            }
        }
    }
    let vpath = dir.join("vcross.exr");
    std::fs::write(&vpath, splitsum::io::exr::encode_rgb32(w, h, &img).unwrap()).unwrap();
    let loaded = load_environment(&vpath, &InputOptions::default()).unwrap();
    let Environment::Cube(c) = loaded.env else {
        panic!("a 3:4 image is a vertical cross")
    };
    assert_eq!(c.levels[0], cube.levels[0]);
}
