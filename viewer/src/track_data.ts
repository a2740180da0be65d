// A track mesh as the viewer draws it, and the embedded form `trackphys view` writes
// (docs/viewer.md, "The page"): int32 differences, little-endian, of every vertex
// coordinate in millimetres from the previous vertex's, then of every triangle index from
// the previous index.

export interface TrackData {
  positions: Float32Array;
  indices: Uint32Array;
}

export function trackFromEmbedded(bytes: ArrayBuffer, vertices: number, triangles: number): TrackData {
  const expected = (vertices + triangles) * 12;
  if (bytes.byteLength !== expected)
    throw new Error(`the embedded track has ${bytes.byteLength} bytes, expected ${expected}`);
  const differences = new Int32Array(bytes);
  const positions = new Float32Array(vertices * 3);
  const whole = [0, 0, 0];
  for (let i = 0; i < vertices * 3; ++i) {
    whole[i % 3] += differences[i];
    positions[i] = whole[i % 3] / 1000;
  }
  const indices = new Uint32Array(triangles * 3);
  let index = 0;
  for (let i = 0; i < triangles * 3; ++i) {
    index = (index + differences[vertices * 3 + i]) >>> 0;
    indices[i] = index;
  }
  return { positions, indices };
}
