//! CPU side of the maths shared with `shaders/common/*.wgsl`. Each Rust function here has a
//! WGSL twin with the same name, so the CPU reference and the GPU kernels compute the same
//! thing step by step.

pub mod brdf;
pub mod cubemap;
pub mod quadrature;
pub mod sampling;
pub mod sh;
pub mod trig;
