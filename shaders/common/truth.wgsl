// The ground truth of one surface point: the full reflectance integral of the material's
// BRDF (kD(h) c/pi + D G F / (4 n.l n.v), its G and kD as the params' masking and diffuse
// say: the recipe's, or an engine's own) over the environment with the real view direction.
// Hot texels are summed exactly; the cold rest by quasi-Monte Carlo, GGX visible normals
// for the specular lobe (weight F G(l, v) / G1_Smith(n.v)) and cosine directions
// for the diffuse one (weight kD(h) c), from a table of disk points shifted per estimate
// (Cranley-Patterson). At r = 0 the specular lobe is the mirror lookup.
// CPU mirror: src/cpu/preview_truth.rs (same function names).
//
// The including kernel declares the environment as module globals:
//   truth: TruthParams (uniform), env, cold: texture_2d_array<f32>,
//   hot: array<vec4<f32>> (storage: (centroid direction, solid angle), (radiance, 0)),
//   points: array<vec4<f32>> (storage: (u1, cos 2 pi u2, sin 2 pi u2, 0)).

struct TruthParams {
    env_size: u32,
    hot_count: u32,
    point_count: u32,
    masking: u32,      // the BRDF's MASKING_* (common/material.wgsl)
    diffuse: u32,      // the BRDF's DIFFUSE_*
    compensated: u32,  // 1: the kernel scales the specular by specular_compensation
    lut_width: u32,    // the LUT that compensation reads (preview kernel only)
    lut_height: u32,
}

// The BRDF the truth integrates (plan::shading::LightBrdf, its masking and diffuse).
fn truth_brdf() -> LightBrdf {
    return LightBrdf(truth.masking, truth.diffuse);
}

// (radial shift, cos psi, sin psi) of the rotation of the point set seeded by `seed`.
fn pixel_shift(seed: u32) -> vec3<f32> {
    let h1 = pcg_hash(seed);
    let h2 = pcg_hash(h1);
    let h3 = pcg_hash(h2);
    let x = 2.0 * unit_float(h2) - 1.0;
    let y = 2.0 * unit_float(h3) - 1.0;
    let len = sqrt(x * x + y * y);
    if (len < 1e-3) {
        return vec3<f32>(unit_float(h1), 1.0, 0.0);
    }
    return vec3<f32>(unit_float(h1), x / len, y / len);
}

fn shifted_disk_point(p: vec4<f32>, shift: vec3<f32>) -> vec2<f32> {
    let u = p.x + shift.x;
    let r = sqrt(u - floor(u));
    let c = p.y * shift.y - p.z * shift.z;
    let s = p.y * shift.z + p.z * shift.y;
    return vec2<f32>(r * c, r * s);
}

// Sum of L Omega f (n.l) over the hot texels: (specular, diffuse / albedo).
fn hot_texels_shade(n: vec3<f32>, v: vec3<f32>, n_dot_v: f32, alpha: f32, f0: vec3<f32>, metallic: f32, brdf: LightBrdf) -> LightShade {
    var out: LightShade;
    out.spec = vec3<f32>(0.0);
    out.diff = vec3<f32>(0.0);
    for (var i = 0u; i < truth.hot_count; i++) {
        let t = hot[2u * i];
        let s = directional_light(n, v, n_dot_v, alpha, f0, metallic, t.xyz, hot[2u * i + 1u].rgb * t.w, brdf);
        out.spec += s.spec;
        out.diff += s.diff;
    }
    return out;
}

// The specular weight of a visible normal's direction besides F, G(l, v) / G1_Smith(v),
// for n.l > 0: the VNDF's pdf holds D and the exact Smith G1(v) (Heitz 2018).
// Schlick-GGX: G1(n.l) G1(n.v) / G1_Smith(n.v); height-correlated Smith:
// G2 / G1(v) = n.l (n.v + Lambda'(v)) / (n.l Lambda'(v) + n.v Lambda'(l)).
fn vndf_masking_weight(brdf: LightBrdf, n_dot_l: f32, n_dot_v: f32, alpha: f32) -> f32 {
    let a2 = alpha * alpha;
    if (brdf.masking == MASKING_SMITH_CORRELATED) {
        let lv = smith_correlated_lambda(n_dot_v, a2);
        return n_dot_l * (n_dot_v + lv) / (n_dot_l * lv + n_dot_v * smith_correlated_lambda(n_dot_l, a2));
    }
    let k = 0.5 * alpha;
    return g1_schlick_ggx(n_dot_l, k) * g1_schlick_ggx(n_dot_v, k) / g1_smith_ggx(n_dot_v, a2);
}

// One estimate of the light towards v of a point with normal n, its quadrature rotated by
// `shift` (pixel_shift), as (specular, diffuse times the albedo); n_dot_v is n.v clamped
// away from 0 by the caller.
fn truth_shade_parts(n: vec3<f32>, v: vec3<f32>, n_dot_v: f32, m: ShadeMaterial, shift: vec3<f32>) -> LightShade {
    let brdf = truth_brdf();
    let alpha = alpha_from_roughness(m.roughness);
    let tb = tangent_frame(n);
    let t0 = tb[0];
    let b0 = tb[1];
    let vt = vec3<f32>(dot(v, t0), dot(v, b0), n_dot_v);
    let count = f32(truth.point_count);

    let hot_part = hot_texels_shade(n, v, n_dot_v, alpha, m.f0, m.metallic, brdf);
    var spec = hot_part.spec;
    var diff = hot_part.diff;
    if (alpha > 0.0) {
        var sum = vec3<f32>(0.0);
        for (var i = 0u; i < truth.point_count; i++) {
            let h = sample_ggx_vndf(vt, alpha, shifted_disk_point(points[i], shift));
            let v_dot_h = dot(vt, h);
            let lt = 2.0 * v_dot_h * h - vt;
            if (lt.z > 0.0) {
                let l = lt.x * t0 + lt.y * b0 + lt.z * n;
                let radiance = sample_cube_lod(cold, truth.env_size, 1u, l, 0.0);
                sum += radiance * fresnel3(m.f0, max(v_dot_h, 0.0)) * vndf_masking_weight(brdf, lt.z, n_dot_v, alpha);
            }
        }
        spec += sum / count;
    } else {
        let refl = 2.0 * dot(n, v) * n - v;
        spec = sample_cube_lod(env, truth.env_size, 1u, refl, 0.0) * fresnel3(m.f0, n_dot_v);
    }
    if (m.metallic < 1.0) {
        var sum = vec3<f32>(0.0);
        for (var i = 0u; i < truth.point_count; i++) {
            let lt = cosine_hemisphere_from_disk(shifted_disk_point(points[i], shift));
            let l = lt.x * t0 + lt.y * b0 + lt.z * n;
            let radiance = sample_cube_lod(cold, truth.env_size, 1u, l, 0.0);
            let h = normalize(vt + lt);
            sum += radiance * diffuse_weight(brdf, m.f0, lt.z, n_dot_v, max(dot(vt, h), 0.0), alpha);
        }
        diff += sum * ((1.0 - m.metallic) / count);
    }
    var out: LightShade;
    out.spec = spec;
    out.diff = diff * m.albedo;
    return out;
}

// One estimate of the radiance towards v of a point with normal n (truth_shade_parts, the
// two parts summed).
fn truth_shade(n: vec3<f32>, v: vec3<f32>, n_dot_v: f32, m: ShadeMaterial, shift: vec3<f32>) -> vec3<f32> {
    let parts = truth_shade_parts(n, v, n_dot_v, m, shift);
    return parts.spec + parts.diff;
}
