//! What the command line says, message by message: a usage error names the option the
//! user typed, says the allowed values in words, exits 2 and writes nothing; a bad input
//! is named for what it is and exits 1; success says where the files went (and `-q` says
//! nothing); warnings appear where they help and nowhere else.

mod common;

use std::path::Path;
use std::process::Output;

use common::{output_dir, splitsum};

const HDR: &str = "tests/data/venice_sunset_1k.hdr";

fn run(args: &[&str], out: &Path) -> Output {
    splitsum().args(args).arg("-o").arg(out).output().unwrap()
}

fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

/// Exit code 2, one line naming `flag` and containing `words`, and nothing written.
fn usage_error(args: &[&str], flag: &str, words: &str) {
    let dir = output_dir(&format!("messages_usage_{}", flag.trim_start_matches('-')));
    let out = dir.join("out");
    let o = run(args, &out);
    let err = stderr(&o);
    assert_eq!(o.status.code(), Some(2), "{args:?}: {err}");
    assert!(err.contains(flag) && err.contains(words), "{args:?}: {err}");
    assert_eq!(err.lines().count(), 1, "{args:?}: {err}");
    assert!(!out.exists(), "{args:?} wrote {}", out.display());
}

#[test]
fn sizes_name_their_own_option_in_words() {
    usage_error(
        &["bake", "--specular-size", "300", HDR],
        "--specular-size",
        "is not a power of two from 1 to 8192",
    );
    usage_error(
        &["bake", "--irradiance-size", "33", HDR],
        "--irradiance-size",
        "is not a power of two",
    );
    usage_error(
        &["bake", "--min-mip-size", "3", HDR],
        "--min-mip-size",
        "is not a power of two",
    );
}

#[test]
fn options_a_user_is_likely_to_try() {
    // `--size` is `cubemap`'s; `bake` points to its own two sizes.
    usage_error(
        &["bake", "--size", "256", HDR],
        "--specular-size",
        "bake has no --size",
    );
    // `--outdir` is an alias of `-o`.
    let dir = output_dir("messages_outdir");
    let o = splitsum()
        .args([
            "bake",
            "--no-lut",
            "--specular-size",
            "16",
            "-q",
            HDR,
            "--outdir",
        ])
        .arg(&dir)
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(dir.join("venice_sunset_1k/manifest.json").exists());
}

#[test]
fn inputs_that_are_not_files_are_named_for_what_they_are() {
    let dir = output_dir("messages_inputs");
    for (input, says) in [
        ("tests", "is a folder, not an environment file"),
        ("-", "standard input is not supported"),
    ] {
        let o = run(&["bake", input], &dir.join("out"));
        let err = stderr(&o);
        assert_eq!(o.status.code(), Some(1), "{input}: {err}");
        assert!(err.contains(says), "{input}: {err}");
        assert!(!dir.join("out").join(input).exists());
    }
}

#[test]
fn success_says_where_the_files_went() {
    let dir = output_dir("messages_success");
    let o = run(&["bake", "--specular-size", "16", HDR], &dir.join("a"));
    let err = stderr(&o);
    assert!(o.status.success(), "{err}");
    let line = err.lines().next().unwrap_or_default();
    assert!(
        line.starts_with(&format!("baked {HDR} -> "))
            && line.contains("venice_sunset_1k/ (5 files, "),
        "{err}"
    );
    let o = run(
        &["bake", "--specular-size", "16", "-q", HDR],
        &dir.join("b"),
    );
    assert!(o.status.success());
    assert!(
        o.stderr.is_empty() && o.stdout.is_empty(),
        "-q printed {}",
        stderr(&o)
    );
    // -v says what ran, and the preview's kernels only when a preview is asked for.
    let o = run(
        &["bake", "--specular-size", "16", "-v", HDR],
        &dir.join("c"),
    );
    let err = stderr(&o);
    assert!(err.starts_with("backend: "), "{err}");
    assert!(!err.contains("preview"), "{err}");
}

#[test]
fn warnings_where_they_help() {
    let dir = output_dir("messages_warnings");
    // An 8-bit image has no highlights to light with.
    let png = dir.join("ldr.png");
    image::RgbImage::from_pixel(64, 32, image::Rgb([128, 128, 128]))
        .save(&png)
        .unwrap();
    let o = splitsum()
        .args(["bake", "--specular-size", "16", "-o"])
        .arg(dir.join("out"))
        .arg(&png)
        .output()
        .unwrap();
    let err = stderr(&o);
    assert!(o.status.success(), "{err}");
    assert!(
        err.contains("ldr.png") && err.contains("holds no radiance above 1"),
        "{err}"
    );
    // The default LUT fits a PNG: neither `lut` nor `bake` warns about clipping.
    let o = run(&["lut"], &dir.join("lut.png"));
    assert!(
        o.status.success() && !stderr(&o).contains("warning:"),
        "{}",
        stderr(&o)
    );
    let o = run(&["bake", "--specular-size", "16", HDR], &dir.join("bake"));
    assert!(
        o.status.success() && !stderr(&o).contains("warning:"),
        "{}",
        stderr(&o)
    );
}
