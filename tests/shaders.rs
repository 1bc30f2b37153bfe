//! Every assembled WGSL kernel parses and validates with naga (no GPU needed), and the
//! uniform blocks the Rust side fills have the layout the WGSL declares.

use naga::valid::{Capabilities, ValidationFlags, Validator};

fn parse(name: &str, source: &str) -> naga::Module {
    naga::front::wgsl::parse_str(source)
        .unwrap_or_else(|e| panic!("{name}: {}", e.emit_to_string(source)))
}

#[test]
fn all_kernels_validate() {
    for (name, source) in splitsum::gpu::shaders::ALL {
        let module = parse(name, source);
        Validator::new(ValidationFlags::all(), Capabilities::empty())
            .validate(&module)
            .unwrap_or_else(|e| panic!("{name}: {}", e.emit_to_string(source)));
        assert!(
            module.entry_points.iter().any(|e| e.name == "main"),
            "{name} has no main"
        );
    }
}

/// (member name, byte offset) of a WGSL struct, and its size.
fn struct_layout(module: &naga::Module, name: &str) -> (Vec<(String, u32)>, u32) {
    for (_, ty) in module.types.iter() {
        if ty.name.as_deref() == Some(name) {
            if let naga::TypeInner::Struct { members, span } = &ty.inner {
                return (
                    members
                        .iter()
                        .map(|m| (m.name.clone().unwrap_or_default(), m.offset))
                        .collect(),
                    *span,
                );
            }
        }
    }
    panic!("struct {name} not found");
}

#[test]
fn lut_params_layout_matches_rust() {
    use splitsum::plan::lut::LutParams;
    use std::mem::{offset_of, size_of};
    let module = parse("brdf_lut", splitsum::gpu::shaders::BRDF_LUT);
    let (members, span) = struct_layout(&module, "LutParams");
    let rust = [
        ("size", offset_of!(LutParams, size)),
        ("full_rule", offset_of!(LutParams, full_rule)),
        ("partial_rule", offset_of!(LutParams, partial_rule)),
        ("phi_rule", offset_of!(LutParams, phi_rule)),
        ("panel_growth", offset_of!(LutParams, panel_growth)),
        ("max_panels", offset_of!(LutParams, max_panels)),
        ("visibility", offset_of!(LutParams, visibility)),
        ("channel_layout", offset_of!(LutParams, channel_layout)),
        ("distribution", offset_of!(LutParams, distribution)),
    ];
    assert_eq!(members.len(), rust.len());
    for ((wname, woff), (rname, roff)) in members.iter().zip(rust) {
        assert_eq!((wname.as_str(), *woff as usize), (rname, roff));
    }
    assert!(size_of::<LutParams>() >= span as usize);
    assert_eq!(size_of::<LutParams>() % 16, 0);
}

/// The literal the WGSL `const` named `name` is initialised with.
fn wgsl_constant(module: &naga::Module, name: &str) -> naga::Literal {
    let (_, c) = module
        .constants
        .iter()
        .find(|(_, c)| c.name.as_deref() == Some(name))
        .unwrap_or_else(|| panic!("{name} missing"));
    match module.global_expressions[c.init] {
        naga::Expression::Literal(l) => l,
        ref other => panic!("{name}: {other:?}"),
    }
}

/// The value of the WGSL `const` named `name`, an f32 literal.
fn wgsl_f32_constant(module: &naga::Module, name: &str) -> f32 {
    match wgsl_constant(module, name) {
        naga::Literal::F32(v) => v,
        other => panic!("{name}: {other:?}"),
    }
}

/// The value of the WGSL `const` named `name`, a u32 literal.
fn wgsl_u32_constant(module: &naga::Module, name: &str) -> u32 {
    match wgsl_constant(module, name) {
        naga::Literal::U32(v) => v,
        other => panic!("{name}: {other:?}"),
    }
}

/// The WGSL atan coefficients are the Rust ones (one source of truth, checked).
#[test]
fn atan_coefficients_match_rust() {
    let module = parse("equirect_to_cube", splitsum::gpu::shaders::EQUIRECT_TO_CUBE);
    for (k, expected) in splitsum::math::trig::ATAN_COEFFS.iter().enumerate() {
        let name = format!("ATAN_C{k}");
        assert_eq!(wgsl_f32_constant(&module, &name), *expected, "{name}");
    }
}

