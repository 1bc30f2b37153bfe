//! Bad inputs: a non-zero exit, one clear line naming the file and the problem, no panic,
//! no output file left behind.
mod common;

use std::path::Path;
use std::process::Command;

/// Runs `splitsum cubemap INPUT -o <dir>/out.ktx2`; returns (exit code, stderr).
fn convert(input: &Path, dir: &Path) -> (Option<i32>, String) {
    let o = Command::new(env!("CARGO_BIN_EXE_splitsum"))
        .args(["cubemap", "--backend", "cpu"])
        .arg(input)
        .arg("-o")
        .arg(dir.join("out").join("out.ktx2"))
        .output()
        .unwrap();
    (
        o.status.code(),
        String::from_utf8_lossy(&o.stderr).into_owned(),
    )
}

fn check(name: &str, contents: Option<&[u8]>, expect: &[&str]) {
    let dir = common::output_dir(&format!("bad-{name}"));
    let input = dir.join(name);
    if let Some(bytes) = contents {
        std::fs::write(&input, bytes).unwrap();
    }
    let (code, err) = convert(&input, &dir);
    assert_eq!(code, Some(1), "{name}: {err}");
    assert!(!err.contains("panicked"), "{name}: {err}");
    assert_eq!(
        err.trim_end().lines().count(),
        1,
        "{name}: one line expected:\n{err}"
    );
    let first = err.find(": ").map(|i| &err[i + 2..]).unwrap_or("");
    assert!(first.len() < 300, "{name}: overly long message: {err}");
    assert!(
        err.contains(name),
        "{name}: the message must name the file: {err}"
    );
    for e in expect {
        assert!(err.contains(e), "{name}: expected '{e}' in: {err}");
    }
    assert!(
        !dir.join("out").exists(),
        "{name}: no output may be left behind"
    );
}

fn hdr_header(w: u32, h: u32) -> Vec<u8> {
    format!("#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y {h} +X {w}\n").into_bytes()
}

#[test]
fn missing_file() {
    check("missing.hdr", None, &["No such file"]);
    let dir = common::output_dir("bad-missing-once");
    let (_, err) = convert(&dir.join("missing.hdr"), &dir);
    assert_eq!(err.matches("No such file").count(), 1, "said once: {err}");
}

#[test]
fn empty_file() {
    check("empty.hdr", Some(b""), &["empty"]);
}

#[test]
fn truncated_hdr() {
    let real = std::fs::read("tests/data/venice_sunset_1k.hdr").unwrap();
    check(
        "truncated.hdr",
        Some(&real[..real.len() / 2]),
        &["truncated"],
    );
}

#[test]
fn garbage() {
    let bytes: Vec<u8> = (0..5000u32)
        .map(|i| (i.wrapping_mul(2654435761) >> 13) as u8)
        .collect();
    check("garbage.hdr", Some(&bytes), &["Radiance"]);
    check("garbage.exr", Some(&bytes), &["OpenEXR"]);
    check("garbage.png", Some(&bytes), &["PNG"]);
    check("garbage.ktx2", Some(&bytes), &["KTX2"]);
    check("garbage.dds", Some(&bytes), &["DDS"]);
}

#[test]
fn absurd_header_dimensions_are_refused_before_allocating() {
    let mut bytes = hdr_header(600_000, 300_000);
    bytes.extend([2, 2, 0, 8]);
    check("huge.hdr", Some(&bytes), &["600000×300000", "at most"]);
}

#[test]
fn wrong_aspect_ratio() {
    let (w, h) = (48u32, 16u32);
    let img = splitsum::io::hdr::encode(w, h, &vec![[1.0; 3]; (w * h) as usize]);
    check("wide.hdr", Some(&img), &["48×16", "2:1 equirect"]);
}

#[test]
fn unsupported_orientation_and_format() {
    let mut b = b"#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n+Y 16 +X 32\n".to_vec();
    b.extend(vec![0u8; 16 * 32 * 4]);
    check("flipped.hdr", Some(&b), &["orientation"]);
    let mut b = b"#?RADIANCE\nFORMAT=32-bit_rle_xyze\n\n-Y 16 +X 32\n".to_vec();
    b.extend(vec![0u8; 16 * 32 * 4]);
    check("xyze.hdr", Some(&b), &["xyze"]);
}

#[test]
fn unknown_input_extension() {
    check("env.tga", Some(b"whatever"), &["'.tga'"]);
}
