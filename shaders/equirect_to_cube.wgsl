// Equirect -> cube, level 0: each texel is the exact solid-angle mean of the piecewise-
// constant equirect over the texel's footprint, by Green's theorem: the radiance integrated
// along each meridian from a pole (tables `from_north`, `from_south`) is integrated along
// the texel's four great-circle edges, split at source column boundaries, with a 3-point
// Gauss-Legendre rule. CPU mirror, function for function, and the derivation:
// src/cpu/equirect_to_cube.rs.

struct EquirectToCubeParams {
    face_size: u32,
    pad: u32,
    source_size: vec2<u32>, // W, H of the source level
    rotation: vec2<f32>,    // cos, sin of the rotation about +Y
    pad2: vec2<u32>,
}

// Gauss-Legendre 3-point rule on [-1, 1]; equal to GAUSS_NODE and GAUSS_WEIGHTS in
// src/cpu/equirect_to_cube.rs (checked by tests/shaders.rs).
const GAUSS_NODE: f32 = 0.7745967;
const GAUSS_WEIGHT_OUTER: f32 = 0.5555556;
const GAUSS_WEIGHT_CENTRE: f32 = 0.8888889;

@group(0) @binding(0) var<uniform> params: EquirectToCubeParams;
@group(0) @binding(1) var radiance: texture_2d<f32>;
@group(0) @binding(2) var from_north: texture_2d<f32>;
@group(0) @binding(3) var from_south: texture_2d<f32>;
// Per row boundary: cos, sin, 1 - cos, 1 + cos of theta_r.
@group(0) @binding(4) var<storage, read> rows: array<vec4<f32>>;
// Per column boundary: (-sin phi, cos phi), the meridian plane's normal (x, z).
@group(0) @binding(5) var<storage, read> columns: array<vec2<f32>>;
@group(0) @binding(6) var output: texture_storage_2d_array<rgba32float, write>;

// ca - cb without cancellation near a pole.
fn cos_difference(ca: f32, sa: f32, cb: f32, sb: f32) -> f32 {
    let sum = ca + cb;
    if (abs(sum) >= 0.5) {
        return (sb - sa) * (sb + sa) / sum;
    }
    return ca - cb;
}

fn column_of(width: u32, d: vec3<f32>) -> u32 {
    let u = 0.5 + atan2_precise(d.z, d.x) / (2.0 * PI);
    return min(u32(max(floor(u * f32(width)), 0.0)), width - 1u);
}

// Phi at d (in column col), from the north or the south pole; w = the same for L = 1.
fn meridian_cumulative(col: u32, d: vec3<f32>, north: bool) -> vec4<f32> {
    let h2 = d.x * d.x + d.z * d.z;
    let h = sqrt(h2);
    let rho = sqrt(h2 + d.y * d.y);
    let c = d.y / rho;
    let s = h / rho;
    let theta = atan2_precise(h, d.y);
    let height = params.source_size.y;
    let row = min(u32(theta * f32(height) / PI), height - 1u);
    let texel = vec2<i32>(i32(col), i32(row));
    let l = textureLoad(radiance, texel, 0).rgb;
    if (north) {
        let b = rows[row];
        let dc = cos_difference(b.x, b.y, c, s);
        let n = textureLoad(from_north, texel, 0).rgb;
        return vec4<f32>(-(n + l * dc), -(b.z + dc));
    }
    let b = rows[row + 1u];
    let dc = cos_difference(c, s, b.x, b.y);
    let n = textureLoad(from_south, texel, 0).rgb;
    return vec4<f32>(n + l * dc, b.w + dc);
}

// Integral of Phi dphi along the great-circle arc from a to b (radiance, solid angle).
fn edge_integral(a: vec3<f32>, b: vec3<f32>, north: bool) -> vec4<f32> {
    var acc = vec4<f32>(0.0);
    let cross_y = a.x * b.z - a.z * b.x;
    if (cross_y == 0.0) {
        return acc;
    }
    let dir = b - a;
    let w = params.source_size.x;
    let ka = column_of(w, a);
    let kb = column_of(w, b);
    let up = cross_y > 0.0;
    var count = select((ka + w - kb) % w, (kb + w - ka) % w, up);
    if (count > w / 2u) {
        count = 0u;
    }
    var lam0 = 0.0;
    var col = ka;
    for (var step = 0u; step <= count; step++) {
        var lam1 = 1.0;
        var next = col;
        if (step < count) {
            let m = columns[select(col, col + 1u, up)];
            let am = a.x * m.x + a.z * m.y;
            let dm = dir.x * m.x + dir.z * m.y;
            lam1 = lam0;
            if (dm != 0.0) {
                lam1 = clamp(-am / dm, lam0, 1.0);
            }
            next = select((col + w - 1u) % w, (col + 1u) % w, up);
        }
        let half = 0.5 * (lam1 - lam0);
        if (half > 0.0) {
            let mid = lam0 + half;
            for (var k = 0u; k < 3u; k++) {
                var offset = 0.0;
                var weight = GAUSS_WEIGHT_CENTRE;
                if (k == 0u) {
                    offset = -GAUSS_NODE;
                    weight = GAUSS_WEIGHT_OUTER;
                } else if (k == 2u) {
                    offset = GAUSS_NODE;
                    weight = GAUSS_WEIGHT_OUTER;
                }
                let lam = mid + offset * half;
                let d = a + lam * dir;
                let dphi = cross_y / (d.x * d.x + d.z * d.z);
                acc += (weight * half * dphi) * meridian_cumulative(col, d, north);
            }
        }
        lam0 = lam1;
        col = next;
    }
    return acc;
}

// edge_integral in one canonical direction (from the lexicographically smaller end).
fn oriented_edge_integral(a: vec3<f32>, b: vec3<f32>, north: bool) -> vec4<f32> {
    let less = a.x < b.x || (a.x == b.x && (a.y < b.y || (a.y == b.y && a.z < b.z)));
    if (less) {
        return edge_integral(a, b, north);
    }
    return -edge_integral(b, a, north);
}

fn corner(face: u32, s: f32, t: f32) -> vec3<f32> {
    return rotate_y(cube_face_direction(face, s, t), params.rotation.x, -params.rotation.y);
}

fn equirect_to_cube_texel(face: u32, i: u32, j: u32) -> vec4<f32> {
    let inv = 2.0 / f32(params.face_size);
    let s0 = f32(i) * inv - 1.0;
    let s1 = f32(i + 1u) * inv - 1.0;
    let t0 = f32(j) * inv - 1.0;
    let t1 = f32(j + 1u) * inv - 1.0;
    var v = array<vec3<f32>, 4>(corner(face, s0, t0), corner(face, s1, t0),
                                corner(face, s1, t1), corner(face, s0, t1));
    let north = cube_face_direction(face, 0.5 * (s0 + s1), 0.5 * (t0 + t1)).y >= 0.0;
    var sum = vec4<f32>(0.0);
    for (var k = 0u; k < 4u; k++) {
        sum += oriented_edge_integral(v[k], v[(k + 1u) % 4u], north);
    }
    return vec4<f32>(sum.xyz / sum.w, 1.0);
}

@compute @workgroup_size(WORKGROUP_X, WORKGROUP_Y, WORKGROUP_Z)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    if (id.x >= params.face_size || id.y >= params.face_size || id.z >= 6u) {
        return;
    }
    textureStore(output, vec2<i32>(id.xy), i32(id.z), equirect_to_cube_texel(id.z, id.x, id.y));
}
