// What the viewer's shading passes share: the surface a pixel sees, its material and the
// point lights. Mirror of src/view/cpu.rs (same function names). The including shader
// declares `frame` (FrameParams) and `lights` (storage: (position, 0), (colour, 0) each).

// A packed material (FrameUniform's object or floor).
fn unpack_material(m: array<vec4<f32>, 3>) -> ShadeMaterial {
    var s: ShadeMaterial;
    s.f0 = m[0].xyz;
    s.metallic = m[0].w;
    s.albedo = m[1].xyz;
    s.roughness = m[1].w;
    s.lod = m[2].x;
    s.bend = m[2].y;
    s.stretch = m[2].z;
    return s;
}

// The point lights on (the first `count`, frame.light_count, of the including kernel's
// `lights` table: (position, 0), (colour, 0) each) shading the surface a pixel sees.
fn direct_lights(px: PixelView, count: u32) -> vec3<f32> {
    var sum = vec3<f32>(0.0);
    for (var i = 0u; i < count; i++) {
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

fn surface_material(id: u32) -> ShadeMaterial {
    if (id == 1u) {
        return unpack_material(frame.object);
    }
    return unpack_material(frame.floor);
}

// What a shading pass sees at a pixel: its ray's direction, the surface there, the view
// direction v = -dir, n.v clamped away from 0 by frame.front.w (silhouette normals are
// perpendicular to v) and the surface's material (the floor's on background pixels,
// which use only dir).
struct PixelView {
    dir: vec3<f32>,
    s: Surface,
    v: vec3<f32>,
    n_dot_v: f32,
    m: ShadeMaterial,
}

// The view at the pixel centred at `centre` (x + 0.5, y + 0.5) of surface `s`.
fn surface_view(centre: vec2<f32>, s: Surface) -> PixelView {
    var px: PixelView;
    px.dir = pixel_ray(frame, centre).dir;
    px.s = s;
    px.v = -px.dir;
    px.n_dot_v = max(dot(px.s.n, px.v), frame.front.w);
    px.m = surface_material(px.s.id);
    return px;
}
