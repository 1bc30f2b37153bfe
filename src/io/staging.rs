//! The files of one output set (a bake's folder), staged in memory with their records
//! until they are written together ([`crate::io::atomic::write_all_atomic`]): a failed
//! output leaves nothing half-written and earlier files untouched.

use std::path::PathBuf;

use sha2::{Digest, Sha256};

use crate::environment::Cubemap;

/// One file of an output set.
#[derive(Clone, Debug)]
pub struct OutputRecord {
    /// Path of the file.
    pub path: PathBuf,
    /// What it holds ("specular", "irradiance", "sheen", "skybox", "background", "sun", "sh", "brdf_lut",
    /// "preview", "manifest").
    pub kind: &'static str,
    /// Pixel format or file format.
    pub format: String,
    /// Edge in texels (0 for non-images).
    pub size: u32,
    /// Mip levels (0 for non-images).
    pub levels: u32,
    /// File size in bytes.
    pub bytes: usize,
    /// SHA-256 of the file's bytes, hex.
    pub sha256: String,
}

/// What a staged file is: (kind, format, edge, levels), as [`OutputRecord`] records it.
pub type FileMeta<'a> = (&'static str, &'a str, u32, u32);

/// Files staged in memory, with their records, in the order they were added.
#[derive(Debug, Default)]
pub struct Staging {
    /// Each file's path and bytes.
    pub files: Vec<(PathBuf, Vec<u8>)>,
    /// Each file's record.
    pub records: Vec<OutputRecord>,
}

impl Staging {
    /// Adds a file.
    pub fn add(&mut self, path: PathBuf, bytes: Vec<u8>, meta: FileMeta) {
        self.records.push(OutputRecord {
            path: path.clone(),
            kind: meta.0,
            format: meta.1.to_string(),
            size: meta.2,
            levels: meta.3,
            bytes: bytes.len(),
            sha256: sha256_hex(&bytes),
        });
        self.files.push((path, bytes));
    }

    /// Adds the files of one cube (one, or one per level or face), of `kind` in `format`,
    /// with the cube's edge and level count.
    pub fn add_cube(
        &mut self,
        files: Vec<(PathBuf, Vec<u8>)>,
        kind: &'static str,
        format: &str,
        cube: &Cubemap,
    ) {
        for (path, bytes) in files {
            self.add(
                path,
                bytes,
                (kind, format, cube.size, cube.levels.len() as u32),
            );
        }
    }
}

/// SHA-256 of `bytes`, lower-case hex.
pub fn sha256_hex(bytes: &[u8]) -> String {
    Sha256::digest(bytes)
        .iter()
        .map(|b| format!("{b:02x}"))
        .collect()
}
