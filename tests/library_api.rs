//! The library as a pipeline calls it: `examples/bake.rs` (eleven lines through the
//! documented API) built as a crate of its own, outside the repository's workspace, with
//! `splitsum = { path = …, default-features = false }`, bakes the bundled HDRI for a target
//! and writes exactly the bytes `splitsum bake --target T` writes; and that crate's
//! dependency tree holds none of the command line's crates.

mod common;

use std::path::{Path, PathBuf};
use std::process::Command;

use common::{output_dir, splitsum};

/// The command line's own crates, which a library user must not build.
const CLI_CRATES: [&str; 4] = ["clap", "indicatif", "ctrlc", "anyhow"];

/// A crate in `dir` whose `main.rs` is `examples/bake.rs`, depending on this repository
/// without default features; built in release with the repository's lock file (offline,
/// so the versions are the ones the repository tests), into the target folder this test
/// was built in: the dependencies it shares with the test build, same version and
/// features, are compiled once (a folder of its own rebuilt all of them, about two
/// minutes; cargo holds no lock on the folder while tests run). Returns the path of its
/// binary.
fn api_crate(dir: &Path) -> PathBuf {
    let repo = std::env::current_dir().unwrap();
    std::fs::create_dir_all(dir.join("src")).unwrap();
    std::fs::write(
        dir.join("Cargo.toml"),
        format!(
            "[package]\nname = \"bake-with-splitsum\"\nversion = \"0.0.0\"\nedition = \"2021\"\n\n\
             [dependencies]\nsplitsum = {{ path = {:?}, default-features = false }}\n\n\
             [profile.release]\ndebug = false\n\n[workspace]\n",
            repo.display().to_string()
        ),
    )
    .unwrap();
    std::fs::copy("Cargo.lock", dir.join("Cargo.lock")).unwrap();
    std::fs::copy("examples/bake.rs", dir.join("src/main.rs")).unwrap();
    let target_dir = Path::new(env!("CARGO_TARGET_TMPDIR"))
        .parent()
        .unwrap()
        .to_path_buf();
    let o = Command::new(env!("CARGO"))
        .args(["build", "--release", "--offline", "--quiet"])
        .current_dir(dir)
        .env("CARGO_TARGET_DIR", &target_dir)
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    target_dir.join("release/bake-with-splitsum")
}

/// Every file under `dir`, relative to it, with its bytes.
fn files(dir: &Path) -> Vec<(PathBuf, Vec<u8>)> {
    fn walk(root: &Path, dir: &Path, out: &mut Vec<(PathBuf, Vec<u8>)>) {
        for entry in std::fs::read_dir(dir).unwrap() {
            let path = entry.unwrap().path();
            if path.is_dir() {
                walk(root, &path, out);
            } else {
                let bytes = std::fs::read(&path).unwrap();
                out.push((path.strip_prefix(root).unwrap().to_path_buf(), bytes));
            }
        }
    }
    let mut out = Vec::new();
    walk(dir, dir, &mut out);
    out.sort();
    out
}

#[test]
fn a_crate_outside_bakes_every_target_as_the_command_line_does() {
    let dir = output_dir("library-api");
    let binary = api_crate(&dir.join("crate"));
    let input = "tests/data/venice_sunset_1k.hdr";
    for target in ["generic", "bevy", "three", "filament", "babylon", "gltf"] {
        let (lib_out, cli_out) = (dir.join("lib").join(target), dir.join("cli").join(target));
        let o = Command::new(&binary)
            .args([input, lib_out.to_str().unwrap(), target])
            .output()
            .unwrap();
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
        let o = splitsum()
            .args([
                "bake",
                input,
                "--backend",
                "cpu",
                "-q",
                "--target",
                target,
                "-o",
            ])
            .arg(&cli_out)
            .output()
            .unwrap();
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
        let (lib, cli) = (files(&lib_out), files(&cli_out));
        assert!(!cli.is_empty());
        assert_eq!(
            lib.iter().map(|f| &f.0).collect::<Vec<_>>(),
            cli.iter().map(|f| &f.0).collect::<Vec<_>>(),
            "{target}: the same files"
        );
        for ((path, a), (_, b)) in lib.iter().zip(&cli) {
            assert!(a == b, "{target}: {} differs", path.display());
        }
    }
    // Its dependency tree: the library's, none of the command line's crates.
    let o = Command::new(env!("CARGO"))
        .args(["tree", "--offline", "-e", "normal", "--prefix", "none"])
        .current_dir(dir.join("crate"))
        .output()
        .unwrap();
    let tree = String::from_utf8_lossy(&o.stdout);
    assert!(o.status.success() && tree.contains("splitsum"), "{tree}");
    for name in CLI_CRATES {
        assert!(
            !tree.lines().any(|l| l.starts_with(&format!("{name} v"))),
            "{name} is in the library's tree:\n{tree}"
        );
    }
}
