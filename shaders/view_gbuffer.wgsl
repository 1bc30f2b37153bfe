// The viewer's G-buffer pass (fragment stages; the vertex stage and the sphere's ray-cast
// are common/view_raster.wgsl): per pixel the world position with what it is (w: 0
// background, 1 object, 2 floor) and the unit normal, for the deferred kernels (truth,
// heat map, HDR readback). CPU mirror: src/view/raster.rs.

@group(0) @binding(0) var<uniform> frame: FrameParams;

struct GBuffer {
    @location(0) position: vec4<f32>,
    @location(1) normal: vec4<f32>,
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

@fragment
fn fs_sphere(v: VertexOut) -> SphereOut {
    let h = sphere_hit(v.clip.xy);
    if (!h.hit) {
        discard;
    }
    var o: SphereOut;
    o.position = vec4<f32>(h.p, 1.0);
    o.normal = vec4<f32>(h.n, 0.0);
    o.depth = h.depth;
    return o;
}
