//! CPU side of the maths shared with `shaders/common/*.wgsl`. Each Rust function of the
//! shared modules has a WGSL twin with the same name, so the CPU reference and the GPU
//! kernels compute the same thing step by step; `color` (the sRGB transfer functions),
//! `ltc` (linearly transformed cosines) and `quadrature` are used on the CPU only, and `lookup` gives the kernels the bend of the
//! chain's lookup direction (`bent_reflection` is the WGSL's).

pub mod brdf;
pub mod color;
pub mod cubemap;
pub mod lookup;
pub mod ltc;
pub mod quadrature;
pub mod sampling;
pub mod sh;
pub mod trig;
