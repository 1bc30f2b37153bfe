//! The wgpu side: a headless context, a small compute-pass helper with one readback
//! routine, the assembled WGSL sources, and one file per kernel that binds its shader.
//!
//! Kernels take `&wgpu::Device, &wgpu::Queue`, so tests, the CLI and library users share
//! one [`GpuContext`].

pub mod bc6h;
pub mod brdf_lut;
pub mod compute;
pub mod context;
pub mod equirect_to_cube;
pub mod ltc_fit;
pub mod prefilter;
pub mod preview;
pub mod shaders;
pub mod texture;

pub use context::GpuContext;
