//! The command line: argument definitions ([`args`], with the values the flags take in
//! `values`), the commands ([`commands`], [`preview`], [`inspect`], sharing `shared`),
//! and what turns the library's errors into messages that name the flags the user typed.

pub mod args;
pub mod commands;
pub mod inspect;
pub mod preview;
mod shared;
mod values;

use std::ffi::OsString;

/// A usage error: exit code 2. Its message names the flag the user typed.
#[derive(Debug)]
pub struct Usage(pub String);

impl std::fmt::Display for Usage {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(&self.0)
    }
}

impl std::error::Error for Usage {}

/// The flag a library option (a field of `BakeOptions`, `PreviewOptions`, or the argument of
/// a call) is set with in `command`.
pub fn flag(command: &str, option: &str) -> String {
    let flag = match (command, option) {
        (_, "rotate_degrees") => "--rotate",
        ("preview", "exposure_ev" | "preview.exposure_ev") => "--exposure",
        (_, "preview.exposure_ev") => "--preview-exposure",
        (_, "exposure_ev") => "--exposure",
        (_, "preview.cell") => "--preview-cell",
        (_, "preview.truth_samples") => "--truth-samples",
        (_, "sh") => "--no-sh",
        (_, "luts") => "--lut",
        ("bake" | "preview", "size") => "--specular-size",
        _ => return format!("--{}", option.replace('_', "-")),
    };
    flag.to_string()
}

/// The library's error as the command line says it: an option the library refuses becomes
/// a [`Usage`] error naming `command`'s flag for it, as does an output path whose
/// extension names no format; everything else stays as it is (exit 1).
pub fn for_user(command: &str, e: splitsum::Error) -> anyhow::Error {
    match e {
        splitsum::Error::InvalidOption { option, message } => {
            Usage(format!("invalid {}: {message}", flag(command, option))).into()
        }
        e @ (splitsum::Error::UnsupportedOutputFormat { .. } | splitsum::Error::NoDisplay) => {
            Usage(e.to_string()).into()
        }
        e => e.into(),
    }
}

/// Options a user is likely to try where they do not exist, caught before clap (whose
/// suggestion would mislead): `bake --size` (the sizes are `--specular-size` and
/// `--irradiance-size`).
pub fn misplaced_option(args: impl Iterator<Item = String>) -> Option<String> {
    let args: Vec<String> = args.collect();
    let command = args.get(1)?;
    let has = |name: &str| {
        args.iter()
            .take_while(|a| *a != "--")
            .any(|a| a == name || a.starts_with(&format!("{name}=")))
    };
    (command == "bake" && has("--size")).then(|| {
        "bake has no --size: the specular cube's edge is --specular-size (default 256), the irradiance cube's --irradiance-size (default 32)".to_string()
    })
}

/// The Vulkan loader prints "error: XDG_RUNTIME_DIR is invalid or not set" on headless
/// machines; it is harmless but reads like a splitsum failure. Point the variable at a
/// private folder when it is missing (before any thread starts).
pub fn quiet_vulkan_loader() {
    #[cfg(unix)]
    if std::env::var_os("XDG_RUNTIME_DIR").is_none() {
        use std::os::unix::fs::{DirBuilderExt, MetadataExt, PermissionsExt};
        let Ok(uid) = std::fs::metadata("/proc/self").map(|m| m.uid()) else {
            return;
        };
        let dir = std::env::temp_dir().join(format!("splitsum-runtime-{uid}"));
        let _ = std::fs::DirBuilder::new().mode(0o700).create(&dir);
        // Use it only if it is ours and private.
        if let Ok(m) = std::fs::symlink_metadata(&dir) {
            if m.is_dir() && m.uid() == uid && m.permissions().mode() & 0o777 == 0o700 {
                std::env::set_var("XDG_RUNTIME_DIR", OsString::from(dir));
            }
        }
    }
}
