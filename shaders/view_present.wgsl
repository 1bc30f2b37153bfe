// The viewer's present pass (vertex and fragment stages): the mode's picture of a pixel
// (split-sum, the accumulated truth, or the heat map of their difference), exposed, tone
// mapped with Khronos PBR Neutral and sRGB-encoded exactly as the preview's pictures are,
// with the HUD over it. CPU mirror: src/view/cpu.rs (`present_pixel`); the constants
// (PBR_NEUTRAL_*, SRGB_*, LUMINANCE, HEAT_BACKGROUND) are written by src/view/gpu.rs from the Rust
// ones, so none is typed twice.

struct PresentParams {
    width: u32,
    height: u32,
    mode: u32,
    target_is_srgb: u32,
    exposure: f32,
    heat_lo: f32,
    heat_hi: f32,
    heat_entries: u32,
}

@group(0) @binding(0) var<uniform> present: PresentParams;
@group(0) @binding(1) var<storage, read> shaded: array<vec4<f32>>;
@group(0) @binding(2) var<storage, read> accum: array<vec4<f32>>;
@group(0) @binding(3) var<storage, read> heat_table: array<vec4<f32>>;
@group(0) @binding(4) var hud: texture_2d<f32>;

@vertex
fn vs_main(@builtin(vertex_index) i: u32) -> @builtin(position) vec4<f32> {
    // One triangle covering the viewport.
    let x = f32((i << 1u) & 2u);
    let y = f32(i & 2u);
    return vec4<f32>(2.0 * x - 1.0, 1.0 - 2.0 * y, 0.0, 1.0);
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

fn luminance(c: vec3<f32>) -> f32 {
    return dot(c, LUMINANCE);
}

// The heat-map colour of a relative difference: the table, linear between entries, on
// log10 from heat_lo to heat_hi.
fn heat_colour(relative: f32) -> vec3<f32> {
    let t = clamp((log(max(relative, 1e-30)) / log(10.0) - present.heat_lo) / (present.heat_hi - present.heat_lo), 0.0, 1.0);
    let x = t * f32(present.heat_entries - 1u);
    let i = min(u32(floor(x)), present.heat_entries - 2u);
    let f = x - f32(i);
    return mix(heat_table[i].rgb, heat_table[i + 1u].rgb, f);
}

@fragment
fn fs_main(@builtin(position) position: vec4<f32>) -> @location(0) vec4<f32> {
    let pixel = vec2<u32>(position.xy);
    let i = pixel.y * present.width + pixel.x;
    let s = shaded[i];
    let a = accum[i];
    var c: vec3<f32>;
    if (present.mode == 0u || a.w <= 0.0) {
        c = display(s.rgb);
    } else if (present.mode == 1u) {
        c = display(a.rgb / a.w);
    } else if (s.w < 0.5) {
        c = HEAT_BACKGROUND;
    } else {
        let t = luminance(a.rgb / a.w);
        c = heat_colour(abs(luminance(s.rgb) - t) / max(t, 1e-30));
    }
    let h = textureLoad(hud, pixel, 0);
    c = mix(c, h.rgb, h.a);
    if (present.target_is_srgb == 1u) {
        c = vec3<f32>(srgb_to_linear(c.r), srgb_to_linear(c.g), srgb_to_linear(c.b));
    }
    return vec4<f32>(c, 1.0);
}
