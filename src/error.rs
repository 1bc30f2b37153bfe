//! The library's error type. Every variant names what failed (a file, a parameter, the
//! GPU) and why, so the binary can print one clear line per failure.

use std::path::PathBuf;

/// Everything that can go wrong in splitsum. The library never panics on bad input and
/// never prints: it returns one of these.
#[derive(Debug, thiserror::Error)]
pub enum Error {
    /// Reading or writing a file failed at the OS level. (The I/O error is part of the
    /// message rather than a separate `source`, so it is printed once.)
    #[error("{path}: {error}")]
    Io {
        /// The file or folder involved.
        path: PathBuf,
        /// The underlying I/O error.
        error: std::io::Error,
    },

    /// The output path's extension does not name a format this output can be written as.
    #[error("{path}: cannot write {what} as '.{extension}' (supported: {supported})")]
    UnsupportedOutputFormat {
        /// The requested output path.
        path: PathBuf,
        /// What was being written (for example "a BRDF LUT").
        what: &'static str,
        /// The extension found (empty when there is none).
        extension: String,
        /// The extensions that are supported, comma separated.
        supported: String,
    },

    /// Encoding an output file failed (the encoder rejected the data).
    #[error("{path}: could not encode {format}: {message}")]
    Encode {
        /// The output path.
        path: PathBuf,
        /// The file format being written.
        format: &'static str,
        /// The encoder's message.
        message: String,
    },

    /// A block encoder reported a failure (astc-encoder returns a status for every call).
    #[error("{encoder} failed: {message}")]
    Encoder {
        /// The encoder.
        encoder: &'static str,
        /// Its message.
        message: String,
    },

    /// An input file could not be decoded: truncated, corrupt, or not the format its
    /// extension says.
    #[error("{path}: not a valid {format} file: {message}")]
    Decode {
        /// The input file.
        path: PathBuf,
        /// The format it was read as.
        format: &'static str,
        /// What is wrong.
        message: String,
    },

    /// An input file is well formed but uses something splitsum does not support, or is
    /// not an environment (wrong aspect ratio, too small or too large, unknown layout).
    #[error("{path}: {message}")]
    UnsupportedInput {
        /// The input file.
        path: PathBuf,
        /// What is unsupported, and what is expected instead.
        message: String,
    },

    /// An option is outside what splitsum supports, or contradicts another (checked before
    /// any input is read).
    #[error("invalid {option}: {message}")]
    InvalidOption {
        /// The option's field name in the library's options (for example
        /// `"specular_size"` of [`crate::BakeOptions`]; `"preview.cell"` for a field of its
        /// preview options).
        option: &'static str,
        /// What is wrong and what is allowed, in words.
        message: String,
    },

    /// The GPU backend was requested but no wgpu adapter could be found.
    #[error("no GPU adapter found ({reason}); on Linux without a GPU install Mesa's lavapipe (apt-get install mesa-vulkan-drivers libvulkan1), or use the CPU backend")]
    NoAdapter {
        /// What wgpu reported.
        reason: String,
    },

    /// `splitsum view` was asked for a window where no display is reachable.
    #[error("no display to open a window on ($DISPLAY and $WAYLAND_DISPLAY are unset); `splitsum view --screenshot view.png` renders the same picture without one")]
    NoDisplay,

    /// The viewer's window or its surface failed.
    #[error("{message}")]
    Window {
        /// What failed, in words.
        message: String,
    },

    /// The GPU device could not be created, or reported an error while running a kernel.
    #[error("GPU error in {stage}: {message}")]
    Gpu {
        /// What was being done (for example "brdf_lut dispatch").
        stage: String,
        /// wgpu's message.
        message: String,
    },
}

/// Shorthand for results in this crate.
pub type Result<T, E = Error> = std::result::Result<T, E>;

impl Error {
    /// Wraps an I/O error with the path it concerns.
    pub fn io(path: impl Into<PathBuf>, error: std::io::Error) -> Self {
        Error::Io {
            path: path.into(),
            error,
        }
    }
}
