// Prefiltered specular, one mip, by filtered importance sampling (Colbert & Krivanek 2007):
// GGX-distributed half vectors (Hammersley), l = reflect(-n, h), weight n.l, each sample
// reading the environment's mip chain (with its hot texels blacked out) at
// lod = 0.5 log2(omega_s / omega_p) + bias; the hot texels are summed exactly. The samples
// depend only on the level: the Rust side builds them once in n's tangent frame
// (ggx_lobe_samples in src/cpu/prefilter_specular.rs) and every texel rotates them.
// CPU mirror: prefilter_texel in src/cpu/prefilter_specular.rs.

struct PrefilterParams {
    env_size: u32,
    env_levels: u32,
    out_size: u32,
    samples: u32,    // points drawn (N, the hot sum's multiplier)
    roughness: f32,
    lobe_count: u32, // samples above the horizon, in `lobe`
    hot_count: u32,  // hot texels summed exactly
    _pad: u32,
}

@group(0) @binding(0) var<uniform> params: PrefilterParams;
@group(0) @binding(1) var env: texture_2d_array<f32>;
@group(0) @binding(2) var output: texture_storage_2d_array<rgba32float, write>;
// Hot texels, two vec4 each: (centroid direction, solid angle), (radiance, unused).
@group(0) @binding(3) var<storage, read> hot: array<vec4<f32>>;
// Lobe samples in the tangent frame: (l.x, l.y, l.z = n.l, lod).
@group(0) @binding(4) var<storage, read> lobe: array<vec4<f32>>;

// Exact part: sum of L W (n.l) pdf(l) over the hot texels, pdf(l) = D(n.h) / 4.
fn hot_texels_sum(n: vec3<f32>, alpha: f32) -> vec3<f32> {
    var sum = vec3<f32>(0.0);
    for (var k = 0u; k < params.hot_count; k++) {
        let l = hot[2u * k];
        let n_dot_l = dot(n, l.xyz);
        if (n_dot_l > 0.0) {
            let n_dot_h = sqrt(0.5 * (1.0 + n_dot_l));
            sum += l.w * n_dot_l * d_ggx(n_dot_h, alpha) * 0.25 * hot[2u * k + 1u].rgb;
        }
    }
    return sum;
}

fn prefilter_texel(n: vec3<f32>) -> vec4<f32> {
    let tb = tangent_frame(n);
    var sum = vec3<f32>(0.0);
    var weight = 0.0;
    for (var i = 0u; i < params.lobe_count; i++) {
        let s = lobe[i];
        let l = tb[0] * s.x + tb[1] * s.y + n * s.z;
        sum += sample_cube_lod(env, params.env_size, params.env_levels, l, s.w) * s.z;
        weight += s.z;
    }
    let hot_sum = hot_texels_sum(n, alpha_from_roughness(params.roughness));
    return vec4<f32>((sum + f32(params.samples) * hot_sum) / weight, 1.0);
}

@compute @workgroup_size(WORKGROUP_X, WORKGROUP_Y, WORKGROUP_Z)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    let n = params.out_size;
    if (id.x >= n || id.y >= n || id.z >= 6u) {
        return;
    }
    let dir = cube_texel_direction(id.z, i32(id.x), i32(id.y), n);
    textureStore(output, vec2<i32>(id.xy), i32(id.z), prefilter_texel(dir));
}
