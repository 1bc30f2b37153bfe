// The viewer's G-buffer pass (vertex and fragment stages): per pixel the world position
// with what it is (w: 0 background, 1 object, 2 floor) and the unit normal. Meshes and the
// floor are rasterised; the sphere is ray-cast in the fragment stage over its bounding
// box, so its normals are exact at every pixel (as the preview's spheres). CPU mirror:
// src/view/raster.rs.

@group(0) @binding(0) var<uniform> frame: FrameParams;

struct VertexIn {
    @location(0) position: vec4<f32>, // (position, surface id)
    @location(1) normal: vec4<f32>,
}

struct VertexOut {
    @builtin(position) clip: vec4<f32>,
    @location(0) world: vec3<f32>,
    @location(1) normal: vec3<f32>,
    @location(2) @interpolate(flat) id: f32,
}

struct GBuffer {
    @location(0) position: vec4<f32>,
    @location(1) normal: vec4<f32>,
}

@vertex
fn vs_main(v: VertexIn) -> VertexOut {
    var o: VertexOut;
    o.clip = frame.view_projection * vec4<f32>(v.position.xyz, 1.0);
    o.world = v.position.xyz;
    o.normal = v.normal.xyz;
    o.id = v.position.w;
    return o;
}

@fragment
fn fs_mesh(v: VertexOut) -> GBuffer {
    var g: GBuffer;
    g.position = vec4<f32>(v.world, v.id);
    g.normal = vec4<f32>(normalize(v.normal), 0.0);
    return g;
}

struct SphereOut {
    @location(0) position: vec4<f32>,
    @location(1) normal: vec4<f32>,
    @builtin(frag_depth) depth: f32,
}

// The nearest hit of the pixel's ray on the sphere, with the offset from the centre
// computed as q - s d (q the ray's perpendicular offset, s the half chord), which keeps
// full precision at any distance (Haines et al. 2019, "Precision Improvements for
// Ray/Sphere Intersection", Ray Tracing Gems ch. 7).
@fragment
fn fs_sphere(v: VertexOut) -> SphereOut {
    let ray = pixel_ray(frame, v.clip.xy);
    let centre = frame.sphere.xyz;
    let radius = frame.sphere.w;
    let f = ray.origin - centre;
    let b = dot(f, ray.dir);
    let q = f - b * ray.dir;
    let disc = radius * radius - dot(q, q);
    if (disc < 0.0) {
        discard;
    }
    let s = sqrt(disc);
    let t = -b - s;
    if (t <= 0.0) {
        discard;
    }
    let offset = q - s * ray.dir;
    let p = centre + offset;
    let clip = frame.view_projection * vec4<f32>(p, 1.0);
    var o: SphereOut;
    o.position = vec4<f32>(p, 1.0);
    o.normal = vec4<f32>(offset / radius, 0.0);
    o.depth = clip.z / clip.w;
    return o;
}
