// What the viewer's shading kernels share: the G-buffer's surfaces, their materials and
// the point lights. Mirror of src/view/cpu.rs (same function names). The including kernel
// declares `frame` (FrameParams), `lights` (storage: (position, 0), (colour, 0) each),
// `gbuffer_position` and `gbuffer_normal` (texture_2d<f32>).

// A packed material (FrameUniform's object or floor).
fn unpack_material(m: array<vec4<f32>, 3>) -> ShadeMaterial {
    var s: ShadeMaterial;
    s.f0 = m[0].xyz;
    s.metallic = m[0].w;
    s.albedo = m[1].xyz;
    s.roughness = m[1].w;
    s.lod = m[2].x;
    return s;
}

// The point lights on (frame.light_count of the including kernel's `lights` table:
// (position, 0), (colour, 0) each) shading the surface a pixel sees.
fn direct_lights(px: PixelView) -> vec3<f32> {
    var sum = vec3<f32>(0.0);
    for (var i = 0u; i < frame.light_count; i++) {
        sum += point_light(px.s.p, px.s.n, px.v, px.n_dot_v, px.m, lights[2u * i].xyz, lights[2u * i + 1u].xyz, frame.floor_plane.z);
    }
    return sum;
}

// What a pixel of the G-buffer holds.
struct Surface {
    id: u32,          // 0 background, 1 object, 2 floor
    p: vec3<f32>,
    n: vec3<f32>,
}

fn load_surface(pixel: vec2<u32>) -> Surface {
    let g = textureLoad(gbuffer_position, pixel, 0);
    var s: Surface;
    s.id = u32(round(g.w));
    s.p = g.xyz;
    s.n = textureLoad(gbuffer_normal, pixel, 0).xyz;
    return s;
}

fn surface_material(id: u32) -> ShadeMaterial {
    if (id == 1u) {
        return unpack_material(frame.object);
    }
    return unpack_material(frame.floor);
}

// What a shading kernel sees at a pixel: its ray's direction, the G-buffer's surface
// there, the view direction v = -dir, n.v clamped away from 0 by frame.front.w (silhouette
// normals are perpendicular to v) and the surface's material (the floor's on background
// pixels, which use only dir).
struct PixelView {
    dir: vec3<f32>,
    s: Surface,
    v: vec3<f32>,
    n_dot_v: f32,
    m: ShadeMaterial,
}

fn pixel_view(pixel: vec2<u32>) -> PixelView {
    var px: PixelView;
    px.dir = pixel_ray(frame, vec2<f32>(f32(pixel.x) + 0.5, f32(pixel.y) + 0.5)).dir;
    px.s = load_surface(pixel);
    px.v = -px.dir;
    px.n_dot_v = max(dot(px.s.n, px.v), frame.front.w);
    px.m = surface_material(px.s.id);
    return px;
}
