//! Engine targets (`--target`): the generic outputs are pinned byte for byte, and the
//! bevy and three targets are the generic bake seen through each engine's cube lookup.
mod common;

use std::path::{Path, PathBuf};
use std::process::Command;

use common::splitsum;

use common::sha256_hex;

fn run(cmd: &mut Command) {
    let o = cmd.output().unwrap();
    assert!(
        o.status.success(),
        "{cmd:?} failed: {}",
        String::from_utf8_lossy(&o.stderr)
    );
}

/// The numbers of sh.json (its layout is serde_json's; its values are pinned).
fn sh_values_hash(path: &Path) -> String {
    let v: serde_json::Value = serde_json::from_slice(&std::fs::read(path).unwrap()).unwrap();
    let mut bits = Vec::new();
    for key in ["radiance_sh9", "irradiance_sh9"] {
        for c in v[key].as_array().unwrap() {
            for x in c.as_array().unwrap() {
                bits.extend((x.as_f64().unwrap() as f32).to_le_bytes());
            }
        }
    }
    sha256_hex(&bits)
}

/// A generic bake and two generic cubemaps on the CPU backend (deterministic), small.
fn generic_outputs(dir: &Path, extra: &[&str]) -> Vec<(PathBuf, String)> {
    let input = "tests/data/quarry_01_1k.hdr";
    let _ = std::fs::remove_dir_all(dir);
    run(splitsum()
        .args(["bake", input, "--backend", "cpu", "--specular-size", "32"])
        .args(["--irradiance-size", "8", "-q", "-o"])
        .arg(dir)
        .args(extra));
    run(splitsum()
        .args([
            "cubemap",
            input,
            "--backend",
            "cpu",
            "--size",
            "32",
            "--mips",
        ])
        .args(["--pixel-format", "rgb9e5", "--zstd", "-o"])
        .arg(dir.join("cube.ktx2"))
        .args(extra));
    run(splitsum()
        .args(["cubemap", input, "--backend", "cpu", "--size", "32", "-o"])
        .arg(dir.join("cube.dds"))
        .args(extra));
    let bake = dir.join("quarry_01_1k");
    let mut out: Vec<(PathBuf, String)> = ["brdf_lut.png", "irradiance.ktx2", "specular.ktx2"]
        .iter()
        .map(|f| bake.join(f))
        .chain([dir.join("cube.ktx2"), dir.join("cube.dds")])
        .map(|p| {
            let h = sha256_hex(&std::fs::read(&p).unwrap());
            (p, h)
        })
        .collect();
    let sh = bake.join("sh.json");
    let h = sh_values_hash(&sh);
    out.push((sh, h));
    out
}

/// Hashes of the generic outputs, taken before any target existed: adding targets must
/// not change a byte of them (nor a value of sh.json). Re-taken when the numerics change
/// on purpose: brdf_lut.png when the CPU LUT began interpolating between integrated
/// texels, specular.ktx2 when the exact levels' sum was packed into lanes (both within
/// their accuracy tests' bars; the other four are the hashes first taken).
const GENERIC_PINNED: [&str; 6] = [
    "5578f511075f7f0d757987059d2f8321d73793bab686a4534bf1008d0757cf7c",
    "24a55c58dab879775f93ca6bff4eb83baba44063ca8c518853a4097fe6b46897",
    "e08a363f85abecd999bba8e07f66506ecaa5fdc73c78e89daa77ad9fcd7e6f12",
    "4deaab7ee12f7d42b2b68c95e3fb8105b764a6e26e25f15754b5ebae33ea5328",
    "ae025bcfbe944c5d6034041db4531c426cefd9586c26ff21616bad7dacb31fb1",
    "a5dff322e5ad356bd1a38e5d133b972c0d8e8aabe37c5adb98a171e1856b67bc",
];

#[test]
fn generic_outputs_keep_their_bytes() {
    let got = generic_outputs(&common::output_dir("targets-generic"), &[]);
    for ((path, hash), want) in got.iter().zip(GENERIC_PINNED) {
        assert_eq!(hash, want, "{} changed", path.display());
    }
}

