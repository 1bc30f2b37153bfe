//! Engine targets (`--target`): the generic outputs are pinned byte for byte, and the
//! bevy and three targets are the generic bake seen through each engine's cube lookup.
mod common;

use splitsum::environment::walk::texel_centres;
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
/// their accuracy tests' bars) and when the generic chain's levels became geometric in α
/// (docs/conventions.md); the other four are the hashes first taken.
const GENERIC_PINNED: [&str; 6] = [
    "5578f511075f7f0d757987059d2f8321d73793bab686a4534bf1008d0757cf7c",
    "24a55c58dab879775f93ca6bff4eb83baba44063ca8c518853a4097fe6b46897",
    "daa715f3591b5814177caf965982d49e020f89f4033cfa8922056b5d10d64bfc",
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

/// The files a manifest lists, in its order.
fn output_files(m: &serde_json::Value) -> Vec<&str> {
    m["outputs"]
        .as_array()
        .unwrap()
        .iter()
        .map(|o| o["file"].as_str().unwrap())
        .collect()
}

fn cube(path: &Path) -> splitsum::Cubemap {
    splitsum::io::ktx2::read_cube(path).unwrap()
}

/// A CPU bake of quarry_01 with a `specular`² chain, an 8² irradiance cube and `extra`
/// options into `dir`/quarry_01_1k (emptied first).
fn quarry_bake(dir: &Path, specular: u32, extra: &[&str]) -> PathBuf {
    let _ = std::fs::remove_dir_all(dir);
    run(splitsum()
        .args(["bake", "tests/data/quarry_01_1k.hdr", "--backend", "cpu"])
        .arg("--specular-size")
        .arg(specular.to_string())
        .args(["--irradiance-size", "8", "-q", "-o"])
        .arg(dir)
        .args(extra));
    dir.join("quarry_01_1k")
}

/// A small (32²) CPU bake of quarry_01 with `extra` options into `dir`/quarry_01_1k.
fn small_bake(dir: &Path, extra: &[&str]) -> PathBuf {
    quarry_bake(dir, 32, extra)
}

/// `--target bevy`: rgb9e5 + zstd, irradiance, no LUT or SH, and, in rgba16f, exactly the
/// generic bake's texels mirrored in z (specular and irradiance alike).
#[test]
fn bevy_target_is_the_generic_bake_mirrored_in_z() {
    let generic = small_bake(&common::output_dir("targets-bevy-generic"), &["--no-lut"]);
    let bevy = small_bake(&common::output_dir("targets-bevy"), &["--target", "bevy"]);
    let m = manifest(&bevy);
    let files = output_files(&m);
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
    let files = output_files(&m);
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
        ..BakeOptions::for_target(&splitsum::targets::THREE)
    };
    let report = bake(
        &splitsum::backend::CpuBackend,
        Path::new("tests/data/quarry_01_1k.hdr"),
        &dir,
        &opts,
        &[],
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
    // A usage error: the options contradict each other.
    assert_eq!(o.status.code(), Some(2));
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
        err.contains("warning: target bevy: rgba32f is not filterable"),
        "{err}"
    );
    assert!(dir.join("venice_sunset_1k/specular.ktx2").exists());
}

/// A KTX 1 cube as splitsum writes it for Filament.
fn ktx1(path: &Path) -> splitsum::io::ktx1::Ktx1 {
    splitsum::io::ktx1::decode(&std::fs::read(path).unwrap()).unwrap()
}

/// Filament's evaluation of its pre-scaled SH at `w` (`Irradiance_SphericalHarmonics` in
/// Filament's shaders: sh[0] + sh[1] y + sh[2] z + sh[3] x + sh[4] yx + sh[5] yz +
/// sh[6] (3z² − 1) + sh[7] zx + sh[8] (x² − y²)).
fn filament_irradiance(sh: &[[f32; 3]; 9], w: [f32; 3]) -> [f32; 3] {
    let [x, y, z] = w;
    let p = [
        1.0,
        y,
        z,
        x,
        y * x,
        y * z,
        3.0 * z * z - 1.0,
        z * x,
        x * x - y * y,
    ];
    std::array::from_fn(|c| (0..9).map(|k| sh[k][c] * p[k]).sum())
}

