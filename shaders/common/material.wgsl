// A surface's material as the shading functions take it: Cook-Torrance (GGX D, Smith /
// Schlick-GGX G, Fresnel-Schlick) plus Lambert diffuse weighted by kD = (1 - F)(1 - metallic)
// (docs/conventions.md, "Roughness, BRDF"). Mirror of `plan::scene::ShadeMaterial`.
struct ShadeMaterial {
    f0: vec3<f32>,      // linear-RGB reflectance at normal incidence
    metallic: f32,      // 1 for a metal, 0 for a dielectric
    albedo: vec3<f32>,  // linear-RGB diffuse albedo c (Lambert c/pi)
    roughness: f32,     // perceptual roughness r (alpha = r^2)
    lod: f32,           // the specular chain's lod for r (the split-sum lookup)
    bend: f32,          // how far the lookup leans from R toward n for r (0: R, 1: n)
    stretch: f32,       // how strongly the lookup reads two taps toward grazing (0: one)
}

// Fresnel-Schlick per channel: F0 + (1 - F0)(1 - v.h)^5.
fn fresnel3(f0: vec3<f32>, v_dot_h: f32) -> vec3<f32> {
    let w = fresnel_schlick_weight(v_dot_h);
    return f0 * (1.0 - w) + vec3<f32>(w);
}

// A light's shading split into its specular part and its diffuse part per unit albedo.
struct LightShade {
    spec: vec3<f32>,
    diff: vec3<f32>,
}

// A light's BRDF terms (plan::shading::LightBrdf; its compensation is the caller's): the
// specular masking MASKING_* and the diffuse weighting DIFFUSE_*.
struct LightBrdf {
    masking: u32,
    diffuse: u32,
}

// plan::shading::Masking: Schlick-GGX G1(l) G1(v) with k = alpha/2, or the height-correlated
// Smith G2.
const MASKING_SCHLICK_GGX: u32 = 0u;
const MASKING_SMITH_CORRELATED: u32 = 1u;
// plan::shading::DiffuseLobe: Lambert weighted by (1 - F(v.h))(1 - metallic), by
// (1 - metallic) alone, Burley's times (1 - metallic), or Lambert by (1 - F0)(1 - metallic).
const DIFFUSE_FRESNEL_WEIGHTED: u32 = 0u;
const DIFFUSE_LAMBERT: u32 = 1u;
const DIFFUSE_BURLEY: u32 = 2u;
const DIFFUSE_DIELECTRIC_LAMBERT: u32 = 3u;

// What a diffuse lobe of `brdf` weights Lambert by besides (1 - metallic), for light from
// l_t and the view v_t (any frame) with n.l, n.v given: 1 - F(v.h), 1, Burley's, or 1 - F0.
fn diffuse_weight(brdf: LightBrdf, f0: vec3<f32>, n_dot_l: f32, n_dot_v: f32, v_dot_h: f32, alpha: f32) -> vec3<f32> {
    if (brdf.diffuse == DIFFUSE_FRESNEL_WEIGHTED) {
        return vec3<f32>(1.0) - fresnel3(f0, v_dot_h);
    }
    if (brdf.diffuse == DIFFUSE_BURLEY) {
        return vec3<f32>(burley_weight(n_dot_l, n_dot_v, v_dot_h, alpha));
    }
    if (brdf.diffuse == DIFFUSE_DIELECTRIC_LAMBERT) {
        return vec3<f32>(1.0) - f0;
    }
    return vec3<f32>(1.0);
}

// The recipe's BRDF (LightBrdf::GENERIC): the viewer's and the generic preview's.
fn generic_light_brdf() -> LightBrdf {
    return LightBrdf(MASKING_SCHLICK_GGX, DIFFUSE_FRESNEL_WEIGHTED);
}

