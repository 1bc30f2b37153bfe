//! WGSL sources assembled at compile time: each kernel is the shared files it uses from
//! `shaders/common/` followed by its own file, concatenated, so shared functions exist once.

/// Declares an assembled kernel source: common files first, then the kernel.
macro_rules! kernel_source {
    ($kernel:literal, [$($common:literal),*]) => {
        concat!(
            include_str!("../../shaders/common/compute.wgsl"), "\n",
            include_str!("../../shaders/common/trig.wgsl"), "\n",
            $(include_str!(concat!("../../shaders/common/", $common)), "\n",)*
            include_str!(concat!("../../shaders/", $kernel))
        )
    };
}

/// Declares an assembled render-shader source (vertex and fragment stages, so without the
/// workgroup overrides): trig and the shared files it uses, then the shader.
#[cfg_attr(not(feature = "view"), allow(unused_macros))]
macro_rules! render_source {
    ($shader:literal, [$($common:literal),*]) => {
        concat!(
            include_str!("../../shaders/common/trig.wgsl"), "\n",
            $(include_str!(concat!("../../shaders/common/", $common)), "\n",)*
            include_str!(concat!("../../shaders/", $shader))
        )
    };
}

/// `shaders/brdf_lut.wgsl` with brdf and sampling.
pub const BRDF_LUT: &str = kernel_source!("brdf_lut.wgsl", ["brdf.wgsl", "sampling.wgsl"]);

/// `shaders/equirect_to_cube.wgsl` with cubemap.
pub const EQUIRECT_TO_CUBE: &str = kernel_source!("equirect_to_cube.wgsl", ["cubemap.wgsl"]);

/// `shaders/cube_downsample.wgsl` with cubemap.
pub const CUBE_DOWNSAMPLE: &str = kernel_source!("cube_downsample.wgsl", ["cubemap.wgsl"]);

/// `shaders/prefilter_sampled.wgsl` with brdf, sampling, cubemap, cube_fetch, cube_bilinear,
/// cube_sample.
pub const PREFILTER_SAMPLED: &str = kernel_source!(
    "prefilter_sampled.wgsl",
    [
        "brdf.wgsl",
        "sampling.wgsl",
        "cubemap.wgsl",
        "cube_fetch.wgsl",
        "cube_bilinear.wgsl",
        "cube_sample.wgsl"
    ]
);

/// `shaders/convolve_exact.wgsl` with brdf and cubemap.
pub const CONVOLVE_EXACT: &str =
    kernel_source!("convolve_exact.wgsl", ["brdf.wgsl", "cubemap.wgsl"]);

/// `shaders/preview_split_sum.wgsl` with brdf, cubemap, cube_fetch, cube_bilinear,
/// cube_sample, material, split_sum, preview_scene.
pub const PREVIEW_SPLIT_SUM: &str = kernel_source!(
    "preview_split_sum.wgsl",
    [
        "brdf.wgsl",
        "sampling.wgsl",
        "cubemap.wgsl",
        "cube_fetch.wgsl",
        "cube_bilinear.wgsl",
        "cube_sample.wgsl",
        "material.wgsl",
        "lut.wgsl",
        "split_sum.wgsl",
        "filtered.wgsl",
        "preview_scene.wgsl"
    ]
);

/// `shaders/ltc_fit.wgsl` with brdf and material.
pub const LTC_FIT: &str = kernel_source!("ltc_fit.wgsl", ["brdf.wgsl", "material.wgsl"]);

/// `shaders/preview_truth.wgsl` with brdf, sampling, cubemap, cube_fetch, cube_bilinear,
/// cube_sample, material, truth, preview_scene.
pub const PREVIEW_TRUTH: &str = kernel_source!(
    "preview_truth.wgsl",
    [
        "brdf.wgsl",
        "sampling.wgsl",
        "cubemap.wgsl",
        "cube_fetch.wgsl",
        "cube_bilinear.wgsl",
        "cube_sample.wgsl",
        "material.wgsl",
        "lut.wgsl",
        "truth.wgsl",
        "preview_scene.wgsl"
    ]
);