/// `--target filament`: cmgen's file set (`<stem>_ibl.ktx` with the SH under `sh`,
/// `<stem>_skybox.ktx`, `sh.txt`), the chain to 16² at r = 1 − √(1 − m/(M − 1)), level 0
/// the generic bake's turned a quarter about +Y (texel at (−z, y, x) holds L(x, y, z)),
/// and SH that Filament's shader evaluates at the engine's direction to the generic bake's
/// E/π at the world direction.
#[test]
fn filament_target_is_cmgens_file_set_in_filaments_frame() {
    let dir = common::output_dir("targets-filament");
    let _ = std::fs::remove_dir_all(&dir);
    let bake = |out: &Path, extra: &[&str]| quarry_bake(out, 64, extra);
    let filament = bake(&dir.join("f"), &["--target", "filament"]);
    let exact = bake(
        &dir.join("f32"),
        &["--target", "filament", "--pixel-format", "rgba32f"],
    );
    let generic = bake(&dir.join("g"), &["--pixel-format", "rgba32f", "--no-lut"]);

    let m = manifest(&filament);
    assert_eq!(m["target"]["name"], "filament");
    assert_eq!(m["parameters"]["container"], "ktx (KTX 1)");
    assert_eq!(m["parameters"]["pixel_format"], "rg11b10f");
    assert_eq!(m["parameters"]["specular_levels"], 3, "64² to 16²");
    assert_eq!(
        m["parameters"]["roughness_per_mip"],
        "1 - sqrt(1 - m / (levels - 1))"
    );
    let files = output_files(&m);
    assert_eq!(
        files,
        ["quarry_01_1k_ibl.ktx", "quarry_01_1k_skybox.ktx", "sh.txt"]
    );

    // The IBL: R11F_G11F_B10F with cmgen's glType, three levels, the SH as text.
    let ibl = ktx1(&filament.join("quarry_01_1k_ibl.ktx"));
    assert_eq!(
        (ibl.gl.gl_type, ibl.gl.internal_format, ibl.faces),
        (0x8C3A, 0x8C3A, 6)
    );
    assert_eq!(ibl.levels.len(), 3);
    let sh_key = splitsum::io::sh_text::parse(
        std::str::from_utf8(ibl.value("sh").expect("the sh key")).unwrap(),
    )
    .unwrap();
    let sh_txt =
        splitsum::io::sh_text::parse(&std::fs::read_to_string(filament.join("sh.txt")).unwrap())
            .unwrap();
    for (a, b) in sh_key.iter().flatten().zip(sh_txt.iter().flatten()) {
        assert!((a - b).abs() <= 1e-6 * a.abs().max(1.0), "{a} vs {b}");
    }
    let skybox = ktx1(&filament.join("quarry_01_1k_skybox.ktx"));
    assert_eq!((skybox.width, skybox.levels.len()), (64, 1));

    // Level 0 in rgba32f: the generic cube turned, texel for texel.
    let turned = splitsum::io::ktx1::read_cube(&exact.join("quarry_01_1k_ibl.ktx")).unwrap();
    let g = cube(&generic.join("specular.ktx2"));
    let frame = splitsum::math::cubemap::AxisMap {
        axis: [2, 1, 0],
        sign: [-1, 1, 1],
    };
    assert_eq!(turned.levels[0], g.remapped(frame).levels[0]);
    assert_eq!(
        splitsum::targets::FILAMENT.orientation.texel_map(),
        frame,
        "the target's frame"
    );
    // A KTX 1 cube is an input too: read back at its own size, it is the same cube.
    let back = dir.join("back.ktx2");
    run(splitsum()
        .args([
            "cubemap",
            "--backend",
            "cpu",
            "--pixel-format",
            "rgba32f",
            "-o",
        ])
        .arg(&back)
        .arg(exact.join("quarry_01_1k_skybox.ktx")));
    assert_eq!(cube(&back).levels[0], turned.levels[0]);

    // The SH: Filament's polynomial at (−z, y, x) is the generic E/π at (x, y, z).
    let v: serde_json::Value =
        serde_json::from_slice(&std::fs::read(generic.join("sh.json")).unwrap()).unwrap();
    let world: [[f32; 3]; 9] = std::array::from_fn(|k| {
        std::array::from_fn(|c| v["irradiance_sh9"][k][c].as_f64().unwrap() as f32)
    });
    for d in common::uniform_directions(64, 7) {
        let d = d.map(|x| x as f32);
        let want = splitsum::math::sh::sh_eval(&world, d);
        let got = filament_irradiance(&sh_key, frame.apply(d));
        for c in 0..3 {
            assert!(
                (got[c] - want[c]).abs() <= 1e-5 * want[c].abs().max(1.0),
                "{d:?}: {got:?} vs {want:?}"
            );
        }
    }
}