/// The split-sum shading's constants (the diffuse weight's fit, the stretched lookup's
/// guard and fade) are the same on both sides.
#[test]
fn split_sum_constants_match_rust() {
    use splitsum::math::brdf::{DIFFUSE_FRESNEL_POWER, DIFFUSE_FRESNEL_SCALE};
    use splitsum::math::lookup::{STRETCH_EPSILON, STRETCH_FADE_ROUGHNESS};
    let module = parse(
        "preview_split_sum",
        splitsum::gpu::shaders::PREVIEW_SPLIT_SUM,
    );
    for (name, rust) in [
        ("DIFFUSE_FRESNEL_SCALE", DIFFUSE_FRESNEL_SCALE),
        ("DIFFUSE_FRESNEL_POWER", DIFFUSE_FRESNEL_POWER),
        ("STRETCH_EPSILON", STRETCH_EPSILON),
        ("STRETCH_FADE_ROUGHNESS", STRETCH_FADE_ROUGHNESS),
    ] {
        assert_eq!(wgsl_f32_constant(&module, name), rust, "{name}");
    }
}

/// The grazing taps' constants (`plan::filtered`) and the chain's mappings
/// (`plan::chain::MipRoughness`) are the same on both sides.
#[test]
fn filtered_lookup_constants_match_rust() {
    use splitsum::plan::chain::{MipRoughness, BABYLON_LOD_SCALE, BABYLON_MINIMUM_VARIANCE};
    use splitsum::plan::filtered::{
        FILTERED_FADE_IN_ROUGHNESS, FILTERED_LEVEL_TAPS, FILTERED_LOD_BIAS, FILTERED_N_DOT_V,
        FILTERED_PLANE_POINTS, FILTERED_ROUGHNESS, FILTERED_TAPS, MIN_FILTERED_ALPHA,
    };
    let module = parse(
        "preview_split_sum",
        splitsum::gpu::shaders::PREVIEW_SPLIT_SUM,
    );
    for (name, rust) in [
        ("FILTERED_N_DOT_V_LO", FILTERED_N_DOT_V[0]),
        ("FILTERED_N_DOT_V_HI", FILTERED_N_DOT_V[1]),
        ("FILTERED_ROUGHNESS_LO", FILTERED_ROUGHNESS[0]),
        ("FILTERED_ROUGHNESS_HI", FILTERED_ROUGHNESS[1]),
        ("FILTERED_FADE_IN_ROUGHNESS", FILTERED_FADE_IN_ROUGHNESS),
        ("FILTERED_LOD_BIAS", FILTERED_LOD_BIAS),
        ("FILTERED_PLANE_INNER", FILTERED_PLANE_POINTS[0]),
        ("FILTERED_PLANE_OUTER", FILTERED_PLANE_POINTS[1]),
        ("MIN_FILTERED_ALPHA", MIN_FILTERED_ALPHA),
        ("BABYLON_LOD_SCALE", BABYLON_LOD_SCALE),
        ("BABYLON_MINIMUM_VARIANCE", BABYLON_MINIMUM_VARIANCE),
    ] {
        assert_eq!(wgsl_f32_constant(&module, name), rust, "{name}");
    }
    for (name, rust) in [
        ("FILTERED_TAPS", FILTERED_TAPS),
        ("FILTERED_LEVEL_TAPS", FILTERED_LEVEL_TAPS),
        ("MIP_ROUGHNESS_LINEAR", MipRoughness::Linear.code()),
        ("MIP_ROUGHNESS_QUADRATIC", MipRoughness::Quadratic.code()),
    ] {
        assert_eq!(wgsl_u32_constant(&module, name), rust, "{name}");
    }
    // The third mapping is the kernels' fall-through.
    assert_eq!(MipRoughness::Babylon.code(), 2);
}

