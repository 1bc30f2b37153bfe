// Directions, equirect and cube-face mappings, texel solid angles.
// Mirror of src/math/cubemap.rs (same function names). Equirect: u = 0.5 + atan2(z, x)/2pi,
// v = acos(y)/pi (v = 0 top). Faces +X, -X, +Y, -Y, +Z, -Z per the Vulkan face selection
// table, rows top to bottom.

// Direction through face coordinates (s, t) in [-1, 1]^2 (not normalised).
fn cube_face_direction(face: u32, s: f32, t: f32) -> vec3<f32> {
    switch face {
        case 0u: { return vec3<f32>(1.0, -t, -s); }
        case 1u: { return vec3<f32>(-1.0, -t, s); }
        case 2u: { return vec3<f32>(s, 1.0, t); }
        case 3u: { return vec3<f32>(s, -1.0, -t); }
        case 4u: { return vec3<f32>(s, -t, 1.0); }
        default: { return vec3<f32>(-s, -t, -1.0); }
    }
}

// Unit direction through the centre of texel (i, j) of an n x n face (one texel off the
// face allowed: extended on the face's plane).
fn cube_texel_direction(face: u32, i: i32, j: i32, n: u32) -> vec3<f32> {
    let s = (f32(i) + 0.5) * 2.0 / f32(n) - 1.0;
    let t = (f32(j) + 0.5) * 2.0 / f32(n) - 1.0;
    return normalize(cube_face_direction(face, s, t));
}

// Face and (s, t) in [-1, 1]^2 that direction d lands on (inverse of cube_face_direction).
fn cube_face_coords(d: vec3<f32>) -> vec3<f32> {
    let a = abs(d);
    if (a.x >= a.y && a.x >= a.z) {
        if (d.x >= 0.0) {
            return vec3<f32>(0.0, -d.z / a.x, -d.y / a.x);
        }
        return vec3<f32>(1.0, d.z / a.x, -d.y / a.x);
    } else if (a.y >= a.z) {
        if (d.y >= 0.0) {
            return vec3<f32>(2.0, d.x / a.y, d.z / a.y);
        }
        return vec3<f32>(3.0, d.x / a.y, -d.z / a.y);
    } else if (d.z >= 0.0) {
        return vec3<f32>(4.0, d.x / a.z, -d.y / a.z);
    }
    return vec3<f32>(5.0, -d.x / a.z, -d.y / a.z);
}

// Equirect (u, v) of a unit direction: u from atan2(z, x), v = acos(y) = atan2(|xz|, y).
fn equirect_uv(d: vec3<f32>) -> vec2<f32> {
    return vec2<f32>(0.5 + atan2_precise(d.z, d.x) / (2.0 * PI),
                     atan2_precise(sqrt(d.x * d.x + d.z * d.z), d.y) / PI);
}

// Rotation about +Y (right-handed: +X turns towards -Z for a positive angle).
fn rotate_y(d: vec3<f32>, cos_a: f32, sin_a: f32) -> vec3<f32> {
    return vec3<f32>(cos_a * d.x + sin_a * d.z, d.y, -sin_a * d.x + cos_a * d.z);
}

// atan2(x y, sqrt(x^2 + y^2 + 1)): integral of the face's solid-angle density.
fn area_element(x: f32, y: f32) -> f32 {
    return atan2_precise(x * y, sqrt(x * x + y * y + 1.0));
}

// Exact solid angle of texel (i, j) of an n x n face.
fn cube_texel_solid_angle(i: u32, j: u32, n: u32) -> f32 {
    let inv = 2.0 / f32(n);
    let x0 = f32(i) * inv - 1.0;
    let y0 = f32(j) * inv - 1.0;
    let x1 = x0 + inv;
    let y1 = y0 + inv;
    return area_element(x0, y0) - area_element(x0, y1) - area_element(x1, y0) + area_element(x1, y1);
}

// Solid-angle density of the face parametrisation: 1 / (1 + s^2 + t^2)^(3/2).
fn cube_face_jacobian(s: f32, t: f32) -> f32 {
    let r2 = 1.0 + s * s + t * t;
    return 1.0 / (r2 * sqrt(r2));
}