/// Each of `cases` (extra options, and what the error must say) makes a 32² CPU bake of
/// `tests/data/<stem>.hdr` for `target` into `dir` exit 2 (a usage error) with that error, before any file
/// is written.
fn assert_refused(dir: &Path, stem: &str, target: &str, cases: &[(&[&str], &str)]) {
    let _ = std::fs::remove_dir_all(dir);
    for (extra, says) in cases {
        let o = splitsum()
            .arg("bake")
            .arg(format!("tests/data/{stem}.hdr"))
            .args(["--target", target, "--specular-size", "32"])
            .args(["--backend", "cpu", "-q", "-o"])
            .arg(dir)
            .args(*extra)
            .output()
            .unwrap();
        let err = String::from_utf8_lossy(&o.stderr);
        // Usage errors: refused before the input is read.
        assert_eq!(o.status.code(), Some(2), "{extra:?}: {err}");
        assert!(err.contains(says), "{extra:?}: {err}");
        assert!(!dir.join(stem).exists(), "{extra:?} wrote files");
    }
}

/// What Filament's KTX 1 cannot hold, and options the target ignores, are refused in one
/// line before any file is written.
#[test]
fn filament_target_refuses_what_it_cannot_write() {
    let dir = common::output_dir("targets-filament-refusals");
    assert_refused(
        &dir,
        "venice_sunset_1k",
        "filament",
        &[
            (
                &["--pixel-format", "rgb9e5"],
                "rgb9e5 cannot be written as KTX 1",
            ),
            (&["--container", "dds"], "container applies to"),
            (&["--no-sh"], "writes the irradiance SH into its file"),
        ],
    );
}

