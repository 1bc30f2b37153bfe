// The ground truth of one surface point: the full reflectance integral of the material's
// BRDF (kD(h) c/pi + D G F / (4 n.l n.v)) over the environment with the real view direction.
// Hot texels are summed exactly; the cold rest by quasi-Monte Carlo, GGX visible normals
// for the specular lobe (weight F G1(n.l) G1(n.v) / G1_Smith(n.v)) and cosine directions
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
    _pad: u32,
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
fn hot_texels_shade(n: vec3<f32>, v: vec3<f32>, n_dot_v: f32, alpha: f32, f0: vec3<f32>, metallic: f32) -> LightShade {
    var out: LightShade;
    out.spec = vec3<f32>(0.0);
    out.diff = vec3<f32>(0.0);
    for (var i = 0u; i < truth.hot_count; i++) {
        let t = hot[2u * i];
        let s = directional_light(n, v, n_dot_v, alpha, f0, metallic, t.xyz, hot[2u * i + 1u].rgb * t.w);
        out.spec += s.spec;
        out.diff += s.diff;
    }
    return out;
}

// One estimate of the radiance towards v of a point with normal n, its quadrature rotated
// by `shift` (pixel_shift); n_dot_v is n.v clamped away from 0 by the caller.
fn truth_shade(n: vec3<f32>, v: vec3<f32>, n_dot_v: f32, m: ShadeMaterial, shift: vec3<f32>) -> vec3<f32> {
    let alpha = alpha_from_roughness(m.roughness);
    let k = k_ibl(m.roughness);
    let tb = tangent_frame(n);
    let t0 = tb[0];
    let b0 = tb[1];
    let vt = vec3<f32>(dot(v, t0), dot(v, b0), n_dot_v);
    let count = f32(truth.point_count);

    let hot_part = hot_texels_shade(n, v, n_dot_v, alpha, m.f0, m.metallic);
    var spec = hot_part.spec;
    var diff = hot_part.diff;
    if (alpha > 0.0) {
        let view_term = g1_schlick_ggx(n_dot_v, k) / g1_smith_ggx(n_dot_v, alpha * alpha);
        var sum = vec3<f32>(0.0);
        for (var i = 0u; i < truth.point_count; i++) {
            let h = sample_ggx_vndf(vt, alpha, shifted_disk_point(points[i], shift));
            let v_dot_h = dot(vt, h);
            let lt = 2.0 * v_dot_h * h - vt;
            if (lt.z > 0.0) {
                let l = lt.x * t0 + lt.y * b0 + lt.z * n;
                let radiance = sample_cube_lod(cold, truth.env_size, 1u, l, 0.0);
                sum += radiance * fresnel3(m.f0, max(v_dot_h, 0.0)) * (g1_schlick_ggx(lt.z, k) * view_term);
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
            let h = normalize(vt + lt);
            let l = lt.x * t0 + lt.y * b0 + lt.z * n;
            let radiance = sample_cube_lod(cold, truth.env_size, 1u, l, 0.0);
            sum += radiance * (vec3<f32>(1.0) - fresnel3(m.f0, max(dot(vt, h), 0.0)));
        }
        diff += sum * ((1.0 - m.metallic) / count);
    }
    return spec + diff * m.albedo;
}
