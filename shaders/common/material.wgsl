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

// What a light of irradiance e (L times its solid angle) from unit direction l sends
// towards v off a point with normal n, e f(l, v) (n.l) with the truth's BRDF: GGX D,
// Schlick-GGX G1 with k = alpha/2 for l and v, Fresnel-Schlick at v.h, plus Lambert
// weighted by (1 - F)(1 - metallic); at alpha 0 no specular (a mirror shows a direction's
// light as a point: the mirror lookup's). The truth's hot texels and the lights taken out
// of the environment are shaded by it. Mirror of plan::material::directional_light.
fn directional_light(n: vec3<f32>, v: vec3<f32>, n_dot_v: f32, alpha: f32, f0: vec3<f32>, metallic: f32, l: vec3<f32>, e: vec3<f32>) -> LightShade {
    var out: LightShade;
    out.spec = vec3<f32>(0.0);
    out.diff = vec3<f32>(0.0);
    let n_dot_l = dot(n, l);
    if (n_dot_l <= 0.0) {
        return out;
    }
    let k = 0.5 * alpha;
    let h = normalize(l + v);
    let f = fresnel3(f0, max(dot(v, h), 0.0));
    if (alpha > 0.0) {
        // f (n.l) = D F G1(n.l) (G1(n.v)/(n.v)) / 4
        let w = d_ggx(max(dot(n, h), 0.0), alpha) * g1_schlick_ggx(n_dot_l, k) * g1_over_n_dot_v(n_dot_v, k) * 0.25;
        out.spec = e * f * w;
    }
    if (metallic < 1.0) {
        out.diff = e * (vec3<f32>(1.0) - f) * ((1.0 - metallic) * n_dot_l / PI);
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