/// cmgen's faces, which Filament shows as they are, are the Filament target's: level 0 of
/// `cmgen -x DIR --format=ktx --size=64` and of a 64² `--target filament` cube of the same
/// HDRI put the sun within half a degree of each other and agree in pattern (the
/// correlation of ln(1 + L) over 4×4-texel blocks); a generic cube read as Filament's does
/// not.
/// Runs where cmgen is installed (`.ci/run` installs it and requires it).
#[test]
fn filament_frame_is_cmgens() {
    let Ok(cmgen) = common::which_cmgen() else {
        common::skip_peer("cmgen not found");
        return;
    };
    let dir = common::output_dir("targets-filament-cmgen");
    let _ = std::fs::remove_dir_all(&dir);
    let input = "tests/data/venice_sunset_1k.hdr";
    run(Command::new(&cmgen)
        .args(["-q", "-x"])
        .arg(dir.join("cmgen"))
        .args(["--format=ktx", "--size=64", input]));
    let theirs = splitsum::io::ktx1::read_cube(&dir.join("cmgen/cmgen_skybox.ktx")).unwrap();
    let cube_for = |target: &str| {
        let path = dir.join(format!("{target}.ktx"));
        run(splitsum()
            .args(["cubemap", input, "--size", "64", "--backend", "cpu"])
            .args(["--target", target, "--pixel-format", "rg11b10f", "-o"])
            .arg(&path));
        splitsum::io::ktx1::read_cube(&path).unwrap()
    };
    // ln(1 + L) of level 0 averaged over 4×4 blocks, and the luminance-weighted direction
    // of the texels above half the maximum of level 0.
    let stats = |c: &splitsum::Cubemap| {
        let n0 = c.size;
        let mut pattern = Vec::new();
        for f in 0..6 {
            for bj in 0..n0 / 4 {
                for bi in 0..n0 / 4 {
                    let mut sum = 0.0;
                    for j in 4 * bj..4 * bj + 4 {
                        for i in 4 * bi..4 * bi + 4 {
                            sum += c.texel(0, f, i, j)[1] as f64 / 16.0;
                        }
                    }
                    pattern.push((1.0 + sum).ln());
                }
            }
        }
        let lum = |t: [f32; 4]| 0.2126 * t[0] + 0.7152 * t[1] + 0.0722 * t[2];
        let max = c.levels[0].iter().map(|&t| lum(t)).fold(0.0, f32::max);
        let mut sun = [0.0f64; 3];
        for (f, i, j, _) in texel_centres(n0) {
            let l = lum(c.texel(0, f, i, j));
            if l >= 0.5 * max {
                let d = splitsum::math::cubemap::cube_texel_direction(f, i as i32, j as i32, n0);
                for k in 0..3 {
                    sun[k] += (l * d[k]) as f64;
                }
            }
        }
        let len = sun.iter().map(|v| v * v).sum::<f64>().sqrt();
        (pattern, sun.map(|v| v / len))
    };
    let correlation = |a: &[f64], b: &[f64]| {
        let n = a.len() as f64;
        let (ma, mb) = (a.iter().sum::<f64>() / n, b.iter().sum::<f64>() / n);
        let (mut ab, mut aa, mut bb) = (0.0, 0.0, 0.0);
        for (x, y) in a.iter().zip(b) {
            ab += (x - ma) * (y - mb);
            aa += (x - ma).powi(2);
            bb += (y - mb).powi(2);
        }
        ab / (aa * bb).sqrt()
    };
    let degrees = |a: [f64; 3], b: [f64; 3]| {
        (a[0] * b[0] + a[1] * b[1] + a[2] * b[2])
            .clamp(-1.0, 1.0)
            .acos()
            .to_degrees()
    };
    let (their_pattern, their_sun) = stats(&theirs);
    let (ours, our_sun) = stats(&cube_for("filament"));
    let (generic, generic_sun) = stats(&cube_for("generic"));
    let (c_ours, c_generic) = (
        correlation(&ours, &their_pattern),
        correlation(&generic, &their_pattern),
    );
    let (d_ours, d_generic) = (degrees(our_sun, their_sun), degrees(generic_sun, their_sun));
    println!("filament: sun {d_ours:.2}°, correlation {c_ours:.4}; generic: sun {d_generic:.1}°, correlation {c_generic:.4}");
    assert!(
        d_ours < 0.5 && c_ours > 0.99,
        "filament: {d_ours}°, {c_ours}"
    );
    assert!(
        d_generic > 45.0 && c_generic < 0.9,
        "generic: {d_generic}°, {c_generic}"
    );
}

