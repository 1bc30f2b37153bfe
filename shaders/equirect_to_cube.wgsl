// Equirect -> cube, level 0: each texel is the solid-angle-weighted footprint mean of the
// environment, from S x S sub-texel samples that each read the equirect pyramid
// trilinearly at the level matching the sample's solid angle. CPU mirror, function for
// function: src/cpu/equirect_to_cube.rs.

struct EquirectToCubeParams {
    face_size: u32,
    samples_per_axis: u32,
    base_level: u32,       // pyramid level stored in mip 0 of `source`
    level_count: u32,      // pyramid levels in all (the last one is 1 texel high)
    source_size: vec2<u32>, // size of pyramid level 0
    rotation: vec2<f32>,   // cos, sin of the rotation about +Y
}

@group(0) @binding(0) var<uniform> params: EquirectToCubeParams;
@group(0) @binding(1) var source: texture_2d<f32>;
@group(0) @binding(2) var output: texture_storage_2d_array<rgba32float, write>;

// Fractional pyramid level whose (latitude-prefiltered) texels subtend omega_sample.
fn equirect_lod(omega_sample: f32, height: u32) -> f32 {
    let texel = PI / f32(height);
    return 0.5 * log2(omega_sample / (texel * texel));
}

// Bilinear lookup of pyramid level `level` (absolute) at uv: columns wrap, rows clamp.
fn sample_equirect_bilinear(level: u32, uv: vec2<f32>) -> vec3<f32> {
    let mip = level - params.base_level;
    // Level sizes halve with floor, as the pyramid's (computed here rather than queried:
    // lavapipe answers textureDimensions wrongly when the level differs across lanes).
    let dims = vec2<i32>(max(params.source_size >> vec2<u32>(level), vec2<u32>(1u)));
    let x = uv.x * f32(dims.x) - 0.5;
    let y = uv.y * f32(dims.y) - 0.5;
    let x0 = floor(x);
    let y0 = floor(y);
    let fx = x - x0;
    let fy = y - y0;
    let xa = ((i32(x0) % dims.x) + dims.x) % dims.x;
    let xb = (xa + 1) % dims.x;
    let ya = clamp(i32(y0), 0, dims.y - 1);
    let yb = clamp(i32(y0) + 1, 0, dims.y - 1);
    let t00 = textureLoad(source, vec2<i32>(xa, ya), mip).rgb;
    let t10 = textureLoad(source, vec2<i32>(xb, ya), mip).rgb;
    let t01 = textureLoad(source, vec2<i32>(xa, yb), mip).rgb;
    let t11 = textureLoad(source, vec2<i32>(xb, yb), mip).rgb;
    return t00 * ((1.0 - fx) * (1.0 - fy)) + t10 * (fx * (1.0 - fy))
         + t01 * ((1.0 - fx) * fy) + t11 * (fx * fy);
}

// Trilinear lookup in direction d at fractional level lod.
fn sample_equirect_lod(d: vec3<f32>, lod_in: f32) -> vec3<f32> {
    let last = f32(params.level_count - 1u);
    let lod = clamp(lod_in, f32(params.base_level), last);
    let l0 = floor(lod);
    let f = lod - l0;
    let uv = equirect_uv(d);
    let a = sample_equirect_bilinear(u32(l0), uv);
    if (f <= 0.0) {
        return a;
    }
    let b = sample_equirect_bilinear(min(u32(l0) + 1u, params.level_count - 1u), uv);
    return a + f * (b - a);
}

fn equirect_to_cube_texel(face: u32, i: u32, j: u32) -> vec4<f32> {
    let n = params.face_size;
    let s_count = params.samples_per_axis;
    let omega_sample = cube_texel_solid_angle(i, j, n) / f32(s_count * s_count);
    var sum = vec3<f32>(0.0);
    var weight = 0.0;
    for (var sy = 0u; sy < s_count; sy++) {
        for (var sx = 0u; sx < s_count; sx++) {
            let s = (f32(i) + (f32(sx) + 0.5) / f32(s_count)) * 2.0 / f32(n) - 1.0;
            let t = (f32(j) + (f32(sy) + 0.5) / f32(s_count)) * 2.0 / f32(n) - 1.0;
            let w = cube_face_jacobian(s, t);
            let d = rotate_y(normalize(cube_face_direction(face, s, t)),
                             params.rotation.x, -params.rotation.y);
            let lod = equirect_lod(omega_sample, params.source_size.y);
            sum += w * sample_equirect_lod(d, lod);
            weight += w;
        }
    }
    return vec4<f32>(sum / weight, 1.0);
}

@compute @workgroup_size(WORKGROUP_X, WORKGROUP_Y, WORKGROUP_Z)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    if (id.x >= params.face_size || id.y >= params.face_size || id.z >= 6u) {
        return;
    }
    textureStore(output, vec2<i32>(id.xy), i32(id.z), equirect_to_cube_texel(id.z, id.x, id.y));
}
