// Exact convolutions over every texel of a small source mip (no noise):
//   mode 0, prefiltered specular:  sum L D(n.h) (n.l) W / sum D(n.h) (n.l) W,
//   mode 1, irradiance / pi:       (1/pi) sum max(0, n . M_c) per channel c,
//   mode 2, prefiltered sheen:     sum L D_Charlie(n.h) (n.l) W / sum D_Charlie(n.h) (n.l) W,
// with W the source texel's exact solid angle, l its radiance centroid direction and M_c
// its first radiance moments. CPU mirrors: prefilter_lobe_texel in
// src/cpu/prefilter_specular.rs (with ggx_prefilter_weight in prefilter_exact_texel, with
// charlie_prefilter_weight in prefilter_charlie_texel, src/cpu/prefilter_sheen.rs) and
// irradiance_texel in src/cpu/irradiance.rs.

struct ConvolveParams {
    out_size: u32,
    count: u32,       // source texels
    mode: u32,        // 0 specular, 1 irradiance, 2 sheen
    roughness: f32,   // modes 0 and 2
    hot_count: u32,   // mode 1: hot cells (src/environment/hot.rs), after the source texels
    pad0: u32,
    pad1: u32,
    pad2: u32,
}

// Modes 0 and 2: two vec4 per texel (dir_omega, radiance); mode 1: five (moments of R, G, B,
// centroid + sin^2 sigma, radiance * omega).
@group(0) @binding(0) var<uniform> params: ConvolveParams;
@group(0) @binding(1) var<storage, read> source: array<vec4<f32>>;
@group(0) @binding(2) var output: texture_storage_2d_array<rgba32float, write>;
// Mode 1: the hot cells, five vec4 each like the source texels (a separate binding keeps
// each under the 2 MiB that lavapipe reads of a storage binding; one dummy in mode 0).
@group(0) @binding(3) var<storage, read> hot: array<vec4<f32>>;

// Modes 0 and 2: the lobe's weight of a source texel at n.l > 0, before its solid angle.
fn lobe_weight(n_dot_l: f32, alpha: f32) -> f32 {
    if (params.mode == 2u) {
        return charlie_prefilter_weight(n_dot_l, alpha);
    }
    return ggx_prefilter_weight(n_dot_l, alpha);
}

fn prefilter_lobe_texel(n: vec3<f32>, roughness: f32) -> vec4<f32> {
    let alpha = alpha_from_roughness(roughness);
    var sum = vec3<f32>(0.0);
    var weight = 0.0;
    for (var k = 0u; k < params.count; k++) {
        let l = source[2u * k];
        let n_dot_l = dot(n, l.xyz);
        if (n_dot_l > 0.0) {
            let w = lobe_weight(n_dot_l, alpha) * l.w;
            sum += w * source[2u * k + 1u].rgb;
            weight += w * source[2u * k + 1u].a; // 0 for a hot cell (see Rust)
        }
    }
    return vec4<f32>(sum / weight, 1.0);
}

// Mean clamped cosine over a cap of half-angle sigma at cos theta from n (Snyder 1996;
// Lagarde & de Rousiers 2014).
// Below this sin^2 sigma the cap is a flat disk (SMALL_CAP_SIN2 in src/cpu/irradiance.rs,
// checked by tests/shaders.rs): n.l linear across it, mean of its positive part in closed form.
const SMALL_CAP_SIN2: f32 = 1e-3;

fn clipped_cap_cosine(cos_theta: f32, sin2_sigma: f32) -> f32 {
    if (sin2_sigma < 1e-12) {
        return max(cos_theta, 0.0);
    }
    if (sin2_sigma < SMALL_CAP_SIN2) {
        let sigma = sqrt(sin2_sigma);
        let g = sqrt(max(1.0 - cos_theta * cos_theta, 0.0));
        let reach = g * sigma;
        if (cos_theta >= reach) {
            return cos_theta;
        }
        if (cos_theta <= -reach) {
            return 0.0;
        }
        let t = cos_theta / reach;
        let r = sqrt(max(1.0 - t * t, 0.0));
        let asin_t = atan_precise(t / max(r, 1e-9));
        let a = (0.5 * PI + t * r + asin_t) / PI;
        let b = 2.0 * r * r * r / (3.0 * PI);
        return reach * (t * a + b);
    }
    let cap = 2.0 * PI * (1.0 - sqrt(max(1.0 - sin2_sigma, 0.0)));
    var e = 0.0;
    if (cos_theta * cos_theta > sin2_sigma) {
        e = PI * sin2_sigma * max(cos_theta, 0.0);
    } else {
        let sin_theta = sqrt(max(1.0 - cos_theta * cos_theta, 0.0));
        let x = sqrt(max(1.0 / sin2_sigma - 1.0, 0.0));
        let y = clamp(-x * cos_theta / max(sin_theta, 1e-9), -1.0, 1.0);
        let st_y = sin_theta * sqrt(max(1.0 - y * y, 0.0));
        e = (cos_theta * acos_precise(y) - x * st_y) * sin2_sigma + atan_precise(st_y / max(x, 1e-9));
    }
    return max(e, 0.0) / cap;
}

fn irradiance_texel(n: vec3<f32>) -> vec4<f32> {
    var e = vec3<f32>(0.0);
    // The source texels, then the hot cells, in one loop (one copy of the cap code).
    for (var k = 0u; k < params.count + params.hot_count; k++) {
        var t: array<vec4<f32>, 5>;
        if (k < params.count) {
            t = array<vec4<f32>, 5>(source[5u * k], source[5u * k + 1u], source[5u * k + 2u],
                                    source[5u * k + 3u], source[5u * k + 4u]);
        } else {
            let h = k - params.count;
            t = array<vec4<f32>, 5>(hot[5u * h], hot[5u * h + 1u], hot[5u * h + 2u],
                                    hot[5u * h + 3u], hot[5u * h + 4u]);
        }
        let d = t[3];
        let cos_theta = dot(n, d.xyz);
        if (cos_theta * cos_theta > d.w) {
            if (cos_theta > 0.0) {
                e += max(vec3<f32>(dot(n, t[0].xyz), dot(n, t[1].xyz), dot(n, t[2].xyz)),
                         vec3<f32>(0.0));
            }
        } else {
            e += clipped_cap_cosine(cos_theta, d.w) * t[4].rgb;
        }
    }
    return vec4<f32>(e / PI, 1.0);
}

@compute @workgroup_size(WORKGROUP_X, WORKGROUP_Y, WORKGROUP_Z)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    let n = params.out_size;
    if (id.x >= n || id.y >= n || id.z >= 6u) {
        return;
    }
    let dir = cube_texel_direction(id.z, i32(id.x), i32(id.y), n);
    var out: vec4<f32>;
    if (params.mode == 1u) {
        out = irradiance_texel(dir);
    } else {
        out = prefilter_lobe_texel(dir, params.roughness);
    }
    textureStore(output, vec2<i32>(id.xy), i32(id.z), out);
}
