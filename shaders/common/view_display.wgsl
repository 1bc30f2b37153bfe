// What the viewer's display passes share (the present pass, view_present.wgsl, and the
// forward pass, view_forward.wgsl): exposure, Khronos PBR Neutral tone mapping and the
// sRGB encoding, exactly as the preview's pictures are made, then the HUD over the
// picture. CPU mirror: src/view/cpu.rs (`display`, `present`). The constants
// (PBR_NEUTRAL_*, SRGB_*) are written before the shader by src/view/gpu/pipelines.rs
// from the Rust ones, so none is typed twice. The including shader declares `present`
// (PresentParams, uniform) and `hud` (texture_2d<f32>: sRGB, straight alpha).

struct PresentParams {
    width: u32,
    height: u32,
    mode: u32,
    reserved: u32,
    exposure: f32,
    heat_lo: f32,
    heat_hi: f32,
    heat_entries: u32,
}

// One triangle covering the viewport at depth z, for vertex i of 0, 1, 2.
fn fullscreen_triangle(i: u32, z: f32) -> vec4<f32> {
    let x = f32((i << 1u) & 2u);
    let y = f32(i & 2u);
    return vec4<f32>(2.0 * x - 1.0, 1.0 - 2.0 * y, z, 1.0);
}

// Khronos PBR Neutral (the specification's reference GLSL, term for term).
fn pbr_neutral(c_in: vec3<f32>) -> vec3<f32> {
    let x = min(c_in.r, min(c_in.g, c_in.b));
    var offset = 0.04;
    if (x < 0.08) {
        offset = x - 6.25 * x * x;
    }
    var c = c_in - vec3<f32>(offset);
    let peak = max(c.r, max(c.g, c.b));
    if (peak < PBR_NEUTRAL_START_COMPRESSION) {
        return c;
    }
    let d = 1.0 - PBR_NEUTRAL_START_COMPRESSION;
    let new_peak = 1.0 - d * d / (peak + d - PBR_NEUTRAL_START_COMPRESSION);
    c = c * (new_peak / peak);
    let g = 1.0 - 1.0 / (PBR_NEUTRAL_DESATURATION * (peak - new_peak) + 1.0);
    return c + (vec3<f32>(new_peak) - c) * g;
}

// The sRGB transfer function (IEC 61966-2-1) of a linear value, clamped to [0, 1].
fn linear_to_srgb(v_in: f32) -> f32 {
    let v = clamp(v_in, 0.0, 1.0);
    if (v <= SRGB_LINEAR_MAX) {
        return SRGB_SLOPE * v;
    }
    return (1.0 + SRGB_OFFSET) * pow(v, 1.0 / SRGB_GAMMA) - SRGB_OFFSET;
}

fn srgb_to_linear(c: f32) -> f32 {
    if (c <= SRGB_ENCODED_LINEAR_MAX) {
        return c / SRGB_SLOPE;
    }
    return pow((c + SRGB_OFFSET) / (1.0 + SRGB_OFFSET), SRGB_GAMMA);
}

// A linear radiance, exposed and tone-mapped, sRGB-encoded.
fn display(c: vec3<f32>) -> vec3<f32> {
    let t = pbr_neutral(max(c, vec3<f32>(0.0)) * present.exposure);
    return vec3<f32>(linear_to_srgb(t.r), linear_to_srgb(t.g), linear_to_srgb(t.b));
}


// 1 when the target stores sRGB itself, a constant of each pipeline (one a target format,
// src/view/gpu/pipelines.rs): read from the uniform block, lavapipe ran the decoding
// below for every target, as it runs both sides of an `if` (docs/accuracy.md, "The
// viewer").
override TARGET_IS_SRGB: u32 = 0u;

// The sRGB-encoded colour c of `pixel` with the HUD over it, as the target stores it (an
// sRGB target encodes again on store, so its value is decoded first).
fn with_hud(c_in: vec3<f32>, pixel: vec2<u32>) -> vec4<f32> {
    let h = textureLoad(hud, pixel, 0);
    var c = mix(c_in, h.rgb, h.a);
    if (TARGET_IS_SRGB == 1u) {
        c = vec3<f32>(srgb_to_linear(c.r), srgb_to_linear(c.g), srgb_to_linear(c.b));
    }
    return vec4<f32>(c, 1.0);
}
