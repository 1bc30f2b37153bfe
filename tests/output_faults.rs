//! Output-path faults that need a file system of their own: a full disk and a
//! read-only folder. Each runs splitsum inside a private mount namespace (`unshare`) on
//! a tiny tmpfs, so nothing outside the test is touched and the mount vanishes with it.
//! (Permission bits cannot simulate these when the tests run as root.) Machines where no
//! tmpfs can be mounted skip with a message.
use std::path::{Path, PathBuf};
use std::process::Command;

/// Exit code of the script when the tmpfs cannot be mounted.
const NO_TMPFS: i32 = 77;

/// Runs `script` with `$DIR` a fresh 256 KiB tmpfs, `$KEEP` a normal folder that
/// survives, `$SPLITSUM` the binary and `$INPUT` the bundled HDRI. Returns `$KEEP`, or
/// None where mounting a tmpfs is not permitted (no root, or a container that forbids it).
fn in_tiny_tmpfs(name: &str, script: &str) -> Option<PathBuf> {
    let base = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join(name);
    let _ = std::fs::remove_dir_all(&base);
    let (dir, keep) = (base.join("mnt"), base.join("keep"));
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::create_dir_all(&keep).unwrap();
    let full = format!("mount -t tmpfs -o size=256k tmpfs \"$DIR\" || exit {NO_TMPFS}\n{script}");
    let status = Command::new("unshare")
        .args(["--mount", "--map-root-user", "sh", "-c", &full])
        .env("DIR", &dir)
        .env("KEEP", &keep)
        .env("SPLITSUM", env!("CARGO_BIN_EXE_splitsum"))
        .env(
            "INPUT",
            Path::new("tests/data/venice_sunset_1k.hdr")
                .canonicalize()
                .unwrap(),
        )
        .env("XDG_RUNTIME_DIR", &base)
        .status();
    match status {
        Ok(s)
            if s.code() == Some(NO_TMPFS) || s.code() == Some(1) && !keep.join("ran").exists() =>
        {
            eprintln!("skipping: cannot mount a tmpfs in a private namespace here");
            None
        }
        Ok(s) => {
            assert!(s.success(), "the test script failed: {s}");
            Some(keep)
        }
        Err(e) => {
            eprintln!("skipping: no unshare ({e})");
            None
        }
    }
}

fn read(path: &Path) -> String {
    std::fs::read_to_string(path).unwrap_or_default()
}

/// The stderr of script step `step`, after checking that it exited 1 without a panic.
fn failed_step(keep: &Path, step: &str) -> String {
    let err = read(&keep.join(format!("{step}.err")));
    assert_eq!(
        read(&keep.join(format!("{step}.code"))).trim(),
        "1",
        "{step}: {err}"
    );
    assert!(!err.contains("panicked"), "{step}: {err}");
    err
}

/// Every file under `dir`, relative, sorted.
fn files(dir: &Path) -> Vec<String> {
    let mut out = Vec::new();
    let mut stack = vec![dir.to_path_buf()];
    while let Some(d) = stack.pop() {
        for e in std::fs::read_dir(&d).unwrap().flatten() {
            if e.path().is_dir() {
                stack.push(e.path());
            } else {
                out.push(e.path().strip_prefix(dir).unwrap().display().to_string());
            }
        }
    }
    out.sort();
    out
}

/// A small bake fits; a larger one into the same folder runs out of space while writing.
/// It must fail with exit 1 naming the file and the cause, leave the first bake's files
/// byte for byte, and leave no temporary files. `lut` likewise.
#[test]
fn a_full_disk_is_a_clean_error_that_keeps_earlier_outputs() {
    let Some(keep) = in_tiny_tmpfs(
        "output-disk-full",
        r#"touch "$KEEP/ran"
"$SPLITSUM" bake --backend cpu --no-lut --specular-size 8 --irradiance-size 4 -o "$DIR" "$INPUT" 2>"$KEEP/first.err"
echo $? >"$KEEP/first.code"
cp -r "$DIR" "$KEEP/before"
"$SPLITSUM" bake --backend cpu --specular-size 128 -o "$DIR" "$INPUT" 2>"$KEEP/second.err"
echo $? >"$KEEP/second.code"
"$SPLITSUM" lut --backend cpu --size 512 -o "$DIR/lut.exr" 2>"$KEEP/lut.err"
echo $? >"$KEEP/lut.code"
cp -r "$DIR" "$KEEP/after"
"#,
    ) else {
        return;
    };
    assert_eq!(
        read(&keep.join("first.code")).trim(),
        "0",
        "{}",
        read(&keep.join("first.err"))
    );
    for step in ["second", "lut"] {
        let err = failed_step(&keep, step);
        assert!(err.contains("No space left on device"), "{step}: {err}");
    }
    let second = read(&keep.join("second.err"));
    assert!(
        second.contains("venice_sunset_1k/"),
        "names the file: {second}"
    );
    assert!(read(&keep.join("lut.err")).contains("lut.exr"));
    let (before, after) = (keep.join("before"), keep.join("after"));
    assert!(files(&before).len() >= 4, "{:?}", files(&before));
    assert_eq!(files(&before), files(&after), "files added or removed");
    for f in files(&before) {
        assert!(
            std::fs::read(before.join(&f)).unwrap() == std::fs::read(after.join(&f)).unwrap(),
            "{f} changed"
        );
    }
}

/// A read-only folder (a read-only mount: root ignores permission bits) gives exit 1 and
/// an error naming the output, for `lut`, `cubemap` and `bake`.
#[test]
fn a_read_only_folder_is_a_clean_error() {
    let Some(keep) = in_tiny_tmpfs(
        "output-read-only",
        r#"touch "$KEEP/ran"
mount -o remount,ro "$DIR" || exit 77
"$SPLITSUM" lut --backend cpu --size 8 -o "$DIR/lut.png" 2>"$KEEP/lut.err"
echo $? >"$KEEP/lut.code"
"$SPLITSUM" cubemap --backend cpu --size 8 -o "$DIR/sky.ktx2" "$INPUT" 2>"$KEEP/cubemap.err"
echo $? >"$KEEP/cubemap.code"
"$SPLITSUM" bake --backend cpu --no-lut --specular-size 8 --irradiance-size 4 -o "$DIR/out" "$INPUT" 2>"$KEEP/bake.err"
echo $? >"$KEEP/bake.code"
ls -A "$DIR" >"$KEEP/listing"
"#,
    ) else {
        return;
    };
    for (step, names) in [("lut", "lut.png"), ("cubemap", "sky.ktx2"), ("bake", "out")] {
        let err = failed_step(&keep, step);
        assert!(err.contains("Read-only file system"), "{step}: {err}");
        assert!(err.contains(names), "{step}: {err}");
    }
    assert_eq!(read(&keep.join("listing")), "");
}
