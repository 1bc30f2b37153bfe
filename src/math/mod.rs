//! CPU side of the maths shared with `shaders/common/*.wgsl`. Each Rust function of the
//! shared modules has a WGSL twin with the same name, so the CPU reference and the GPU
//! kernels compute the same thing step by step; `color` (the sRGB transfer functions),
//! `quadrature` and `lookup` (the lookup directions the study compares) are used on the
//! CPU only.

pub mod brdf;
pub mod color;
pub mod cubemap;
// The lookup study's (an example): not part of a build without the internals.
#[cfg(any(test, feature = "internals"))]
pub mod lookup;
pub mod quadrature;
pub mod sampling;
pub mod sh;
pub mod trig;
