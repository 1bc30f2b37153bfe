// Split-sum BRDF LUT (Karis 2013): R = scale A, G = bias B, for n.v = (i + 0.5) / W and
// roughness = (j + 0.5) / H. Deterministic panel Gauss-Legendre quadrature in the
// GGX-sampled domain; the derivation is in src/lut.rs and the CPU mirror, function for
// function, in src/cpu/brdf_lut.rs.

struct LutParams {
    size: vec2<u32>,
    full_rule: vec2<u32>,     // (offset, count) into `rules`
    partial_rule: vec2<u32>,
    phi_rule: vec2<u32>,
    panel_growth: f32,
    max_panels: u32,
    visibility: u32,          // 0 Schlick-GGX, 1 correlated Smith, 2 Ashikhmin, 3 sheen
    channel_layout: u32,      // 0 (A, B), 1 multiscatter (B, A + B), 2 albedo (A + B, 0)
    distribution: u32,        // 0 GGX, 1 Charlie
}

@group(0) @binding(0) var<uniform> params: LutParams;
@group(0) @binding(1) var<storage, read> rules: array<vec2<f32>>;   // (x, w) on [0, 1]
@group(0) @binding(2) var output: texture_storage_2d<rgba32float, write>;

// g_vis: G1(n.v)/(n.v) for Schlick-GGX, Lambda'(v) for the correlated visibility, the
// sheen Lambda(v) for V_Sheen.
struct LutTexel {
    cos_v: f32,
    sin_v: f32,
    alpha2: f32,
    k: f32,
    g_vis: f32,
    visibility: u32,
    alpha: f32,
    distribution: u32,
}

// q at polar angle theta of the half vector, in the texel's distribution.
fn lut_q_at_theta(tx: LutTexel, theta: f32) -> f32 {
    if (tx.distribution == 1u) {
        let c = cos(theta);
        return charlie_q_from_theta(c * c, tx.alpha);
    }
    return ggx_q_at_theta(theta, tx.alpha2);
}

// (cos^2, sin^2) of the half vector at q, in the texel's distribution.
fn lut_theta_from_q(tx: LutTexel, q: f32) -> vec2<f32> {
    if (tx.distribution == 1u) {
        return charlie_theta_from_q(q, tx.alpha);
    }
    return ggx_theta_from_q(q, tx.alpha2);
}

// 4 V (n.l): f (n.l) / pdf(l) = 4 V (n.l) F (v.h)/(n.h) for pdf(l) = D (n.h) / (4 v.h).
fn lut_visibility(tx: LutTexel, n_dot_l: f32) -> f32 {
    if (tx.visibility == 1u) {
        return smith_correlated_4v_n_dot_l(tx.cos_v, n_dot_l, tx.alpha2, tx.g_vis);
    }
    if (tx.visibility == 2u) {
        return ashikhmin_4v_n_dot_l(tx.cos_v, n_dot_l);
    }
    if (tx.visibility == 3u) {
        return sheen_4v_n_dot_l(tx.cos_v, n_dot_l, tx.alpha, tx.g_vis);
    }
    return g1_schlick_ggx(n_dot_l, tx.k) * tx.g_vis;
}

// The stored pair for the integrals (A, B).
fn arrange(channel_layout: u32, ab: vec2<f32>) -> vec2<f32> {
    if (channel_layout == 1u) {
        return vec2<f32>(ab.y, ab.x + ab.y);
    }
    if (channel_layout == 2u) {
        return vec2<f32>(ab.x + ab.y, 0.0);
    }
    return ab;
}

// n.v and roughness at the centre of texel (i, j).
fn lut_texel_coords(id: vec2<u32>, size: vec2<u32>) -> vec2<f32> {
    return (vec2<f32>(id) + 0.5) / vec2<f32>(size);
}

// Panel variable x and dx/dt for abscissa t; singular ends get x ~ t^2 there.
fn panel_map(t: f32, lower_singular: bool, upper_singular: bool) -> vec2<f32> {
    if (lower_singular && upper_singular) {
        return vec2<f32>(t * t * (3.0 - 2.0 * t), 6.0 * t * (1.0 - t));
    } else if (lower_singular) {
        return vec2<f32>(t * t, 2.0 * t);
    } else if (upper_singular) {
        let s = 1.0 - t;
        return vec2<f32>(1.0 - s * s, 2.0 * s);
    }
    return vec2<f32>(t, 1.0);
}

// End of the partial panel starting at theta_h = t0: geometric growth away from both
// breakpoints, which are mirror images about pi/4.
fn next_panel_end(t0: f32, growth: f32) -> f32 {
    if (t0 < 0.5 * FRAC_PI_2) {
        return min(t0 * growth, 0.5 * FRAC_PI_2);
    }
    return FRAC_PI_2 - (FRAC_PI_2 - t0) / growth;
}

