//! CPU reference kernels. Each file mirrors one WGSL kernel in `shaders/` function for
//! function; they are the ground the GPU results are checked against, and the `cpu` backend.

pub mod brdf_lut;
pub mod cube_downsample;
pub mod cube_resample;
pub mod cube_sample;
pub mod equirect_to_cube;
pub mod irradiance;
pub mod lut_interpolation;
pub mod prefilter_sheen;
pub mod prefilter_specular;
pub mod preview_split_sum;
pub mod preview_truth;
pub mod roughest_level;
pub mod sh_project;
