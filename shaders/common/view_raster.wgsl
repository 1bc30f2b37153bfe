// The raster stages the viewer's G-buffer pass (view_gbuffer.wgsl) and forward pass
// (view_forward.wgsl) share: the mesh vertex stage and the sphere ray-cast over its
// bounding box, so its normals are exact at every pixel (as the preview's spheres). The
// including shader declares `frame` (FrameParams). CPU mirror: src/view/raster.rs.

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

@vertex
fn vs_main(v: VertexIn) -> VertexOut {
    var o: VertexOut;
    o.clip = frame.view_projection * vec4<f32>(v.position.xyz, 1.0);
    o.world = v.position.xyz;
    o.normal = v.normal.xyz;
    o.id = v.position.w;
    return o;
}

// Where the ray through pixel centre `centre` first meets the sphere: the point, its
// unit normal and its depth; hit false where the ray misses it or starts inside it.
struct SphereHit {
    hit: bool,
    p: vec3<f32>,
    n: vec3<f32>,
    depth: f32,
}

// The nearest hit with the offset from the centre computed as q - s d (q the ray's
// perpendicular offset, s the half chord), which keeps full precision at any distance
// (Haines et al. 2019, "Precision Improvements for Ray/Sphere Intersection", Ray Tracing
// Gems ch. 7).
fn sphere_hit(centre_px: vec2<f32>) -> SphereHit {
    var h: SphereHit;
    h.hit = false;
    let ray = pixel_ray(frame, centre_px);
    let centre = frame.sphere.xyz;
    let radius = frame.sphere.w;
    let f = ray.origin - centre;
    let b = dot(f, ray.dir);
    let q = f - b * ray.dir;
    let disc = radius * radius - dot(q, q);
    if (disc < 0.0) {
        return h;
    }
    let s = sqrt(disc);
    if (-b - s <= 0.0) {
        return h;
    }
    let offset = q - s * ray.dir;
    h.hit = true;
    h.p = centre + offset;
    h.n = offset / radius;
    let clip = frame.view_projection * vec4<f32>(h.p, 1.0);
    h.depth = clip.z / clip.w;
    return h;
}