// 4 (n.l) times the specular masking over 4 (n.l)(n.v) of `brdf`, for n.l > 0: the
// Schlick-GGX G1(n.l) G1(n.v)/(n.v), or the correlated 4 V (n.l).
fn light_masking(brdf: LightBrdf, n_dot_l: f32, n_dot_v: f32, alpha: f32) -> f32 {
    if (brdf.masking == MASKING_SMITH_CORRELATED) {
        let a2 = alpha * alpha;
        return smith_correlated_4v_n_dot_l(n_dot_v, n_dot_l, a2, smith_correlated_lambda(n_dot_v, a2));
    }
    let k = 0.5 * alpha;
    return g1_schlick_ggx(n_dot_l, k) * g1_over_n_dot_v(n_dot_v, k);
}

// What a light of irradiance e (L times its solid angle) from unit direction l sends
// towards v off a point with normal n, e f(l, v) (n.l) with `brdf`: GGX D, its masking,
// Fresnel-Schlick at v.h, plus Lambert weighted as its diffuse says; at alpha 0 no
// specular (a mirror shows a direction's light as a point: the mirror lookup's). The
// truth's hot texels and the lights taken out of the environment are shaded by it.
// Mirror of plan::material::directional_light.
fn directional_light(n: vec3<f32>, v: vec3<f32>, n_dot_v: f32, alpha: f32, f0: vec3<f32>, metallic: f32, l: vec3<f32>, e: vec3<f32>, brdf: LightBrdf) -> LightShade {
    var out: LightShade;
    out.spec = vec3<f32>(0.0);
    out.diff = vec3<f32>(0.0);
    let n_dot_l = dot(n, l);
    if (n_dot_l <= 0.0) {
        return out;
    }
    let h = normalize(l + v);
    let f = fresnel3(f0, max(dot(v, h), 0.0));
    if (alpha > 0.0) {
        // f (n.l) = D F (4 (n.l) masking) / 4
        let w = d_ggx(max(dot(n, h), 0.0), alpha) * light_masking(brdf, n_dot_l, n_dot_v, alpha) * 0.25;
        out.spec = e * f * w;
    }
    if (metallic < 1.0) {
        let weight = diffuse_weight(brdf, f0, n_dot_l, n_dot_v, max(dot(v, h), 0.0), alpha);
        out.diff = e * weight * ((1.0 - metallic) * n_dot_l / PI);
    }
    return out;
}

// The radiance towards v that a point light (position, intensity) sends off the point p
// with normal n: Cook-Torrance with GGX D (alpha = max(r^2, min_alpha)), Schlick-GGX G1
// with k = (r + 1)^2 / 8 for l and v, Fresnel-Schlick at v.h, plus Lambert c/pi weighted
// by (1 - F)(1 - metallic), times n.l and colour / d^2. Mirror of plan::material::point_light.
fn point_light(p: vec3<f32>, n: vec3<f32>, v: vec3<f32>, n_dot_v: f32, m: ShadeMaterial, light_position: vec3<f32>, light_colour: vec3<f32>, min_alpha: f32) -> vec3<f32> {
    let to_light = light_position - p;
    let d2 = dot(to_light, to_light);
    let l = to_light / sqrt(d2);
    let n_dot_l = dot(n, l);
    if (n_dot_l <= 0.0 || d2 <= 0.0) {
        return vec3<f32>(0.0);
    }
    let h = normalize(l + v);
    let f = fresnel3(m.f0, max(dot(v, h), 0.0));
    let k = k_direct(m.roughness);
    let alpha = max(alpha_from_roughness(m.roughness), min_alpha);
    let d = d_ggx(max(dot(n, h), 0.0), alpha);
    let g = g1_schlick_ggx(n_dot_l, k) * g1_schlick_ggx(n_dot_v, k);
    let specular = f * (d * g / (4.0 * n_dot_l * n_dot_v));
    let diffuse = (vec3<f32>(1.0) - f) * (1.0 - m.metallic) * m.albedo / PI;
    return (specular + diffuse) * light_colour * (n_dot_l / d2);
}