fn manifest(dir: &Path) -> serde_json::Value {
    serde_json::from_slice(&std::fs::read(dir.join("manifest.json")).unwrap()).unwrap()
}

fn cube(path: &Path) -> splitsum::Cubemap {
    splitsum::io::input::read_ktx2_cube(path).unwrap()
}

/// A small CPU bake of quarry_01 with `extra` options into `dir`/quarry_01_1k.
fn small_bake(dir: &Path, extra: &[&str]) -> PathBuf {
    let _ = std::fs::remove_dir_all(dir);
    run(splitsum()
        .args(["bake", "tests/data/quarry_01_1k.hdr", "--backend", "cpu"])
        .args([
            "--specular-size",
            "32",
            "--irradiance-size",
            "8",
            "-q",
            "-o",
        ])
        .arg(dir)
        .args(extra));
    dir.join("quarry_01_1k")
}

/// `--target bevy`: rgb9e5 + zstd, irradiance, no LUT or SH, and, in rgba16f, exactly the
/// generic bake's texels mirrored in z (specular and irradiance alike).
#[test]
fn bevy_target_is_the_generic_bake_mirrored_in_z() {
    let generic = small_bake(&common::output_dir("targets-bevy-generic"), &["--no-lut"]);
    let bevy = small_bake(&common::output_dir("targets-bevy"), &["--target", "bevy"]);
    let files: Vec<String> = manifest(&bevy)["outputs"]
        .as_array()
        .unwrap()
        .iter()
        .map(|o| o["file"].as_str().unwrap().to_string())
        .collect();
    assert_eq!(
        files,
        ["specular.ktx2", "irradiance.ktx2"],
        "the manifest lists the others"
    );
    let m = manifest(&bevy);
    assert_eq!(m["target"]["name"], "bevy");
    assert_eq!(m["parameters"]["pixel_format"], "rgb9e5");
    assert_eq!(m["parameters"]["zstd"], 10);
    assert_eq!(m["parameters"]["roughness_per_mip"], "m / (levels - 1)");
    let bytes = std::fs::read(bevy.join("specular.ktx2")).unwrap();
    assert_eq!(
        u32::from_le_bytes(bytes[44..48].try_into().unwrap()),
        2,
        "zstd"
    );

    let half = small_bake(
        &common::output_dir("targets-bevy-16f"),
        &["--target", "bevy", "--pixel-format", "rgba16f", "--no-zstd"],
    );
    for name in ["specular.ktx2", "irradiance.ktx2"] {
        let want = cube(&generic.join(name)).mirrored(2);
        assert_eq!(cube(&half.join(name)), want, "{name}");
    }
    // rgb9e5 holds the same texels to its 9-bit mantissa.
    let packed = cube(&bevy.join("specular.ktx2"));
    let want = cube(&generic.join("specular.ktx2")).mirrored(2);
    for (a, b) in packed
        .levels
        .iter()
        .flatten()
        .zip(want.levels.iter().flatten())
    {
        let scale = a[0].max(a[1]).max(a[2]).max(1e-3);
        for c in 0..3 {
            assert!((a[c] - b[c]).abs() <= scale / 256.0, "{a:?} vs {b:?}");
        }
    }
}