/// The shading models' codes (`plan::shading`'s enums as u32) and the Fresnel mean are
/// the same on both sides.
#[test]
fn shading_codes_match_rust() {
    use splitsum::plan::shading::{
        DiffuseLobe, IblTerms, Masking, RadianceBlend, FRESNEL_MEAN_WEIGHT,
    };
    let module = parse("preview_truth", splitsum::gpu::shaders::PREVIEW_TRUTH);
    let split = parse(
        "preview_split_sum",
        splitsum::gpu::shaders::PREVIEW_SPLIT_SUM,
    );
    assert_eq!(
        wgsl_f32_constant(&split, "FRESNEL_MEAN_WEIGHT"),
        FRESNEL_MEAN_WEIGHT
    );
    for (m, name, rust) in [
        (&split, "IBL_TERMS_SPLITSUM", IblTerms::Splitsum as u32),
        (
            &split,
            "IBL_TERMS_ENERGY_COMPENSATED",
            IblTerms::EnergyCompensated as u32,
        ),
        (
            &split,
            "IBL_TERMS_MULTISCATTER_IRRADIANCE",
            IblTerms::MultiscatterIrradiance as u32,
        ),
        (
            &split,
            "IBL_TERMS_MULTISCATTER_RADIANCE",
            IblTerms::MultiscatterRadiance as u32,
        ),
        (
            &split,
            "IBL_TERMS_LEGACY_DIFFUSE",
            IblTerms::LegacyDiffuse as u32,
        ),
        (&split, "RADIANCE_BLEND_NONE", RadianceBlend::None as u32),
        (&split, "RADIANCE_BLEND_ALPHA", RadianceBlend::Alpha as u32),
        (
            &split,
            "RADIANCE_BLEND_ALPHA_SQUARED",
            RadianceBlend::AlphaSquared as u32,
        ),
        (&module, "MASKING_SCHLICK_GGX", Masking::SchlickGgx as u32),
        (
            &module,
            "MASKING_SMITH_CORRELATED",
            Masking::SmithCorrelated as u32,
        ),
        (
            &module,
            "DIFFUSE_FRESNEL_WEIGHTED",
            DiffuseLobe::FresnelWeighted as u32,
        ),
        (&module, "DIFFUSE_LAMBERT", DiffuseLobe::Lambert as u32),
        (&module, "DIFFUSE_BURLEY", DiffuseLobe::Burley as u32),
        (
            &module,
            "DIFFUSE_DIELECTRIC_LAMBERT",
            DiffuseLobe::DielectricLambert as u32,
        ),
    ] {
        assert_eq!(wgsl_u32_constant(m, name), rust, "{name}");
    }
}

/// The small-cap threshold of the irradiance kernel is the same on both sides.
#[test]
fn small_cap_threshold_matches_rust() {
    let module = parse("convolve_exact", splitsum::gpu::shaders::CONVOLVE_EXACT);
    assert_eq!(
        wgsl_f32_constant(&module, "SMALL_CAP_SIN2"),
        splitsum::cpu::convolve_exact::SMALL_CAP_SIN2
    );
}

/// The conversion's Gauss-Legendre rule is the same on both sides.
#[test]
fn conversion_quadrature_matches_rust() {
    use splitsum::cpu::equirect_to_cube::{GAUSS_NODE, GAUSS_WEIGHTS};
    let module = parse("equirect_to_cube", splitsum::gpu::shaders::EQUIRECT_TO_CUBE);
    assert_eq!(wgsl_f32_constant(&module, "GAUSS_NODE"), GAUSS_NODE);
    assert_eq!(
        wgsl_f32_constant(&module, "GAUSS_WEIGHT_OUTER"),
        GAUSS_WEIGHTS[0]
    );
    assert_eq!(
        wgsl_f32_constant(&module, "GAUSS_WEIGHT_CENTRE"),
        GAUSS_WEIGHTS[1]
    );
}

/// Checks a WGSL struct's member names and offsets against a Rust `#[repr(C)]` struct.
macro_rules! assert_layout {
    ($source:expr, $wgsl:literal, $rust:ty, [$($field:ident),*]) => {{
        let module = parse($wgsl, $source);
        let (members, span) = struct_layout(&module, $wgsl);
        let rust: Vec<(&str, usize)> = vec![$((stringify!($field), std::mem::offset_of!($rust, $field))),*];
        assert_eq!(members.len(), rust.len(), "{}", $wgsl);
        for ((wname, woff), (rname, roff)) in members.iter().zip(&rust) {
            assert_eq!((wname.as_str(), *woff as usize), (*rname, *roff), "{}", $wgsl);
        }
        assert!(std::mem::size_of::<$rust>() >= span as usize);
        assert_eq!(std::mem::size_of::<$rust>() % 16, 0);
    }};
}