fn ggx_q_at_theta(theta: f32, alpha2: f32) -> f32 {
    let c = cos(theta);
    let s = sin(theta);
    return ggx_q_from_theta(c * c, s * s, alpha2);
}

// One theta_h panel [q_a, q_b] (q falls as theta_h grows) times phi; returns (A, B).
fn integrate_panel(tx: LutTexel, q_a: f32, q_b: f32, full: bool, lower_singular: bool,
                   upper_singular: bool, theta_rule: vec2<u32>) -> vec2<f32> {
    var sum = vec2<f32>(0.0);
    let width = q_a - q_b;
    for (var i = 0u; i < theta_rule.y; i++) {
        let node = rules[theta_rule.x + i];
        let xm = panel_map(node.x, lower_singular, upper_singular);
        let q = q_a - width * xm.x;
        let weight_q = width * node.y * xm.y;
        let cs2 = lut_theta_from_q(tx, q);
        let cos_h = sqrt(cs2.x);
        let sin_h = sqrt(cs2.y);
        var phi_max = PI;
        if (!full) {
            let c0 = tx.cos_v * (1.0 - 2.0 * cs2.x) / (2.0 * tx.sin_v * sin_h * cos_h);
            phi_max = acos_precise(c0);
        }
        let weight_panel = weight_q * phi_max / PI;
        for (var j = 0u; j < params.phi_rule.y; j++) {
            let pn = rules[params.phi_rule.x + j];
            let phi = phi_max * pn.x;
            let v_dot_h = tx.sin_v * sin_h * cos(phi) + tx.cos_v * cos_h;
            let n_dot_l = 2.0 * v_dot_h * cos_h - tx.cos_v;
            if (n_dot_l > 0.0) {
                // f (n.l) / pdf(l) without F = 4 V (n.l) * (v.h)/(n.h)
                let g = lut_visibility(tx, n_dot_l) * v_dot_h / cos_h;
                let fc = fresnel_schlick_weight(v_dot_h);
                let wgt = weight_panel * pn.y * g;
                sum += wgt * vec2<f32>(1.0 - fc, fc);
            }
        }
    }
    return sum;
}

fn brdf_lut_texel(n_dot_v: f32, roughness: f32) -> vec2<f32> {
    let alpha = alpha_from_roughness(roughness);
    let alpha2 = alpha * alpha;
    let k = k_ibl(roughness);
    var g_vis = g1_over_n_dot_v(n_dot_v, k);
    if (params.visibility == 1u) {
        g_vis = smith_correlated_lambda(n_dot_v, alpha2);
    } else if (params.visibility == 2u) {
        g_vis = 0.0;
    } else if (params.visibility == 3u) {
        g_vis = lambda_sheen(n_dot_v, alpha);
    }
    let tx = LutTexel(n_dot_v, sqrt(max(1.0 - n_dot_v * n_dot_v, 0.0)), alpha2, k, g_vis,
                      params.visibility, alpha, params.distribution);
    let theta_v = acos_precise(n_dot_v);
    // Horizon breakpoints in theta_h.
    let theta_full = 0.5 * (FRAC_PI_2 - theta_v);
    let theta_end = 0.5 * (FRAC_PI_2 + theta_v);

    let q_full = lut_q_at_theta(tx, theta_full);
    let q_mid = lut_q_at_theta(tx, theta_full / params.panel_growth);
    var ab = integrate_panel(tx, 1.0, q_mid, true, false, false, params.full_rule);
    ab += integrate_panel(tx, q_mid, q_full, true, false, false, params.full_rule);
    var t0 = theta_full;
    var q0 = q_full;
    for (var panel = 0u; panel < params.max_panels; panel++) {
        if (t0 >= theta_end) {
            break;
        }
        let next = next_panel_end(t0, params.panel_growth);
        let last = panel + 1u == params.max_panels || next >= theta_end;
        var t1 = next;
        if (last) {
            t1 = theta_end;
        }
        let q1 = lut_q_at_theta(tx, t1);
        ab += integrate_panel(tx, q0, q1, false, panel == 0u, last, params.partial_rule);
        t0 = t1;
        q0 = q1;
    }
    return arrange(params.channel_layout, ab);
}

@compute @workgroup_size(WORKGROUP_X, WORKGROUP_Y, WORKGROUP_Z)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    if (id.x >= params.size.x || id.y >= params.size.y) {
        return;
    }
    let c = lut_texel_coords(id.xy, params.size);
    let ab = brdf_lut_texel(c.x, c.y);
    textureStore(output, vec2<i32>(id.xy), vec4<f32>(ab, 0.0, 1.0));
}
