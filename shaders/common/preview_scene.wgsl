// The preview's scene: which sphere (material row, roughness column) or background ray a
// pixel of a panel sees. Mirror of src/plan/scene.rs (same function names); every
// number comes from the uniform block, filled by Scene::uniform on the Rust side.
// `preview_material` reads the including kernel's `spheres` and `materials` tables.

struct SceneParams {
    width: u32,
    height: u32,
    cell: u32,
    columns: u32,
    radius: f32,      // sphere radius in pixels
    tan_half_x: f32,  // background camera
    tan_half_y: f32,
    min_n_dot_v: f32, // smallest n.v the shading uses (silhouette normals are perpendicular to v)
    right: vec4<f32>,
    up: vec4<f32>,
    forward: vec4<f32>,
}

struct PixelGeometry {
    sphere: bool,
    dir: vec3<f32>,   // the normal on a sphere, the ray direction on the background
    v: vec3<f32>,     // towards the camera (spheres)
    material: u32,
    column: u32,
}

// A sphere pixel sees the sphere orthographically (normal (x, y, sqrt(1 - x^2 - y^2)) in
// camera space, v the camera's backward axis); any other pixel the environment through a
// pinhole camera covering the panel.
fn pixel_geometry(s: SceneParams, x: u32, y: u32) -> PixelGeometry {
    var g: PixelGeometry;
    let col = x / s.cell;
    let row = y / s.cell;
    let half = 0.5 * f32(s.cell);
    let cx = f32(x - col * s.cell) + 0.5 - half;
    let cy = half - (f32(y - row * s.cell) + 0.5);
    let u = cx / s.radius;
    let w = cy / s.radius;
    let r2 = u * u + w * w;
    if (r2 < 1.0) {
        let z = sqrt(1.0 - r2);
        g.sphere = true;
        g.dir = u * s.right.xyz + w * s.up.xyz - z * s.forward.xyz;
        g.v = -s.forward.xyz;
        g.material = row;
        g.column = col;
        return g;
    }
    let nx = 2.0 * (f32(x) + 0.5) / f32(s.width) - 1.0;
    let ny = 1.0 - 2.0 * (f32(y) + 0.5) / f32(s.height);
    g.sphere = false;
    g.dir = normalize((nx * s.tan_half_x) * s.right.xyz + (ny * s.tan_half_y) * s.up.xyz + s.forward.xyz);
    return g;
}

// The material of the sphere in row `material`, column `column`: the row's (F0, metallic),
// (albedo, 0) from `materials`, the sphere's (roughness, lod, bend, stretch) from `spheres`
// (a row of scene.columns spheres per material).
fn preview_material(material: u32, column: u32) -> ShadeMaterial {
    let fm = materials[2u * material];
    let col = spheres[material * scene.columns + column];
    var m: ShadeMaterial;
    m.f0 = fm.rgb;
    m.metallic = fm.w;
    m.albedo = materials[2u * material + 1u].rgb;
    m.roughness = col.x;
    m.lod = col.y;
    m.bend = col.z;
    m.stretch = col.w;
    return m;
}