/// `--target three`: r187's PMREM layout (to 8², r = 1 − √(1 − m/(M − 1))), x mirrored,
/// no irradiance cube, sh.json unmirrored, the LUT (when asked) as RG16F KTX2.
#[test]
fn three_target_is_a_pmrem_chain_mirrored_in_x() {
    let three = small_bake(
        &common::output_dir("targets-three"),
        &["--target", "three", "--lut"],
    );
    let m = manifest(&three);
    assert_eq!(m["target"]["name"], "three");
    assert_eq!(m["parameters"]["specular_levels"], 3, "32² to 8²");
    assert_eq!(
        m["parameters"]["roughness_per_mip"],
        "1 - sqrt(1 - m / (levels - 1))"
    );
    let files: Vec<&str> = m["outputs"]
        .as_array()
        .unwrap()
        .iter()
        .map(|o| o["file"].as_str().unwrap())
        .collect();
    assert_eq!(files, ["specular.ktx2", "sh.json", "brdf_lut.ktx2"]);
    let lut = std::fs::read(three.join("brdf_lut.ktx2")).unwrap();
    let vk = u32::from_le_bytes(lut[12..16].try_into().unwrap());
    assert_eq!(vk, 83, "VK_FORMAT_R16G16_SFLOAT");

    // The same chain baked by the library in generic orientation, then mirrored.
    use splitsum::bake::{bake, BakeOptions};
    let dir = common::output_dir("targets-three-generic-orientation");
    let opts = BakeOptions {
        specular_size: 32,
        irradiance_size: 8,
        zstd: None,
        ..BakeOptions::for_target(&splitsum::target::THREE)
    };
    let report = bake(
        &splitsum::CpuBackend,
        Path::new("tests/data/quarry_01_1k.hdr"),
        &dir,
        &opts,
        None,
        &mut |_| {},
    )
    .unwrap();
    let lib = cube(&report.out_dir.join("specular.ktx2"));
    assert_eq!(cube(&three.join("specular.ktx2")), lib);
    let generic = small_bake(&common::output_dir("targets-three-generic"), &["--no-lut"]);
    // sh.json is world space: the same as the generic bake's.
    assert_eq!(
        sh_values_hash(&three.join("sh.json")),
        sh_values_hash(&generic.join("sh.json"))
    );
    // Level 0 is the environment, mirrored in x.
    let g = cube(&generic.join("specular.ktx2"));
    assert_eq!(lib.levels[0], g.mirrored(0).levels[0]);
}

/// `cubemap --target` mirrors every level; an equirect layout cannot carry a mirror.
#[test]
fn cubemap_targets_mirror_and_refuse_an_equirect() {
    let dir = common::output_dir("targets-cubemap");
    let input = "tests/data/venice_sunset_1k.hdr";
    let out = |name: &str| dir.join(name);
    // A 16² rgba32f cube with every mip for `target`, in `<target>.ktx2`.
    let cubemap = |target: &str| {
        let path = out(&format!("{target}.ktx2"));
        run(splitsum()
            .args([
                "cubemap",
                input,
                "--size",
                "16",
                "--mips",
                "--backend",
                "cpu",
            ])
            .args(["--pixel-format", "rgba32f", "--target", target, "-o"])
            .arg(&path));
        cube(&path)
    };
    let generic = cubemap("generic");
    for (target, axis) in [("bevy", 2), ("three", 0)] {
        assert_eq!(cubemap(target), generic.mirrored(axis));
    }
    let o = splitsum()
        .args(["cubemap", input, "--size", "16", "--target", "bevy"])
        .args(["--layout", "equirect", "-o"])
        .arg(out("sky.hdr"))
        .output()
        .unwrap();
    assert_eq!(o.status.code(), Some(1));
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(err.contains("an equirect is not a cube"), "{err}");
    assert!(!out("sky.hdr").exists());
}

/// rgba32f for Bevy is written, with a warning that says why it may not bind.
#[test]
fn bevy_warns_about_rgba32f() {
    let dir = common::output_dir("targets-bevy-32f");
    let o = splitsum()
        .args([
            "bake",
            "tests/data/venice_sunset_1k.hdr",
            "--backend",
            "cpu",
            "-q",
        ])
        .args(["--specular-size", "16", "--irradiance-size", "8"])
        .args(["--target", "bevy", "--pixel-format", "rgba32f", "-o"])
        .arg(&dir)
        .output()
        .unwrap();
    assert!(o.status.success());
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(
        err.contains("warning: --target bevy: rgba32f is not filterable"),
        "{err}"
    );
    assert!(dir.join("venice_sunset_1k/specular.ktx2").exists());
}