/// `shaders/view_split_sum.wgsl` with brdf, sampling, cubemap, cube_fetch_bordered,
/// cube_bilinear, cube_sample, material, split_sum, filtered, view_frame, view_surface, ltc,
/// view_sun, view_floor_shadow, view_floor, view_gbuffer_read, view_shade.
#[cfg_attr(not(feature = "view"), allow(dead_code))]
pub const VIEW_SPLIT_SUM: &str = kernel_source!(
    "view_split_sum.wgsl",
    [
        "brdf.wgsl",
        "sampling.wgsl",
        "cubemap.wgsl",
        "cube_fetch_bordered.wgsl",
        "cube_bilinear.wgsl",
        "cube_sample.wgsl",
        "material.wgsl",
        "lut.wgsl",
        "split_sum.wgsl",
        "filtered.wgsl",
        "view_frame.wgsl",
        "view_surface.wgsl",
        "ltc.wgsl",
        "view_sun.wgsl",
        "view_floor_shadow.wgsl",
        "view_floor.wgsl",
        "view_gbuffer_read.wgsl",
        "view_shade.wgsl"
    ]
);

/// `shaders/view_truth.wgsl` with brdf, sampling, cubemap, cube_fetch_bordered,
/// cube_bilinear, cube_sample, material, truth, view_frame, view_surface, ltc, view_sun,
/// view_floor_shadow, view_gbuffer_read.
#[cfg_attr(not(feature = "view"), allow(dead_code))]
pub const VIEW_TRUTH: &str = kernel_source!(
    "view_truth.wgsl",
    [
        "brdf.wgsl",
        "sampling.wgsl",
        "cubemap.wgsl",
        "cube_fetch_bordered.wgsl",
        "cube_bilinear.wgsl",
        "cube_sample.wgsl",
        "material.wgsl",
        "truth.wgsl",
        "view_frame.wgsl",
        "view_surface.wgsl",
        "ltc.wgsl",
        "view_sun.wgsl",
        "view_floor_shadow.wgsl",
        "view_gbuffer_read.wgsl"
    ]
);

/// `shaders/view_gbuffer.wgsl` with view_frame and view_raster.
#[cfg_attr(not(feature = "view"), allow(dead_code))]
pub const VIEW_GBUFFER: &str = render_source!(
    "view_gbuffer.wgsl",
    ["view_frame.wgsl", "view_raster.wgsl"]
);

/// `shaders/view_present.wgsl` with view_display, without the constants the viewer writes
/// before it (`view::gpu::present_source`).
#[cfg_attr(not(feature = "view"), allow(dead_code))]
pub const VIEW_PRESENT_BODY: &str = render_source!("view_present.wgsl", ["view_display.wgsl"]);

/// `shaders/view_forward.wgsl` with brdf, sampling, cubemap, cube_filter_bordered,
/// cube_sample, material, split_sum, filtered, view_frame, view_surface, ltc, view_sun,
/// view_floor_shadow, view_floor, view_gbuffer_read, view_shade, view_floor_filter,
/// view_raster, view_display,
/// without the constants the viewer writes before it (`view::gpu::forward_source`).
#[cfg_attr(not(feature = "view"), allow(dead_code))]
pub const VIEW_FORWARD_BODY: &str = render_source!(
    "view_forward.wgsl",
    [
        "brdf.wgsl",
        "sampling.wgsl",
        "cubemap.wgsl",
        "cube_filter_bordered.wgsl",
        "cube_sample.wgsl",
        "material.wgsl",
        "lut.wgsl",
        "split_sum.wgsl",
        "filtered.wgsl",
        "view_frame.wgsl",
        "view_surface.wgsl",
        "ltc.wgsl",
        "view_sun.wgsl",
        "view_floor_shadow.wgsl",
        "view_floor.wgsl",
        "view_gbuffer_read.wgsl",
        "view_shade.wgsl",
        "view_floor_filter.wgsl",
        "view_raster.wgsl",
        "view_display.wgsl"
    ]
);

#[cfg(any(test, feature = "internals"))]
/// Every assembled kernel by name, for validation.
pub const ALL: &[(&str, &str)] = &[
    ("prefilter_sampled", PREFILTER_SAMPLED),
    ("convolve_exact", CONVOLVE_EXACT),
    ("brdf_lut", BRDF_LUT),
    ("equirect_to_cube", EQUIRECT_TO_CUBE),
    ("cube_downsample", CUBE_DOWNSAMPLE),
    ("preview_split_sum", PREVIEW_SPLIT_SUM),
    ("preview_truth", PREVIEW_TRUTH),
    ("ltc_fit", LTC_FIT),
    ("view_split_sum", VIEW_SPLIT_SUM),
    ("view_truth", VIEW_TRUTH),
];
