// A track mesh as the viewer draws it, and the embedded form `trackphys view` writes: the
// vertices as float32 x, y, z, then the triangles as uint32 indices (little-endian).

export interface TrackData {
  positions: Float32Array;
  indices: Uint32Array;
}

export function trackFromEmbedded(bytes: ArrayBuffer, vertices: number, triangles: number): TrackData {
  const expected = vertices * 12 + triangles * 12;
  if (bytes.byteLength !== expected)
    throw new Error(`the embedded track has ${bytes.byteLength} bytes, expected ${expected}`);
  return {
    positions: new Float32Array(bytes, 0, vertices * 3),
    indices: new Uint32Array(bytes, vertices * 12, triangles * 3),
  };
}
