// The viewer's present pass (vertex and fragment stages) for the deferred frames: the
// mode's picture of a pixel (split-sum, the accumulated truth, or the heat map of their
// difference) displayed as common/view_display.wgsl says, with the HUD over it. CPU
// mirror: src/view/cpu.rs (`present_pixel`); the constants (LUMINANCE, HEAT_BACKGROUND
// and view_display's) are written by src/view/gpu/pipelines.rs from the Rust ones.

@group(0) @binding(0) var<uniform> present: PresentParams;
@group(0) @binding(1) var<storage, read> shaded: array<vec4<f32>>;
@group(0) @binding(2) var<storage, read> accum: array<vec4<f32>>;
@group(0) @binding(3) var<storage, read> heat_table: array<vec4<f32>>;
@group(0) @binding(4) var hud: texture_2d<f32>;

@vertex
fn vs_main(@builtin(vertex_index) i: u32) -> @builtin(position) vec4<f32> {
    return fullscreen_triangle(i, 0.0);
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
    return with_hud(c, pixel);
}
