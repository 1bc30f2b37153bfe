// The sphere the engine checks render, as the engines load models: a glTF binary.
// A UV sphere of radius 1 at the origin with one white metallic-roughness material, as a
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
  const positions = new Float32Array(pos);
  const indices = new Uint16Array(idx);
  const bin = new Uint8Array(positions.byteLength + indices.byteLength + 3 & ~3);
  bin.set(new Uint8Array(positions.buffer), 0);
  bin.set(new Uint8Array(indices.buffer), positions.byteLength);
  const json = {
    asset: { version: '2.0' },
    scene: 0,
    scenes: [{ nodes: [0] }],
    nodes: [{ mesh: 0 }],
    meshes: [{ primitives: [{ attributes: { POSITION: 0, NORMAL: 0 }, indices: 1, material: 0 }] }],
    materials: [{ pbrMetallicRoughness: { baseColorFactor: [1, 1, 1, 1], metallicFactor: metallic, roughnessFactor: roughness } }],
    accessors: [
      { bufferView: 0, componentType: 5126, count: positions.length / 3, type: 'VEC3', min: [-1, -1, -1], max: [1, 1, 1] },
      { bufferView: 1, componentType: 5123, count: indices.length, type: 'SCALAR' },
    ],
    bufferViews: [
      { buffer: 0, byteOffset: 0, byteLength: positions.byteLength, target: 34962 },
      { buffer: 0, byteOffset: positions.byteLength, byteLength: indices.byteLength, target: 34963 },
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

