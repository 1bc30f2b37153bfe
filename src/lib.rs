//! # splitsum
//!
//! Bakes image-based lighting for physically based renderers: the split-sum BRDF lookup
//! table, HDRI → cubemap conversion, prefiltered GGX specular cubemaps, diffuse irradiance
//! and spherical harmonics, with WGSL compute kernels run through wgpu, checked against a
//! CPU reference that is written function for function like the WGSL.
//!
//! A whole bake, as a `build.rs` or an asset server calls it: [`Baker`] validates the
//! options (an [`Error::InvalidOption`] names the field), picks the backend with the
//! command line's fallback policy, computes the LUTs the target names, and writes exactly
//! what `splitsum bake --target T` writes.
//!
//! ```no_run
//! use splitsum::{BakeOptions, Baker, TARGETS};
//! for target in TARGETS {
//!     let mut baker = Baker::new(BakeOptions::for_target(target))?;
//!     let report = baker.bake("sky.hdr".as_ref(), format!("out/{}", target.name).as_ref())?;
//!     for warning in &report.warnings {
//!         eprintln!("warning: {warning}");
//!     }
//! }
//! # Ok::<(), splitsum::Error>(())
//! ```
//!
//! The in-memory pieces, for callers that write their own files: [`Baker::load`],
//! [`Baker::bake_environment`] (a [`BakedEnvironment`]: the specular chain, irradiance,
//! SH), [`Baker::lut`] (a [`BrdfLut`]), [`Baker::cubemap`] (an HDRI as a [`Cubemap`]),
//! and the writers [`write_cubemap`] and [`write_lut`].
//!
//! The library never prints and never panics on bad input; every failure is an [`Error`].
//! Its conventions (orientation, texel centres, roughness per mip, units, LUT axes, each
//! target's frame) are in `docs/conventions.md`.
//!
//! # Layers
//!
//! The modules, from the bottom; none imports from a layer above its own
//! (`tests/layers.rs` checks it), and no two modules import each other:
//!
//! 0. `error`: the error type.
//! 1. `math`: the maths shared with `shaders/common/*.wgsl` (BRDF, sampling, cube
//!    directions, SH, trigonometry, quadrature).
//! 2. `environment`: equirects and cubemaps in memory, their texel walk and sampling, the
//!    hot-texel split and the source texels the exact kernels read.
//! 3. `plan`: what both backends compute: the specular chain's layout and method per
//!    level, the prepared sources, the sheen chain's driver, the LUT models, the preview's
//!    scene.
//! 4. `cpu` (the CPU twins of the WGSL kernels, one file each) and `gpu` (wgpu, one file
//!    per kernel binding).
//! 5. `backend`: the `Backend` trait with its CPU and GPU implementations.
//! 6. `stages`: conversion, the in-memory bake of one environment, SH, the preview.
//! 7. `io` (every format, read and written in its own module, and the one cube container
//!    dispatcher) and `targets` (one module per engine: its table and its writer).
//! 8. `bake` (the whole bake, the manifest, [`Baker`]) and `verify`.
//! 9. `view` (feature `view`): the interactive viewer, its renderers and window.
//! 10. the command line (`src/main.rs`, `src/cli/`), which only uses what is exported here.

#![warn(missing_docs)]

/// Declares the crate's internal modules: `pub(crate)`, or public but hidden from the
/// documentation with the `internals` feature (the project's own tests, benchmarks and fuzz
/// targets reach the kernels through it; it is not part of the API and may change).
macro_rules! internal_modules {
    ($($name:ident),* $(,)?) => {
        $(
            #[cfg(feature = "internals")]
            #[doc(hidden)]
            pub mod $name;
            #[cfg(not(feature = "internals"))]
            pub(crate) mod $name;
        )*
    };
}

internal_modules!(
    error,
    math,
    environment,
    plan,
    cpu,
    gpu,
    backend,
    stages,
    io,
    targets,
    bake,
    verify,
);

// `splitsum view` (feature `view`): public but hidden with `internals`, crate-private
// otherwise; its front door is re-exported below. (A plain comment: an outer doc comment
// here would be joined to the module's own and its links resolved from the crate root.)
#[cfg(all(feature = "view", feature = "internals"))]
#[doc(hidden)]
pub mod view;
#[cfg(all(feature = "view", not(feature = "internals")))]
pub(crate) mod view;

pub use backend::{BackendChoice, BackendJob};
pub use bake::{
    clipped_sun_warning, read_bake_dir, BakeOptions, BakeReport, Baker, LoadedInput, Manifest,
};
pub use cpu::ltc_fit::fit_ltc;
pub use environment::inventory::{inventory, Inventory};
pub use environment::sun::{
    find_lights, find_sources, find_sun, split_lights, split_sun, take_sources_out, RectLight,
    Source, SourceShape, Sun, SunFit, SunMode, MAX_LIGHTS, MIN_SHARE as MIN_SUN_SHARE,
};
pub use environment::{Cubemap, Environment, Equirect};
pub use error::{Error, Result};
pub use io::atomic::remove_in_flight_temporaries;
pub use io::atomic::write_atomic;
pub use io::check_output_extension;
pub use io::cubemap::{check_cube_path, write_cubemap, Container, CubeLayout, CubeWriteOptions};
pub use io::format::CUBE_PIXEL_FORMATS;
pub use io::input::input_stem;
pub use io::ltc::{read_ltc, write_ltc};
pub use io::lut::{check_lut_path, png_clip_warning, write_lut, LutWriteOptions};
pub use io::staging::OutputRecord;
pub use io::PixelFormat;
pub use math::lookup::SpecularLookup;
pub use plan::astc::AstcQuality;
pub use plan::bc6h::Bc6hQuality;
pub use plan::chain::{MipRoughness, SpecularChain};
pub use plan::ltc::{LtcCell, LtcTable};
pub use plan::lut::{BrdfLut, LutModel, DEFAULT_LUT_SIZE, MAX_LUT_SIZE};
pub use plan::shading::{
    DiffuseLobe, IblTerms, IrradianceSource, LightBrdf, Masking, Shading, ShadingTerms,
};
pub use stages::convert::check_cube_size;
pub use stages::light::{BakedEnvironment, Stage};
pub use stages::preview::{
    Preview, PreviewOptions, SphereStats, PREVIEW_ROUGHNESS, RELATIVE_DIFFERENCE_DEFINITION,
};
pub use stages::sh::ShCoefficients;
pub use targets::generic::sun_json;
pub use targets::{
    FileSet, LutChannels, LutSpec, Orientation, Target, BABYLON, BEVY, FILAMENT, GENERIC, GLTF,
    TARGETS, THREE,
};
pub use verify::{verify_input, Verification, VerifyRow};
#[cfg(feature = "view")]
pub use view::{
    render_screenshot, run as run_view,
    state::{parse_keys, Action as ViewAction, KEYS as VIEW_KEYS},
    LightSource, ViewOptions, DEFAULT_SIZE as VIEW_DEFAULT_SIZE,
};
