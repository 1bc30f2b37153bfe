// Cook-Torrance microfacet terms used by the split-sum integrals.
// Mirror of src/math/brdf.rs (same function names); conventions in docs/conventions.md:
// perceptual roughness r, alpha = r^2, Schlick-GGX k = r^2 / 2 for IBL (Karis 2013).

// GGX alpha from perceptual roughness: alpha = r^2 (Burley 2012, Karis 2013).
fn alpha_from_roughness(roughness: f32) -> f32 {
    return roughness * roughness;
}

// Schlick-GGX k for image-based lighting: k = alpha / 2 = r^2 / 2 (Karis 2013).
fn k_ibl(roughness: f32) -> f32 {
    return 0.5 * alpha_from_roughness(roughness);
}

// Schlick-GGX k for analytic lights: k = (r + 1)^2 / 8 (Karis 2013; the viewer's point lights).
fn k_direct(roughness: f32) -> f32 {
    return (roughness + 1.0) * (roughness + 1.0) / 8.0;
}

// GGX / Trowbridge-Reitz NDF (Walter et al. 2007, eq. 33):
// D(h) = alpha^2 / (pi ((n.h)^2 (alpha^2 - 1) + 1)^2).
fn d_ggx(n_dot_h: f32, alpha: f32) -> f32 {
    let a2 = alpha * alpha;
    let d = n_dot_h * n_dot_h * (a2 - 1.0) + 1.0;
    return a2 / (PI * d * d);
}

// GGX D times n.l in a prefiltered sum with n = v (n.l > 0): n.h = (1 + n.l) / |n + l| =
// sqrt((1 + n.l) / 2).
fn ggx_prefilter_weight(n_dot_l: f32, alpha: f32) -> f32 {
    return d_ggx(sqrt(0.5 * (1.0 + n_dot_l)), alpha) * n_dot_l;
}

// Charlie sheen D (Estevez & Kulla 2017) times n.l in a prefiltered sum with n = v, up to a
// constant factor: sin^2(theta_h) = (1 - n.l) / 2, so D ~ (1 - n.l)^(1 / (2 alpha)).
fn charlie_prefilter_weight(n_dot_l: f32, alpha: f32) -> f32 {
    return pow(max(1.0 - n_dot_l, 0.0), 0.5 / alpha) * n_dot_l;
}

// Schlick-GGX masking G1(x) = x / (x (1 - k) + k) (Schlick 1994, Karis 2013).
fn g1_schlick_ggx(n_dot_x: f32, k: f32) -> f32 {
    return n_dot_x / (n_dot_x * (1.0 - k) + k);
}

// G1(n.v) / (n.v) = 1 / (n.v (1 - k) + k): the 1/(n.v) of the BRDF divided out analytically.
fn g1_over_n_dot_v(n_dot_v: f32, k: f32) -> f32 {
    return 1.0 / (n_dot_v * (1.0 - k) + k);
}

// Lambda'(x) = sqrt((n.x)^2 (1 - a^2) + a^2) of the height-correlated Smith-GGX visibility
// (Heitz 2014, eq. 99).
fn smith_correlated_lambda(n_dot_x: f32, alpha2: f32) -> f32 {
    return sqrt(n_dot_x * n_dot_x * (1.0 - alpha2) + alpha2);
}

// 4 V (n.l) for V = 0.5 / (n.l Lambda'(v) + n.v Lambda'(l)): finite at grazing n.v.
fn smith_correlated_4v_n_dot_l(n_dot_v: f32, n_dot_l: f32, alpha2: f32, lambda_v: f32) -> f32 {
    return 2.0 * n_dot_l / (n_dot_l * lambda_v + n_dot_v * smith_correlated_lambda(n_dot_l, alpha2));
}

// 4 V (n.l) for the Ashikhmin / Neubelt visibility V = 1 / (4 (n.l + n.v - n.l n.v)).
fn ashikhmin_4v_n_dot_l(n_dot_v: f32, n_dot_l: f32) -> f32 {
    return n_dot_l / (n_dot_l + n_dot_v - n_dot_l * n_dot_v);
}

