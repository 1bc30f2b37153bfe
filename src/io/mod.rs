//! Readers and writers, one file per format. Every writer goes through
//! [`atomic::write_atomic`], so an output is either complete or absent.

pub mod atomic;
pub mod cubemap;
pub mod dds;
pub mod exr;
pub mod format;
pub mod hdr;
pub mod input;
pub mod ktx2;
pub mod ldr;
pub mod limits;
pub mod lut;
pub mod png;

pub use format::{EncodedTexture, PixelFormat};

use std::path::Path;

/// The lower-cased extension of `path`, or "" when it has none.
pub fn extension_of(path: &Path) -> String {
    path.extension()
        .and_then(|e| e.to_str())
        .unwrap_or("")
        .to_ascii_lowercase()
}
