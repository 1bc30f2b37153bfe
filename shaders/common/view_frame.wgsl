// The viewer's frame: camera, materials, sphere and floor, filled by FrameUniform::new on
// the Rust side (src/view/frame.rs; layout checked in tests/shaders.rs), and the ray of a
// pixel. Mirror of src/view/camera.rs (`CameraFrame::pixel_ray`).

struct FrameParams {
    width: u32,
    height: u32,
    truth_frame: u32,
    light_count: u32,
    position: vec4<f32>,   // w: 1 for parallel rays
    right: vec4<f32>,      // w: half extent x
    up: vec4<f32>,         // w: half extent y
    front: vec4<f32>,      // w: smallest n.v of the shading
    view_projection: mat4x4<f32>,
    object: array<vec4<f32>, 3>, // (F0, metallic), (albedo, roughness), (lod, bend, 0, 0)
    floor: array<vec4<f32>, 3>,
    sphere: vec4<f32>,     // (centre, radius)
    floor_plane: vec4<f32>, // (height, half extent, smallest alpha of the point lights, 0)
    // The lights taken out of the environment: (split-sum entries, truth disc cells after
    // them, how many cast a shadow (light k has map k), the shadow maps' edge in texels).
    sun: vec4<u32>,
    // Each light's shadow map, four entries a light: (origin, half extent), (right, depth
    // bias), (up, normal offset), (front, penumbra spread) (src/view/shadow.rs).
    shadow: array<vec4<f32>, SHADOW_ENTRIES>,
}

// The most lights with a shadow map (src/view/frame.rs): their visibilities are a vec4.
const MAX_SHADOW_MAPS: u32 = 4u;
// Entries of `FrameParams.shadow`: four a map.
const SHADOW_ENTRIES: u32 = 4u * MAX_SHADOW_MAPS;

struct Ray {
    origin: vec3<f32>,
    dir: vec3<f32>,
}

// The ray through pixel centre `centre` (x + 0.5, y + 0.5; y down).
fn pixel_ray(f: FrameParams, centre: vec2<f32>) -> Ray {
    let nx = 2.0 * centre.x / f32(f.width) - 1.0;
    let ny = 1.0 - 2.0 * centre.y / f32(f.height);
    var r: Ray;
    if (f.position.w > 0.5) {
        r.origin = f.position.xyz + (nx * f.right.w) * f.right.xyz + (ny * f.up.w) * f.up.xyz;
        r.dir = f.front.xyz;
    } else {
        r.origin = f.position.xyz;
        r.dir = normalize((nx * f.right.w) * f.right.xyz + (ny * f.up.w) * f.up.xyz + f.front.xyz);
    }
    return r;
}
