//! CPU twins of the WGSL kernels: each file mirrors one kernel in `shaders/` function for
//! function (same names, same order of operations), so the GPU results can be checked
//! against them and the CPU backend ([`crate::backend`]) computes the same values.
//!
//! | file | kernel |
//! |---|---|
//! | `brdf_lut.rs` | `shaders/brdf_lut.wgsl` |
//! | `equirect_to_cube.rs` | `shaders/equirect_to_cube.wgsl` |
//! | `prefilter_sampled.rs` | `shaders/prefilter_sampled.wgsl` |
//! | `convolve_exact.rs` | `shaders/convolve_exact.wgsl` (specular, irradiance, sheen) |
//! | `preview_split_sum.rs` | `shaders/preview_split_sum.wgsl` |
//! | `preview_truth.rs` | `shaders/preview_truth.wgsl` |
//! | `ltc_fit.rs` | `shaders/ltc_fit.wgsl` |
//!
//! The shared WGSL in `shaders/common/` has its twins in [`crate::math`] and, for cube
//! sampling, [`crate::environment::sample`]; the mip reduction's
//! (`shaders/cube_downsample.wgsl`) is [`crate::environment::mips`], since every cube of
//! an environment carries that chain.

pub mod brdf_lut;
pub mod convolve_exact;
pub mod equirect_to_cube;
pub mod ltc_fit;
pub mod prefilter_sampled;
pub mod preview_split_sum;
pub mod preview_truth;
