//! Atomic file output: write to a temporary file in the destination folder, flush it to
//! disk, then rename it over the destination. Readers never see a partial file, and a
//! failed write leaves whatever was there before untouched. The temporaries being written
//! are registered, so a program interrupted mid-write (the binary's Ctrl-C / SIGTERM
//! handler) can remove them with [`remove_in_flight_temporaries`].

use std::io::Write;
use std::path::{Path, PathBuf};
use std::sync::Mutex;

use crate::{Error, Result};

/// Temporaries created by [`stage`] and not yet renamed or removed.
static IN_FLIGHT: Mutex<Vec<PathBuf>> = Mutex::new(Vec::new());

fn track(tmp: &Path) {
    if let Ok(mut list) = IN_FLIGHT.lock() {
        list.push(tmp.to_path_buf());
    }
}

fn untrack(tmp: &Path) {
    if let Ok(mut list) = IN_FLIGHT.lock() {
        list.retain(|p| p != tmp);
    }
}

/// Removes every temporary file a write in progress has created (best effort), and
/// returns how many there were. For an interrupt handler: the destinations keep their
/// previous contents, and no `.NAME.PID.tmp` file is left behind.
pub fn remove_in_flight_temporaries() -> usize {
    let list = match IN_FLIGHT.lock() {
        Ok(mut list) => std::mem::take(&mut *list),
        Err(_) => return 0,
    };
    for tmp in &list {
        let _ = std::fs::remove_file(tmp);
    }
    list.len()
}

/// Writes `bytes` to `path` atomically, creating the parent folders.
pub fn write_atomic(path: &Path, bytes: &[u8]) -> Result<()> {
    write_all_atomic(&[(path.to_path_buf(), bytes.to_vec())])
}

/// Writes several files as one unit: every file is staged as a temporary file beside its
/// destination first; only when all are written and flushed are they renamed into place.
/// On failure the temporaries are removed and no destination has changed.
pub fn write_all_atomic(files: &[(PathBuf, Vec<u8>)]) -> Result<()> {
    let mut staged: Vec<(PathBuf, &Path)> = Vec::new();
    let cleanup = |staged: &[(PathBuf, &Path)]| {
        for (tmp, _) in staged {
            let _ = std::fs::remove_file(tmp);
            untrack(tmp);
        }
    };
    for (path, bytes) in files {
        match stage(path, bytes) {
            Ok(tmp) => staged.push((tmp, path)),
            Err(e) => {
                cleanup(&staged);
                return Err(e);
            }
        }
    }
    for (i, (tmp, path)) in staged.iter().enumerate() {
        if let Err(e) = std::fs::rename(tmp, path) {
            cleanup(&staged[i..]);
            return Err(Error::io(*path, e));
        }
        untrack(tmp);
    }
    Ok(())
}

/// Writes `bytes` to a temporary file beside `path` and returns the temporary's path.
fn stage(path: &Path, bytes: &[u8]) -> Result<PathBuf> {
    let parent = match path.parent() {
        Some(p) if !p.as_os_str().is_empty() => p.to_path_buf(),
        _ => PathBuf::from("."),
    };
    std::fs::create_dir_all(&parent).map_err(|e| Error::io(&parent, e))?;
    if path.is_dir() {
        return Err(Error::io(
            path,
            std::io::Error::other("is a folder, not a file"),
        ));
    }
    let name = path
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_else(|| "output".into());
    let tmp = parent.join(format!(".{name}.{}.tmp", std::process::id()));
    track(&tmp);
    let result = (|| {
        let mut f = std::fs::File::create(&tmp)?;
        f.write_all(bytes)?;
        f.sync_all()
    })();
    match result {
        Ok(()) => Ok(tmp),
        Err(e) => {
            let _ = std::fs::remove_file(&tmp);
            untrack(&tmp);
            Err(Error::io(path, e))
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A staged temporary is registered until renamed; an interrupt handler's call removes
    /// the ones still in flight and leaves finished files alone.
    #[test]
    fn in_flight_temporaries_are_removed_on_request() {
        let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("target/unit-test-tmp/atomic");
        std::fs::create_dir_all(&dir).unwrap();
        let done = dir.join("done.bin");
        write_atomic(&done, b"kept").unwrap();
        let tmp = stage(&dir.join("pending.bin"), b"partial").unwrap();
        assert!(tmp.exists());
        assert!(remove_in_flight_temporaries() >= 1);
        assert!(!tmp.exists(), "the temporary is removed");
        assert_eq!(std::fs::read(&done).unwrap(), b"kept");
        assert!(!dir.join("pending.bin").exists());
    }
}
