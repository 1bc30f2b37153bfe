// The floor's shading by view direction (src/view/floor.rs says why and how): a table of
// view directions over the upper hemisphere, each holding T0 (the split-sum IBL and the
// lights without a map) and T1..T4 (the lights of shadow maps 0..3), interpolated
// bilinearly. Mirror of `FloorTable::radiance` in src/view/floor.rs. The including
// shader declares `floor_table` (storage: a header (columns, rows, layers, 0), then layer
// l, row j, column i at entry 1 + (l rows + j) columns + i, (radiance, 0) each).

// Where a view direction falls in the grid: the two columns and the first row around it,
// and the weights of the second column and row.
struct FloorCell {
    i0: u32,
    i1: u32,
    j0: u32,
    fu: f32,
    fw: f32,
}

// Where view direction v falls in a table of `size` (columns W, rows H), in columns and
// rows: column i at azimuth 2 pi (i + 1/2) / W - pi, wrapping; row j at polar angle
// (pi / 2) j / (H - 1), clamped at the horizon.
fn floor_table_position(v: vec3<f32>, size: vec2<f32>) -> vec2<f32> {
    let x = (atan2(v.z, v.x) + PI) / (2.0 * PI) * size.x - 0.5;
    let y = acos(clamp(v.y, 0.0, 1.0)) / (0.5 * PI) * (size.y - 1.0);
    return vec2<f32>(x, y);
}

fn floor_cell(v: vec3<f32>) -> FloorCell {
    let w = floor_table[0].x;
    let h = floor_table[0].y;
    let position = floor_table_position(v, vec2<f32>(w, h));
    let x = position.x;
    let xf = floor(x);
    let y = position.y;
    let j0 = min(floor(y), h - 2.0);
    var c: FloorCell;
    c.i0 = u32((i32(xf) + i32(w)) % i32(w));
    c.i1 = (c.i0 + 1u) % u32(w);
    c.j0 = u32(j0);
    c.fu = x - xf;
    c.fw = y - j0;
    return c;
}

// Layer l of the table at cell c, bilinear.
fn floor_layer(c: FloorCell, l: u32) -> vec3<f32> {
    let w = u32(floor_table[0].x);
    let base = 1u + (l * u32(floor_table[0].y) + c.j0) * w;
    let a = mix(floor_table[base + c.i0].xyz, floor_table[base + c.i1].xyz, c.fu);
    let b = mix(floor_table[base + w + c.i0].xyz, floor_table[base + w + c.i1].xyz, c.fu);
    return mix(a, b, c.fw);
}

// The floor's radiance seen along v (unit, towards the eye), less the point lights: T0
// plus each of the first `count` lights' maps' layer times its visibility.
fn floor_table_radiance(v: vec3<f32>, visibility: vec4<f32>, count: u32) -> vec3<f32> {
    let c = floor_cell(v);
    var sum = floor_layer(c, 0u);
    for (var k = 0u; k < min(count, MAX_SHADOW_MAPS); k++) {
        sum += visibility[k] * floor_layer(c, 1u + k);
    }
    return sum;
}
