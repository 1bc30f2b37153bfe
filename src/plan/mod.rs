//! The plan both backends follow: what each kernel computes and from what, decided once in
//! Rust so the CPU and GPU paths cannot disagree. The specular chain's layout and the
//! method per level ([`chain`]), the prepared sources of the prefilter ([`sources`]), the
//! sheen chain's plan and driver ([`sheen`]), the least-squares fit of a level for
//! bilinear lookups ([`fit`]), the conversion's parameters ([`convert`]), the LUT models
//! and their quadrature ([`lut`]), the BC6H and ASTC encoders' settings ([`bc6h`],
//! [`astc`]), the shading
//! functions' material ([`material`]), how a shader combines a bake's files ([`shading`]:
//! the recipe's and each engine's), the recipe's taps at grazing views ([`filtered`]), the
//! preview's scene ([`scene`]) and the LTC table of area lights ([`ltc`]).

pub mod astc;
pub mod bc6h;
pub mod chain;
pub mod convert;
pub mod filtered;
pub mod fit;
pub mod ltc;
pub mod lut;
pub mod material;
pub mod scene;
pub mod shading;
pub mod sheen;
pub mod sources;
