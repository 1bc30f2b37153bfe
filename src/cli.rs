//! Command-line definitions (clap derive). Parsing only; `main.rs` calls the library.

use std::path::PathBuf;

use clap::{Args, Parser, Subcommand, ValueEnum};

/// Bakes image-based lighting for physically based renderers.
///
/// Conventions: perceptual roughness r with GGX α = r², Smith/Schlick-GGX k = r²/2 for IBL,
/// Fresnel-Schlick. LUT texel (i, j) of a W×H table holds n·v = (i+½)/W and r = (j+½)/H;
/// row 0 (r ≈ 0) is the first row of every file (top of a PNG), so a shader samples it at
/// uv = (n·v, r). R = scale A and G = bias B: specular ≈ prefiltered · (F0·A + B).
#[derive(Debug, Parser)]
#[command(
    name = "splitsum",
    version,
    about,
    long_about,
    propagate_version = true
)]
#[command(after_help = "Exit codes: 0 success, 1 a job failed, 2 usage error.")]
pub struct Cli {
    /// What to bake.
    #[command(subcommand)]
    pub command: Command,
}

/// The subcommands.
#[derive(Debug, Subcommand)]
pub enum Command {
    /// Writes the split-sum BRDF lookup table (scale A in R, bias B in G).
    ///
    /// Texel (i, j) of an N×N table holds n·v = (i+½)/N and roughness r = (j+½)/N; row 0
    /// (r ≈ 0) is the first row stored (top of a PNG), so a shader samples it at
    /// uv = (n·v, r) and computes specular ≈ prefiltered · (F0·A + B). GGX with α = r²,
    /// Smith/Schlick-GGX with k = r²/2, Fresnel-Schlick.
    ///
    /// Format from the extension: .png (16-bit RGB, B = 0), .exr (float32 R, G),
    /// .ktx2 (R16G16_SFLOAT, or R32G32_SFLOAT with --f32), .dds (DXGI R16G16_FLOAT or
    /// R32G32_FLOAT with --f32).
    Lut(LutArgs),
}

/// Options shared by every command.
#[derive(Debug, Args)]
pub struct CommonArgs {
    /// Compute backend: auto picks a GPU adapter when there is one (Mesa's lavapipe counts)
    /// and the CPU otherwise.
    #[arg(long, value_enum, default_value_t = BackendArg::Auto)]
    pub backend: BackendArg,

    /// Print the adapter used and timings to stderr.
    #[arg(short, long)]
    pub verbose: bool,
}

/// `splitsum lut`.
#[derive(Debug, Args)]
pub struct LutArgs {
    /// Output file; the extension picks the format.
    #[arg(short, long, default_value = "out/brdf_lut.png")]
    pub output: PathBuf,

    /// Width and height of the table in texels.
    #[arg(long, default_value_t = 512,
          value_parser = clap::value_parser!(u32).range(1..=splitsum::lut::MAX_LUT_SIZE as i64))]
    pub size: u32,

    /// KTX2/DDS: store 32-bit floats instead of 16-bit.
    #[arg(long = "f32")]
    pub f32: bool,

    #[command(flatten)]
    pub common: CommonArgs,
}

/// `--backend` values.
#[derive(Clone, Copy, Debug, ValueEnum)]
pub enum BackendArg {
    /// GPU when available, else CPU.
    Auto,
    /// GPU (wgpu) only; fails without an adapter.
    Gpu,
    /// CPU reference implementation.
    Cpu,
}

impl From<BackendArg> for splitsum::BackendChoice {
    fn from(b: BackendArg) -> Self {
        match b {
            BackendArg::Auto => splitsum::BackendChoice::Auto,
            BackendArg::Gpu => splitsum::BackendChoice::Gpu,
            BackendArg::Cpu => splitsum::BackendChoice::Cpu,
        }
    }
}
