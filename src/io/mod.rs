//! Readers and writers, one file per format. Every writer goes through
//! [`atomic::write_atomic`], so an output is either complete or absent.

pub mod astc;
pub mod atomic;
pub mod bc6h;
pub mod cubemap;
pub mod dds;
pub mod env;
pub mod exr;
pub mod format;
pub mod hdr;
pub mod input;
pub mod ktx1;
pub mod ktx2;
pub mod ldr;
pub mod limits;
pub mod ltc;
pub mod lut;
pub mod png;
pub mod sh_text;
pub mod staging;

pub use format::PixelFormat;

use std::path::Path;

/// Checks that `path`'s extension is one of `allowed` (what `what` can be written as),
/// before any work is done.
pub fn check_output_extension(
    path: &Path,
    what: &'static str,
    allowed: &[&str],
) -> crate::Result<()> {
    let ext = extension_of(path);
    if allowed.contains(&ext.as_str()) {
        Ok(())
    } else {
        Err(crate::Error::UnsupportedOutputFormat {
            path: path.to_path_buf(),
            what,
            extension: ext,
            supported: allowed.join(", "),
        })
    }
}

/// The lower-cased extension of `path`, or "" when it has none.
pub fn extension_of(path: &Path) -> String {
    path.extension()
        .and_then(|e| e.to_str())
        .unwrap_or("")
        .to_ascii_lowercase()
}

/// Reads a whole input file; an empty file is an error naming it.
pub fn read_file(path: &Path) -> crate::Result<Vec<u8>> {
    let bytes = std::fs::read(path).map_err(|e| crate::Error::io(path, e))?;
    if bytes.is_empty() {
        return Err(crate::Error::Decode {
            path: path.to_path_buf(),
            format: "input",
            message: "the file is empty".into(),
        });
    }
    Ok(bytes)
}

/// Pretty JSON with a final newline. Serialising splitsum's plain structs cannot fail, and
/// non-finite floats (which sanitised inputs never give) become `null`.
pub fn to_json(value: &impl serde::Serialize) -> String {
    let mut s = serde_json::to_string_pretty(value).unwrap_or_default();
    s.push('\n');
    s
}
