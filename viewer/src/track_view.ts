// The track mesh, coloured by elevation (blue low, through green, to sand high) and lit
// from a low sun, so that both height and banking read at a glance.
import * as THREE from "three";

const LOW = new THREE.Color(0x2b5fa8);
const MIDDLE = new THREE.Color(0x5f9e4a);
const HIGH = new THREE.Color(0xd9b56c);

export function makeTrackMesh(positions: Float32Array, indices: Uint32Array): THREE.Mesh {
  const geometry = new THREE.BufferGeometry();
  geometry.setAttribute("position", new THREE.BufferAttribute(positions, 3));
  geometry.setIndex(new THREE.BufferAttribute(indices, 1));
  geometry.computeVertexNormals();
  geometry.computeBoundingBox();
  const box = geometry.boundingBox!;
  const span = Math.max(box.max.y - box.min.y, 1e-6);
  const colours = new Float32Array(positions.length);
  const colour = new THREE.Color();
  for (let i = 0; i < positions.length; i += 3) {
    const h = (positions[i + 1] - box.min.y) / span;
    if (h < 0.5) colour.lerpColors(LOW, MIDDLE, h * 2);
    else colour.lerpColors(MIDDLE, HIGH, h * 2 - 1);
    colours[i] = colour.r;
    colours[i + 1] = colour.g;
    colours[i + 2] = colour.b;
  }
  geometry.setAttribute("color", new THREE.BufferAttribute(colours, 3));
  const material = new THREE.MeshLambertMaterial({ vertexColors: true, side: THREE.DoubleSide });
  const mesh = new THREE.Mesh(geometry, material);
  mesh.name = "track";
  return mesh;
}

/** A low sun from one side (banked faces turned to it light up) and a sky/ground fill. */
export function addLights(scene: THREE.Scene): void {
  scene.add(new THREE.HemisphereLight(0xdde8ff, 0x3a3228, 1.2));
  const sun = new THREE.DirectionalLight(0xffffff, 2.0);
  sun.position.set(0.6, 0.5, 0.35);
  scene.add(sun);
}
