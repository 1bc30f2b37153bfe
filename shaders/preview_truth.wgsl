// The preview's ground truth: per sphere pixel the full reflectance integral of the preview
// BRDF (kD(h) c/pi + D G F / (4 n.l n.v)) over the environment with the real view
// direction. Hot texels are summed exactly; the cold rest by quasi-Monte Carlo, GGX visible
// normals for the specular lobe (weight F G1(n.l) G1(n.v) / G1_Smith(n.v)) and cosine
// directions for the diffuse one (weight kD(h) c), from a table of disk points shifted per
// pixel by a hash (Cranley-Patterson). At r = 0 the specular lobe is the mirror lookup.
// CPU mirror: src/cpu/preview_truth.rs (same function names).

struct TruthParams {
    env_size: u32,
    hot_count: u32,
    point_count: u32,
    _pad: u32,
}

@group(0) @binding(0) var<uniform> scene: SceneParams;
@group(0) @binding(1) var<uniform> params: TruthParams;
@group(0) @binding(2) var env: texture_2d_array<f32>;
@group(0) @binding(3) var cold: texture_2d_array<f32>;
// Hot texels, two vec4 each: (centroid direction, solid angle), (radiance, unused).
@group(0) @binding(4) var<storage, read> hot: array<vec4<f32>>;
@group(0) @binding(5) var<storage, read> columns: array<vec4<f32>>;
@group(0) @binding(6) var<storage, read> materials: array<vec4<f32>>;
// Quadrature points: (u1, cos 2 pi u2, sin 2 pi u2, 0).
@group(0) @binding(7) var<storage, read> points: array<vec4<f32>>;
@group(0) @binding(8) var output: texture_storage_2d<rgba32float, write>;

// (radial shift, cos psi, sin psi) of a pixel's rotation of the point set.
fn pixel_shift(pixel: u32) -> vec3<f32> {
    let h1 = pcg_hash(pixel);
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

fn fresnel3(f0: vec3<f32>, v_dot_h: f32) -> vec3<f32> {
    let w = fresnel_schlick_weight(v_dot_h);
    return f0 * (1.0 - w) + vec3<f32>(w);
}

struct HotShade {
    spec: vec3<f32>,
    diff: vec3<f32>,
}

// Sum of L Omega f (n.l) over the hot texels: (specular, diffuse / albedo).
fn hot_texels_shade(n: vec3<f32>, v: vec3<f32>, n_dot_v: f32, alpha: f32, f0: vec3<f32>, metallic: f32) -> HotShade {
    let k = 0.5 * alpha;
    var out: HotShade;
    out.spec = vec3<f32>(0.0);
    out.diff = vec3<f32>(0.0);
    for (var i = 0u; i < params.hot_count; i++) {
        let t = hot[2u * i];
        let l = t.xyz;
        let n_dot_l = dot(n, l);
        if (n_dot_l <= 0.0) {
            continue;
        }
        let radiance = hot[2u * i + 1u].rgb * t.w;
        let h = normalize(l + v);
        let f = fresnel3(f0, max(dot(v, h), 0.0));
        if (alpha > 0.0) {
            // f (n.l) = D F G1(n.l) (G1(n.v)/(n.v)) / 4
            let w = d_ggx(max(dot(n, h), 0.0), alpha) * g1_schlick_ggx(n_dot_l, k) * g1_over_n_dot_v(n_dot_v, k) * 0.25;
            out.spec += radiance * f * w;
        }
        if (metallic < 1.0) {
            out.diff += radiance * (vec3<f32>(1.0) - f) * ((1.0 - metallic) * n_dot_l / PI);
        }
    }
    return out;
}

fn truth_shade(n: vec3<f32>, v: vec3<f32>, material: u32, column: u32, pixel: u32) -> vec3<f32> {
    let r = columns[column].x;
    let fm = materials[2u * material];
    let albedo = materials[2u * material + 1u].rgb;
    let f0 = fm.rgb;
    let metallic = fm.w;
    let alpha = alpha_from_roughness(r);
    let k = k_ibl(r);
    let n_dot_v = max(dot(n, v), scene.min_n_dot_v);
    let tb = tangent_frame(n);
    let t0 = tb[0];
    let b0 = tb[1];
    let shift = pixel_shift(pixel);
    let vt = vec3<f32>(dot(v, t0), dot(v, b0), n_dot_v);
    let count = f32(params.point_count);

    let hot_part = hot_texels_shade(n, v, n_dot_v, alpha, f0, metallic);
    var spec = hot_part.spec;
    var diff = hot_part.diff;
    if (alpha > 0.0) {
        let view_term = g1_schlick_ggx(n_dot_v, k) / g1_smith_ggx(n_dot_v, alpha * alpha);
        var sum = vec3<f32>(0.0);
        for (var i = 0u; i < params.point_count; i++) {
            let h = sample_ggx_vndf(vt, alpha, shifted_disk_point(points[i], shift));
            let v_dot_h = dot(vt, h);
            let lt = 2.0 * v_dot_h * h - vt;
            if (lt.z > 0.0) {
                let l = lt.x * t0 + lt.y * b0 + lt.z * n;
                let radiance = sample_cube_lod(cold, params.env_size, 1u, l, 0.0);
                sum += radiance * fresnel3(f0, max(v_dot_h, 0.0)) * (g1_schlick_ggx(lt.z, k) * view_term);
            }
        }
        spec += sum / count;
    } else {
        let refl = 2.0 * dot(n, v) * n - v;
        spec = sample_cube_lod(env, params.env_size, 1u, refl, 0.0) * fresnel3(f0, n_dot_v);
    }
    if (metallic < 1.0) {
        var sum = vec3<f32>(0.0);
        for (var i = 0u; i < params.point_count; i++) {
            let lt = cosine_hemisphere_from_disk(shifted_disk_point(points[i], shift));
            let h = normalize(vt + lt);
            let l = lt.x * t0 + lt.y * b0 + lt.z * n;
            let radiance = sample_cube_lod(cold, params.env_size, 1u, l, 0.0);
            sum += radiance * (vec3<f32>(1.0) - fresnel3(f0, max(dot(vt, h), 0.0)));
        }
        diff += sum * ((1.0 - metallic) / count);
    }
    return spec + diff * albedo;
}

@compute @workgroup_size(WORKGROUP_X, WORKGROUP_Y, WORKGROUP_Z)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    if (id.x >= scene.width || id.y >= scene.height) {
        return;
    }
    let g = pixel_geometry(scene, id.x, id.y);
    var c: vec3<f32>;
    if (g.sphere) {
        c = truth_shade(g.dir, g.v, g.material, g.column, id.y * scene.width + id.x);
    } else {
        c = sample_cube_lod(env, params.env_size, 1u, g.dir, 0.0);
    }
    textureStore(output, vec2<i32>(id.xy), vec4<f32>(c, 1.0));
}