/// `--target babylon`: one `<stem>.env` holding the whole chain (32² to 1², six levels) at
/// Babylon's roughness per mip, level 0 the generic cube in Babylon's left-handed frame
/// (texel at (z, y, x) holds L(x, y, z)) to RGBD's precision, and a polynomial that Babylon
/// shades (its band factors undone) to the generic E/π at the engine's direction; and
/// `<stem>_irradiance.env`, the generic irradiance cube in the same frame.
#[test]
fn babylon_target_is_an_env_in_babylons_frame() {
    let dir = common::output_dir("targets-babylon");
    let babylon = small_bake(&dir.join("b"), &["--target", "babylon"]);
    let generic = small_bake(&dir.join("g"), &["--pixel-format", "rgba32f", "--no-lut"]);
    let m = manifest(&babylon);
    assert_eq!(m["target"]["name"], "babylon");
    assert_eq!(m["parameters"]["container"], "env (Babylon.js)");
    assert_eq!(m["parameters"]["specular_levels"], 6, "32² to 1²");
    let files = output_files(&m);
    assert_eq!(files, ["quarry_01_1k.env", "quarry_01_1k_irradiance.env"]);
    let decode = |name: &str| {
        let path = babylon.join(name);
        splitsum::io::env::decode(&path, &std::fs::read(&path).unwrap()).unwrap()
    };
    let env = decode("quarry_01_1k.env");
    assert_eq!((env.cube.size, env.cube.levels.len()), (32, 6));
    assert_eq!(env.lod_generation_scale, 0.8);
    let frame = splitsum::math::cubemap::AxisMap {
        axis: [2, 1, 0],
        sign: [1, 1, 1],
    };
    assert_eq!(splitsum::targets::BABYLON.orientation.texel_map(), frame);
    // RGBD: 8 bits a channel under a shared divisor.
    let rgbd_close = |got: &[[f32; 4]], want: &[[f32; 4]]| {
        assert_eq!(got.len(), want.len());
        for (a, b) in got.iter().zip(want) {
            let top = b[0].max(b[1]).max(b[2]);
            if top > splitsum::io::env::RGBD_MAX {
                continue; // clipped, with a warning
            }
            for c in 0..3 {
                assert!(
                    (a[c] - b[c]).abs() <= 0.04 * b[c] + 0.015 * top + 1e-4,
                    "{a:?} vs {b:?}"
                );
            }
        }
    };
    let g = cube(&generic.join("specular.ktx2")).remapped(frame);
    rgbd_close(&env.cube.levels[0], &g.levels[0]);
    let irradiance = decode("quarry_01_1k_irradiance.env");
    let g = cube(&generic.join("irradiance.ktx2")).remapped(frame);
    assert_eq!(irradiance.cube.size, g.size);
    rgbd_close(&irradiance.cube.levels[0], &g.levels[0]);
    let v: serde_json::Value =
        serde_json::from_slice(&std::fs::read(generic.join("sh.json")).unwrap()).unwrap();
    let world: [[f32; 3]; 9] = std::array::from_fn(|k| {
        std::array::from_fn(|c| v["irradiance_sh9"][k][c].as_f64().unwrap() as f32)
    });
    for d in common::uniform_directions(64, 11) {
        let d = d.map(|x| x as f32);
        let want = splitsum::math::sh::sh_eval(&world, d);
        let got = env.irradiance.shade(frame.apply(d));
        for c in 0..3 {
            assert!(
                (got[c] - want[c]).abs() <= 1e-4 * want[c].abs().max(1.0),
                "{d:?}: {got:?} vs {want:?}"
            );
        }
    }
}

/// What a .env cannot hold is refused in one line before any file is written, and a sun
/// above RGBD's 255 is written clipped with a warning that says how to keep it.
#[test]
fn babylon_target_refuses_what_a_env_cannot_hold_and_warns_of_clipping() {
    let dir = common::output_dir("targets-babylon-refusals");
    assert_refused(
        &dir,
        "quarry_01_1k",
        "babylon",
        &[
            (&["--min-mip-size", "4"], "the whole chain down to 1x1"),
            (&["--pixel-format", "rgba16f"], "RGBD PNGs"),
            (&["--container", "exr"], "container applies to"),
        ],
    );
    let o = splitsum()
        .args(["bake", "tests/data/quarry_01_1k.hdr", "--target", "babylon"])
        .args(["--specular-size", "32", "--backend", "cpu", "-q", "-o"])
        .arg(&dir)
        .output()
        .unwrap();
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(o.status.success(), "{err}");
    assert!(
        err.contains("brighter than the 255 a .env (RGBD) holds"),
        "{err}"
    );
}

