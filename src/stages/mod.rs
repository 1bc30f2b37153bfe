//! The stages of a bake, each a step over the backend's kernels: HDRI → cube conversion
//! ([`convert`], with [`resample`] for cube inputs), the SH projection ([`sh`]), the whole
//! light of one environment in memory ([`light`]: cube, specular chain, irradiance, sheen,
//! SH) and the preview ([`preview`]).

pub mod convert;
pub mod light;
pub mod preview;
pub mod resample;
pub mod sh;