// The KHR_materials_sheen fit of the Charlie Lambda (Estevez & Kulla 2017).
fn lambda_sheen_numeric_helper(x: f32, alpha: f32) -> f32 {
    let t = (1.0 - alpha) * (1.0 - alpha);
    let a = mix(21.5473, 25.3245, t);
    let b = mix(3.82987, 3.32435, t);
    let c = mix(0.19823, 0.16801, t);
    let d = mix(-1.97760, -1.27393, t);
    let e = mix(-4.32054, -4.85967, t);
    return a / (1.0 + b * pow(x, c)) + d * x + e;
}

fn lambda_sheen(cos_theta: f32, alpha: f32) -> f32 {
    if (abs(cos_theta) < 0.5) {
        return exp(lambda_sheen_numeric_helper(cos_theta, alpha));
    }
    return exp(2.0 * lambda_sheen_numeric_helper(0.5, alpha)
        - lambda_sheen_numeric_helper(1.0 - cos_theta, alpha));
}

// 4 V (n.l) for V = clamp(1 / ((1 + Lambda(v) + Lambda(l)) 4 n.v n.l), 0, 1).
fn sheen_4v_n_dot_l(n_dot_v: f32, n_dot_l: f32, alpha: f32, lambda_v: f32) -> f32 {
    let unclamped = 1.0 / ((1.0 + lambda_v + lambda_sheen(n_dot_l, alpha)) * n_dot_v);
    return min(unclamped, 4.0 * n_dot_l);
}

// Fresnel-Schlick weight (1 - v.h)^5: F = F0 (1 - w) + w (Schlick 1994).
fn fresnel_schlick_weight(v_dot_h: f32) -> f32 {
    let m = clamp(1.0 - v_dot_h, 0.0, 1.0);
    let m2 = m * m;
    return m2 * m2 * m;
}

// Fresnel-Schlick for a given F0.
fn fresnel_schlick(f0: f32, v_dot_h: f32) -> f32 {
    let w = fresnel_schlick_weight(v_dot_h);
    return f0 * (1.0 - w) + w;
}

// The fit of the cosine-weighted mean of (1 - v.h)^5 over the light directions
// (math::brdf::DIFFUSE_FRESNEL_SCALE, DIFFUSE_FRESNEL_POWER).
const DIFFUSE_FRESNEL_SCALE: f32 = 0.028;
const DIFFUSE_FRESNEL_POWER: f32 = 2.55;

// Burley's diffuse over Lambert's, (1 + (f90 - 1)(1 - n.l)^5)(1 + (f90 - 1)(1 - n.v)^5),
// f90 = 1/2 + 2 alpha (l.h)^2 (Burley 2012; Filament's and bevy_pbr's Fd_Burley).
// Mirror of math::brdf::burley_weight.
fn burley_weight(n_dot_l: f32, n_dot_v: f32, l_dot_h: f32, alpha: f32) -> f32 {
    let f90 = 0.5 + 2.0 * alpha * l_dot_h * l_dot_h;
    return (1.0 + (f90 - 1.0) * fresnel_schlick_weight(n_dot_l)) * (1.0 + (f90 - 1.0) * fresnel_schlick_weight(n_dot_v));
}

// W(n.v) = (1/pi) integral of (1 - v.h)^5 (n.l) over the hemisphere, fitted as
// 0.028 (1 - n.v)^2.55: the split-sum diffuse weight is (1 - F0)(1 - W)(1 - metallic), the
// BRDF's kD(h) = (1 - F(v.h))(1 - metallic) under uniform light. Mirror of
// math::brdf::diffuse_fresnel_weight.
fn diffuse_fresnel_weight(n_dot_v: f32) -> f32 {
    return DIFFUSE_FRESNEL_SCALE * pow(clamp(1.0 - n_dot_v, 0.0, 1.0), DIFFUSE_FRESNEL_POWER);
}

// Exact Smith masking of GGX, G1(x) = 2 n.x / (n.x + Lambda'(x)) (Walter et al. 2007, eq. 34).
fn g1_smith_ggx(n_dot_x: f32, alpha2: f32) -> f32 {
    return 2.0 * n_dot_x / (n_dot_x + smith_correlated_lambda(n_dot_x, alpha2));
}
