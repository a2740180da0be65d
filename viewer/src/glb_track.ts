// A track mesh dropped as a .glb file (what `drive --record` writes beside a recording):
// every mesh in the file, in world coordinates, as one indexed triangle list.
import * as THREE from "three";
import { GLTFLoader } from "three/examples/jsm/loaders/GLTFLoader.js";
import type { TrackData } from "./track_data";

export async function trackFromGlb(bytes: ArrayBuffer): Promise<TrackData> {
  const gltf = await new GLTFLoader().parseAsync(bytes, "");
  const positions: number[] = [];
  const indices: number[] = [];
  const v = new THREE.Vector3();
  gltf.scene.updateMatrixWorld(true);
  gltf.scene.traverse((object) => {
    if (!(object instanceof THREE.Mesh)) return;
    const geometry = object.geometry as THREE.BufferGeometry;
    const position = geometry.getAttribute("position");
    const base = positions.length / 3;
    for (let i = 0; i < position.count; ++i) {
      v.fromBufferAttribute(position, i).applyMatrix4(object.matrixWorld);
      positions.push(v.x, v.y, v.z);
    }
    const index = geometry.getIndex();
    const count = index ? index.count : position.count;
    for (let i = 0; i < count; ++i) indices.push(base + (index ? index.getX(i) : i));
  });
  if (indices.length === 0) throw new Error("the .glb file holds no triangles");
  return { positions: new Float32Array(positions), indices: new Uint32Array(indices) };
}
