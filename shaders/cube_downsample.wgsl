// Next cube mip: each parent texel is the solid-angle-weighted mean of its 2 x 2 children,
// so the integral of L over the sphere is the same at every level.
// CPU mirror: src/cpu/cube_downsample.rs.

@group(0) @binding(0) var child: texture_2d_array<f32>;
@group(0) @binding(1) var output: texture_storage_2d_array<rgba32float, write>;

fn cube_downsample_texel(n: u32, face: u32, i: u32, j: u32) -> vec4<f32> {
    let cn = 2u * n;
    var sum = vec4<f32>(0.0);
    var weight = 0.0;
    for (var dy = 0u; dy < 2u; dy++) {
        for (var dx = 0u; dx < 2u; dx++) {
            let ci = 2u * i + dx;
            let cj = 2u * j + dy;
            let w = cube_texel_solid_angle(ci, cj, cn);
            sum += w * textureLoad(child, vec2<u32>(ci, cj), face, 0);
            weight += w;
        }
    }
    return sum / weight;
}

@compute @workgroup_size(WORKGROUP_X, WORKGROUP_Y, WORKGROUP_Z)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    let n = textureDimensions(output).x;
    if (id.x >= n || id.y >= n || id.z >= 6u) {
        return;
    }
    textureStore(output, vec2<i32>(id.xy), i32(id.z), cube_downsample_texel(n, id.z, id.x, id.y));
}
