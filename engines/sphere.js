// The models the engine checks render, as the engines load models: glTF binaries.
// The sphere: a UV sphere of radius 1 at the origin with one white metallic-roughness material, as a
// GLB (glTF 2.0 binary) for the engines' own glTF loaders.
export function sphereGlb(metallic, roughness) {
  const rings = 96, segments = 192;
  const pos = [], idx = [];
  for (let i = 0; i <= rings; i++) {
    const theta = (Math.PI * i) / rings;
    for (let j = 0; j <= segments; j++) {
      const phi = (2 * Math.PI * j) / segments;
      pos.push(Math.sin(theta) * Math.cos(phi), Math.cos(theta), Math.sin(theta) * Math.sin(phi));
    }
  }
  for (let i = 0; i < rings; i++) {
    for (let j = 0; j < segments; j++) {
      const a = i * (segments + 1) + j, b = a + segments + 1;
      idx.push(a, a + 1, b, a + 1, b + 1, b);
    }
  }
  return meshGlb(pos, pos, idx, metallic, roughness);
}

// A floor (the square y = 0 of half-size `extent`, facing up) and a unit box centred at
// (0, `height`, 0), both white diffuse (metallic 0, roughness 1), as one GLB: the shadow
// scene of the sun checks (engines/measure.js, shadowAzimuth).
export function shadowSceneGlb(extent, height) {
  const pos = [], nor = [], idx = [];
  const quad = (corners, n) => {
    const base = pos.length / 3;
    for (const c of corners) { pos.push(...c); nor.push(...n); }
    idx.push(base, base + 1, base + 2, base, base + 2, base + 3);
  };
  const e = extent;
  quad([[-e, 0, -e], [-e, 0, e], [e, 0, e], [e, 0, -e]], [0, 1, 0]);
  // The box's six faces, each counter-clockwise seen from outside.
  for (const [axis, sign] of [[0, 1], [0, -1], [1, 1], [1, -1], [2, 1], [2, -1]]) {
    const n = [0, 0, 0];
    n[axis] = sign;
    const [u, v] = [(axis + 1) % 3, (axis + 2) % 3];
    const corner = (a, b) => {
      const c = [0, 0, 0];
      c[axis] = 0.5 * sign;
      c[u] = a;
      c[v] = b;
      return [c[0], c[1] + height, c[2]];
    };
    const h = 0.5;
    const corners = [corner(-h, -h), corner(h, -h), corner(h, h), corner(-h, h)];
    quad(sign > 0 ? corners : corners.reverse(), n);
  }
  return meshGlb(pos, nor, idx, 0, 1);
}

// One mesh of `positions`, `normals` (flat xyz arrays) and triangle `indices`, with one
// white metallic-roughness material, as a GLB.
function meshGlb(pos, nor, idx, metallic, roughness) {
  const positions = new Float32Array(pos);
  const normals = new Float32Array(nor);
  const indices = new Uint16Array(idx);
  const min = [0, 1, 2].map((k) => Math.min(...positions.filter((_, i) => i % 3 === k)));
  const max = [0, 1, 2].map((k) => Math.max(...positions.filter((_, i) => i % 3 === k)));
  const bin = new Uint8Array(positions.byteLength + normals.byteLength + indices.byteLength + 3 & ~3);
  bin.set(new Uint8Array(positions.buffer), 0);
  bin.set(new Uint8Array(normals.buffer), positions.byteLength);
  bin.set(new Uint8Array(indices.buffer), positions.byteLength + normals.byteLength);
  const json = {
    asset: { version: '2.0' },
    scene: 0,
    scenes: [{ nodes: [0] }],
    nodes: [{ mesh: 0 }],
    meshes: [{ primitives: [{ attributes: { POSITION: 0, NORMAL: 1 }, indices: 2, material: 0 }] }],
    materials: [{ pbrMetallicRoughness: { baseColorFactor: [1, 1, 1, 1], metallicFactor: metallic, roughnessFactor: roughness } }],
    accessors: [
      { bufferView: 0, componentType: 5126, count: positions.length / 3, type: 'VEC3', min, max },
      { bufferView: 1, componentType: 5126, count: normals.length / 3, type: 'VEC3' },
      { bufferView: 2, componentType: 5123, count: indices.length, type: 'SCALAR' },
    ],
    bufferViews: [
      { buffer: 0, byteOffset: 0, byteLength: positions.byteLength, target: 34962 },
      { buffer: 0, byteOffset: positions.byteLength, byteLength: normals.byteLength, target: 34962 },
      { buffer: 0, byteOffset: positions.byteLength + normals.byteLength, byteLength: indices.byteLength, target: 34963 },
    ],
    buffers: [{ byteLength: bin.byteLength }],
  };
  let text = new TextEncoder().encode(JSON.stringify(json));
  const jsonChunk = new Uint8Array(text.length + 3 & ~3).fill(0x20);
  jsonChunk.set(text);
  const glb = new Uint8Array(12 + 8 + jsonChunk.length + 8 + bin.length);
  const dv = new DataView(glb.buffer);
  dv.setUint32(0, 0x46546c67, true);
  dv.setUint32(4, 2, true);
  dv.setUint32(8, glb.length, true);
  dv.setUint32(12, jsonChunk.length, true);
  dv.setUint32(16, 0x4e4f534a, true);
  glb.set(jsonChunk, 20);
  dv.setUint32(20 + jsonChunk.length, bin.length, true);
  dv.setUint32(24 + jsonChunk.length, 0x004e4942, true);
  glb.set(bin, 28 + jsonChunk.length);
  return glb;
}