/// `--target gltf`: glTF-IBL-Sampler's folders and LUT files as the glTF Sample Viewer reads
/// them: the GGX chain is the generic prefilter at the viewer's layout (to 16²), value for
/// value;
/// the Charlie chain has the same levels; lut_ggx.png is `splitsum lut --model
/// smith-correlated`, lut_charlie.png holds `--model charlie` in B (the viewer reads `.b`)
/// and lut_sheen_E.png is `--model sheen-albedo`.
#[test]
fn gltf_target_is_the_sample_viewers_file_set() {
    let dir = common::output_dir("targets-gltf");
    let gltf = small_bake(&dir.join("t"), &["--target", "gltf"]);
    let bake64 = |out: &Path, extra: &[&str]| quarry_bake(out, 64, extra);
    let gltf64 = bake64(&dir.join("t64"), &["--target", "gltf"]);
    // The viewer's layout, r = m/(M − 1) to 16², is Bevy's (the generic chain's levels are
    // geometric in α): Bevy's chain to 16², in the same pixel format, turned back into the
    // generic frame.
    let bevy64 = bake64(
        &dir.join("b64"),
        &[
            "--target",
            "bevy",
            "--min-mip-size",
            "16",
            "--pixel-format",
            "rgba16f",
            "--no-zstd",
        ],
    );
    let m = manifest(&gltf);
    assert_eq!(m["target"]["name"], "gltf");
    let files = output_files(&m);
    assert_eq!(
        files,
        [
            "diffuse.ktx2",
            "specular.ktx2",
            "sheen.ktx2",
            "lut_ggx.png",
            "lut_charlie.png",
            "lut_sheen_E.png"
        ]
    );
    for path in [
        "lambertian/diffuse.ktx2",
        "ggx/specular.ktx2",
        "charlie/sheen.ktx2",
    ] {
        assert!(gltf.join(path).is_file(), "{path}");
    }
    let chain = |p: &Path| splitsum::io::ktx2::read_cube_chain(p).unwrap();
    assert!(
        chain(&gltf64.join("ggx/specular.ktx2"))
            == chain(&bevy64.join("specular.ktx2")).remapped(
                splitsum::targets::bevy::BEVY
                    .orientation
                    .texel_map()
                    .inverse()
            ),
        "the GGX chain is the generic prefilter at the viewer's layout"
    );
    let (ggx, sheen) = (
        chain(&gltf64.join("ggx/specular.ktx2")),
        chain(&gltf64.join("charlie/sheen.ktx2")),
    );
    assert_eq!((ggx.levels.len(), sheen.levels.len()), (3, 3), "64² to 16²");
    assert_ne!(ggx.levels[1], sheen.levels[1]);

    let lut = |model: &str| {
        let path = dir.join(format!("{model}.png"));
        run(splitsum()
            .args(["lut", "--backend", "cpu", "--model", model, "-o"])
            .arg(&path));
        path
    };
    assert_eq!(
        std::fs::read(gltf.join("lut_ggx.png")).unwrap(),
        std::fs::read(lut("smith-correlated")).unwrap()
    );
    assert_eq!(
        std::fs::read(gltf.join("lut_sheen_E.png")).unwrap(),
        std::fs::read(lut("sheen-albedo")).unwrap()
    );
    let png = |p: &Path| {
        splitsum::io::png::decode_rgb(&std::fs::read(p).unwrap())
            .unwrap()
            .2
    };
    let charlie = png(&lut("charlie"));
    let blue = png(&gltf.join("lut_charlie.png"));
    for (b, c) in blue.iter().zip(&charlie) {
        assert_eq!([b[0], b[1], b[2]], [0.0, 0.0, c[0]]);
    }
}

/// The roughness of level `m` of a chain of `levels` as docs/conventions.md and
/// docs/targets.md write each mapping, apart from the code that bakes it.
fn written_roughness(mapping: splitsum::MipRoughness, m: u32, levels: u32) -> f32 {
    let t = m as f64 / (levels - 1) as f64;
    let r = match mapping {
        splitsum::MipRoughness::Linear => t,
        splitsum::MipRoughness::Quadratic => 1.0 - (1.0 - t).sqrt(),
        splitsum::MipRoughness::Babylon if m == 0 => 0.0,
        splitsum::MipRoughness::Babylon => (m as f64 / 0.8 - (levels - 1) as f64)
            .exp2()
            .min(1.0)
            .sqrt(),
    };
    r as f32
}

