// The track mesh, coloured by elevation (blue low, through green, to sand high) and lit
// from a low sun, so that both height and banking read at a glance.
import * as THREE from "three";

const LOW = new THREE.Color(0x2b5fa8);
const MIDDLE = new THREE.Color(0x5f9e4a);
const HIGH = new THREE.Color(0xd9b56c);

/** Tile edge (m): small enough that the chase camera's view holds a few tiles of a track
 *  kilometres long, large enough that a tile is hundreds of triangles. */
const TILE = 200;

/** The track as tiles that three.js culls when out of view, sharing one set of vertices. */
export function makeTrackMesh(positions: Float32Array, indices: Uint32Array): THREE.Group {
  const whole = new THREE.BufferGeometry();
  whole.setAttribute("position", new THREE.BufferAttribute(positions, 3));
  whole.setIndex(new THREE.BufferAttribute(indices, 1));
  whole.computeVertexNormals();
  whole.setAttribute("color", new THREE.BufferAttribute(elevationColours(positions), 3));
  const material = new THREE.MeshLambertMaterial({ vertexColors: true, side: THREE.DoubleSide });
  const group = new THREE.Group();
  group.name = "track";
  const v = new THREE.Vector3();
  for (const tile of tiles(positions, indices)) {
    const geometry = new THREE.BufferGeometry();
    for (const name of ["position", "normal", "color"]) geometry.setAttribute(name, whole.getAttribute(name));
    geometry.setIndex(new THREE.BufferAttribute(tile, 1));
    // Bounds of this tile's triangles: the default would span the whole shared vertex array.
    const box = new THREE.Box3();
    for (const i of tile) box.expandByPoint(v.fromArray(positions, i * 3));
    geometry.boundingBox = box;
    geometry.boundingSphere = box.getBoundingSphere(new THREE.Sphere());
    group.add(new THREE.Mesh(geometry, material));
  }
  return group;
}

/** The triangles' indices grouped by the TILE x TILE square (in x, z) of their first corner. */
function tiles(positions: Float32Array, indices: Uint32Array): Uint32Array[] {
  const byCell = new Map<string, number[]>();
  for (let t = 0; t < indices.length; t += 3) {
    const i = indices[t] * 3;
    const key = `${Math.floor(positions[i] / TILE)},${Math.floor(positions[i + 2] / TILE)}`;
    let list = byCell.get(key);
    if (!list) byCell.set(key, (list = []));
    list.push(indices[t], indices[t + 1], indices[t + 2]);
  }
  return Array.from(byCell.values(), (list) => Uint32Array.from(list));
}

function elevationColours(positions: Float32Array): Float32Array {
  let low = Infinity;
  let high = -Infinity;
  for (let i = 1; i < positions.length; i += 3) {
    low = Math.min(low, positions[i]);
    high = Math.max(high, positions[i]);
  }
  const span = Math.max(high - low, 1e-6);
  const colours = new Float32Array(positions.length);
  const colour = new THREE.Color();
  for (let i = 0; i < positions.length; i += 3) {
    const h = (positions[i + 1] - low) / span;
    if (h < 0.5) colour.lerpColors(LOW, MIDDLE, h * 2);
    else colour.lerpColors(MIDDLE, HIGH, h * 2 - 1);
    colour.toArray(colours, i);
  }
  return colours;
}

/** A low sun from one side (banked faces turned to it light up) and a sky/ground fill. */
export function addLights(scene: THREE.Scene): void {
  scene.add(new THREE.HemisphereLight(0xdde8ff, 0x3a3228, 1.2));
  const sun = new THREE.DirectionalLight(0xffffff, 2.0);
  sun.position.set(0.6, 0.5, 0.35);
  scene.add(sun);
}
