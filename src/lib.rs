//! # splitsum
//!
//! Bakes image-based lighting for physically based renderers: the split-sum BRDF lookup
//! table, HDRI → cubemap conversion, prefiltered GGX specular cubemaps, diffuse irradiance
//! and spherical harmonics, with WGSL compute kernels run through wgpu, checked against a
//! CPU reference that is written function for function like the WGSL.
//!
//! A whole bake from a `build.rs`:
//!
//! ```no_run
//! use splitsum::bake::{bake, BakeOptions};
//! let (backend, _note) = splitsum::create_backend(splitsum::BackendChoice::Auto)?;
//! let lut = backend.brdf_lut(512, 512)?; // the generic target's one LUT file
//! let report = bake(backend.as_ref(), "sky.hdr".as_ref(), "out".as_ref(),
//!                   &BakeOptions::default(), &[lut], &mut |_stage| {})?;
//! println!("wrote {}", report.out_dir.display());
//! # Ok::<(), splitsum::Error>(())
//! ```
//!
//! Or just the LUT:
//!
//! ```no_run
//! use splitsum::{create_backend, BackendChoice};
//! use splitsum::io::lut::{write_lut, LutWriteOptions};
//!
//! let (backend, _note) = create_backend(BackendChoice::Auto)?;
//! let lut = backend.brdf_lut(512, 512)?;
//! write_lut("out/brdf_lut.png".as_ref(), &lut, LutWriteOptions::default())?;
//! # Ok::<(), splitsum::Error>(())
//! ```
//!
//! The library never prints and never panics on bad input; every failure is an [`Error`].

pub mod backend;
pub mod bake;
pub mod convert;
pub mod cpu;
pub mod environment;
pub mod error;
pub mod gpu;
pub mod io;
pub mod lut;
pub mod math;
pub mod preview;
pub mod target;
pub mod verify;

pub use backend::{
    create_backend, Backend, BackendChoice, CpuBackend, GpuBackend, SoftwareAdapterBackend,
};
pub use environment::{Cubemap, Environment, Equirect};
pub use error::{Error, Result};
pub use lut::BrdfLut;