/// Every target's manifest states each level of its chain in numbers, and reads back
/// through `Manifest::read`: the edges halve from the specular size down to the target's
/// minimum mip, each roughness is the target's mapping (bit for bit what the bake used, and
/// the written formula within f32 rounding), α = r²; the Charlie chain of a target that
/// writes one has the same levels but level 0, which holds level 1's lobe.
#[test]
fn manifests_state_each_chain_level() {
    const SIZE: u32 = 64;
    let dir = common::output_dir("targets-chain-levels");
    for target in splitsum::TARGETS {
        let name = target.name;
        let bake = quarry_bake(&dir.join(name), SIZE, &["--target", name]);
        let m = splitsum::Manifest::read(&bake).unwrap();
        let p = &m.parameters;
        let levels = p.specular_levels;
        let min = target.min_mip_size.min(SIZE);
        assert_eq!(levels, (SIZE / min).trailing_zeros() + 1, "{name}");
        assert_eq!(p.specular_chain_levels.len(), levels as usize, "{name}");
        assert!(
            m.outputs
                .iter()
                .any(|o| o.size == SIZE && o.levels == levels),
            "{name}: no output holds the chain the manifest states"
        );
        for (k, level) in p.specular_chain_levels.iter().enumerate() {
            let at = k as u32;
            assert_eq!(level.level, at, "{name}");
            assert_eq!(level.size, SIZE >> at, "{name} level {at}");
            assert_eq!(
                level.roughness,
                target.roughness.roughness(at, levels),
                "{name} level {at}"
            );
            let written = written_roughness(target.roughness, at, levels);
            assert!(
                (level.roughness - written).abs() < 1e-6,
                "{name} level {at}: {} against {written}",
                level.roughness
            );
            assert_eq!(level.alpha, level.roughness * level.roughness, "{name}");
        }
        let last = p.specular_chain_levels.last().unwrap();
        assert_eq!(last.size, min, "{name}: the chain ends at the minimum mip");
        assert_eq!(p.specular_chain_levels[0].roughness, 0.0, "{name}");
        if target.files.sheen {
            assert_eq!(p.sheen_chain_levels.len(), levels as usize, "{name}");
            for (k, (sheen, ggx)) in p
                .sheen_chain_levels
                .iter()
                .zip(&p.specular_chain_levels)
                .enumerate()
            {
                let lobe = &p.specular_chain_levels[k.max(1)];
                assert_eq!(
                    (sheen.level, sheen.size, sheen.roughness, sheen.alpha),
                    (ggx.level, ggx.size, lobe.roughness, lobe.alpha),
                    "{name} sheen level {k}"
                );
            }
        } else {
            assert!(p.sheen_chain_levels.is_empty(), "{name}");
        }
        // The JSON a script reads holds the same numbers.
        let json = manifest(&bake);
        assert_eq!(
            json["parameters"]["specular_chain_levels"][0],
            serde_json::json!({"level": 0, "size": SIZE, "roughness": 0.0, "alpha": 0.0}),
            "{name}"
        );
        // A manifest without the numbers (the formula alone) still reads.
        let mut formula_only = json;
        formula_only["parameters"]
            .as_object_mut()
            .unwrap()
            .retain(|k, _| !k.ends_with("_chain_levels"));
        let old = dir.join(format!("{name}-formula-only"));
        std::fs::create_dir_all(&old).unwrap();
        std::fs::write(old.join("manifest.json"), formula_only.to_string()).unwrap();
        let read = splitsum::Manifest::read(&old).unwrap();
        assert!(read.parameters.specular_chain_levels.is_empty(), "{name}");
        assert_eq!(read.parameters.roughness_per_mip, p.roughness_per_mip);
    }
}