#[test]
fn kernel_uniforms_match_rust() {
    use splitsum::gpu::equirect_to_cube::EquirectToCubeUniform;
    use splitsum::gpu::prefilter::{ConvolveUniform, PrefilterUniform};
    use splitsum::gpu::shaders::{CONVOLVE_EXACT, EQUIRECT_TO_CUBE, PREFILTER_SAMPLED};
    assert_layout!(
        EQUIRECT_TO_CUBE,
        "EquirectToCubeParams",
        EquirectToCubeUniform,
        [face_size, pad, source_size, rotation, pad2]
    );
    assert_layout!(
        PREFILTER_SAMPLED,
        "PrefilterParams",
        PrefilterUniform,
        [env_size, env_levels, out_size, samples, roughness, lobe_count, hot_count, _pad]
    );
    assert_layout!(
        CONVOLVE_EXACT,
        "ConvolveParams",
        ConvolveUniform,
        [out_size, count, mode, roughness, hot_count, pad0, pad1, pad2]
    );
}

#[test]
fn preview_uniforms_match_rust() {
    use splitsum::gpu::preview::{SplitSumUniform, TruthUniform};
    use splitsum::gpu::shaders::{PREVIEW_SPLIT_SUM, PREVIEW_TRUTH};
    use splitsum::plan::scene::SceneUniform;
    for source in [PREVIEW_SPLIT_SUM, PREVIEW_TRUTH] {
        assert_layout!(
            source,
            "SceneParams",
            SceneUniform,
            [
                width,
                height,
                cell,
                columns,
                radius,
                tan_half_x,
                tan_half_y,
                min_n_dot_v,
                right,
                up,
                forward
            ]
        );
    }
    assert_layout!(
        PREVIEW_SPLIT_SUM,
        "SplitSumParams",
        SplitSumUniform,
        [
            specular_size,
            specular_levels,
            irradiance_size,
            lut_width,
            lut_height,
            ibl_terms,
            roughness_fresnel,
            radiance_blend,
            filtered,
            mip_roughness,
            pad
        ]
    );
    assert_layout!(
        PREVIEW_TRUTH,
        "TruthParams",
        TruthUniform,
        [
            env_size,
            hot_count,
            point_count,
            masking,
            diffuse,
            compensated,
            lut_width,
            lut_height
        ]
    );
}

/// The exact kernels read the source arrays as vec4s; the Rust structs are whole vec4s.
#[test]
fn source_texel_structs_are_whole_vec4s() {
    use splitsum::environment::texels::{MomentTexel, SourceTexel};
    assert_eq!(std::mem::size_of::<SourceTexel>(), 2 * 16);
    assert_eq!(std::mem::size_of::<MomentTexel>(), 5 * 16);
}

