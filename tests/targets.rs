//! Engine targets (`--target`): the generic outputs are pinned byte for byte, and the
//! bevy and three targets are the generic bake seen through each engine's cube lookup.
mod common;

use std::path::{Path, PathBuf};
use std::process::Command;

fn splitsum() -> Command {
    Command::new(env!("CARGO_BIN_EXE_splitsum"))
}

fn sha256_hex(bytes: &[u8]) -> String {
    use sha2::Digest;
    sha2::Sha256::digest(bytes)
        .iter()
        .map(|b| format!("{b:02x}"))
        .collect()
}

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
        .args(["cubemap", input, "--backend", "cpu", "--size", "32", "--mips"])
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
/// not change a byte of them (nor a value of sh.json).
const GENERIC_PINNED: [&str; 6] = [
    "05247f06f04c187b9d1ba04775702383a71254495e7d75fdfd30ae859dae6728",
    "24a55c58dab879775f93ca6bff4eb83baba44063ca8c518853a4097fe6b46897",
    "6e8e81d20dddd86b580b0ca96e10922bbb49afc0cde00adb5c876f0258f45646",
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