/// The viewer's render shaders (no `main`: vertex and fragment stages) validate, and its
/// uniform blocks have the layout the WGSL declares.
#[test]
fn viewer_shaders_validate_and_match_rust() {
    use splitsum::gpu::shaders::{VIEW_GBUFFER, VIEW_SPLIT_SUM, VIEW_TRUTH};
    use splitsum::view::frame::{FrameUniform, PresentUniform};
    let present = splitsum::view::gpu::present_source();
    let forward = splitsum::view::gpu::forward_source();
    for (name, source, entries) in [
        (
            "view_forward",
            forward.as_str(),
            &[
                "vs_main",
                "fs_object",
                "fs_floor",
                "vs_background",
                "fs_background",
            ][..],
        ),
        (
            "view_gbuffer",
            VIEW_GBUFFER,
            &["vs_main", "fs_mesh", "fs_sphere"][..],
        ),
        (
            "view_present",
            present.as_str(),
            &["vs_main", "fs_main"][..],
        ),
    ] {
        let module = parse(name, source);
        Validator::new(ValidationFlags::all(), Capabilities::empty())
            .validate(&module)
            .unwrap_or_else(|e| panic!("{name}: {}", e.emit_to_string(source)));
        for entry in entries {
            assert!(
                module.entry_points.iter().any(|e| e.name == *entry),
                "{name} has no {entry}"
            );
        }
    }
    for source in [VIEW_GBUFFER, VIEW_SPLIT_SUM, VIEW_TRUTH, forward.as_str()] {
        assert_layout!(
            source,
            "FrameParams",
            FrameUniform,
            [
                width,
                height,
                truth_frame,
                light_count,
                position,
                right,
                up,
                front,
                view_projection,
                object,
                floor,
                sphere,
                floor_plane,
                sun,
                shadow
            ]
        );
    }
    for source in [present.as_str(), forward.as_str()] {
        assert_layout!(
            source,
            "PresentParams",
            PresentUniform,
            [
                width,
                height,
                mode,
                reserved,
                exposure,
                heat_lo,
                heat_hi,
                heat_entries
            ]
        );
    }
}

/// The viewer's area lights and soft shadows: a split-out light's record, the soft
/// shadow's grids and the number of shadow maps are the same on both sides.
#[test]
fn view_area_light_constants_match_rust() {
    let module = parse("view_split_sum", splitsum::gpu::shaders::VIEW_SPLIT_SUM);
    for (name, rust) in [
        ("SPLIT_RECORD", splitsum::view::frame::SPLIT_RECORD as u32),
        ("BLOCKER_TAPS", splitsum::view::shadow::BLOCKER_TAPS),
        ("FILTER_TAPS", splitsum::view::shadow::FILTER_TAPS),
        (
            "MAX_SHADOW_MAPS",
            splitsum::view::frame::MAX_SHADOW_MAPS as u32,
        ),
        (
            "FLOOR_SHADOW_HEADER",
            splitsum::view::floor_shadow::FLOOR_SHADOW_HEADER as u32,
        ),
    ] {
        assert_eq!(wgsl_u32_constant(&module, name), rust, "{name}");
    }
    let fit = splitsum::math::ltc::EDGE_FIT;
    for (k, rust) in fit.iter().enumerate() {
        let name = format!("EDGE_FIT_C{k}");
        assert_eq!(wgsl_f32_constant(&module, &name), *rust, "{name}");
    }
    assert_eq!(
        wgsl_f32_constant(&module, "MIN_SIN_SQUARED"),
        splitsum::math::ltc::MIN_SIN_SQUARED
    );
}

/// The LTC fit's constants are the same on both sides.
#[test]
fn ltc_fit_constants_match_rust() {
    use splitsum::plan::ltc;
    let module = parse("ltc_fit", splitsum::gpu::shaders::LTC_FIT);
    for (name, rust) in [
        ("FIT_THREADS", splitsum::gpu::ltc_fit::FIT_THREADS),
        ("FIT_SAMPLES", ltc::FIT_SAMPLES),
        ("SIMPLEX_ITERATIONS", ltc::SIMPLEX_ITERATIONS),
    ] {
        assert_eq!(wgsl_u32_constant(&module, name), rust, "{name}");
    }
    for (name, rust) in [
        ("MIN_ALPHA", ltc::MIN_ALPHA),
        ("SIMPLEX_STEP", ltc::SIMPLEX_STEP),
        ("SIMPLEX_TOLERANCE", ltc::SIMPLEX_TOLERANCE),
        ("MIN_SCALE", ltc::MIN_SCALE),
        ("MIN_FIT_N_DOT_V", ltc::MIN_FIT_N_DOT_V),
        ("MIN_POSITIVE", f32::MIN_POSITIVE),
    ] {
        assert_eq!(wgsl_f32_constant(&module, name), rust, "{name}");
    }
    let (members, span) = struct_layout(&module, "LtcFitParams");
    let names: Vec<&str> = members.iter().map(|m| m.0.as_str()).collect();
    assert_eq!(names, ["size", "masking", "stage", "step"]);
    assert_eq!(
        span as usize,
        std::mem::size_of::<splitsum::gpu::ltc_fit::LtcFitParams>()
    );
}
