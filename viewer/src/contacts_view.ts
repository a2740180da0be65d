// The contacts at the nearest recorded update: each car's with the road, and those between
// cars. A dot at each point and the normal drawn as a line whose length grows with the
// depth, both coloured by depth; a contact between cars has a larger dot and its line runs
// both ways from the point, since it pushes both cars. Between updates the cars are drawn
// where they are at that instant, and their contacts go with them: at 1000 km/h a car moves
// 2.8 m from one 10 ms update to the next, and contacts left at the nearest update would lag
// or lead it by up to half of that.
import * as THREE from "three";
import { CAR_CONTACT_WIDTH, type CarTrack, type Recording } from "./recording";
import type { Sample } from "./sample";

/** Line length per metre of depth: a 1 cm overlap draws a 30 cm normal. */
const LENGTH_PER_DEPTH = 30;
/** The depth drawn fully red (m). */
const DEEP = 0.05;
const SHALLOW_COLOUR = new THREE.Color(0x39d353);
const MIDDLE_COLOUR = new THREE.Color(0xffd43b);
const DEEP_COLOUR = new THREE.Color(0xff2d2d);
/** Dot sizes (pixels): a contact with the road, one between cars. */
const ROAD_DOT = 6;
const CAR_DOT = 11;

export function depthColour(depth: number, out: THREE.Color): THREE.Color {
  const x = Math.min(Math.max(depth / DEEP, 0), 1);
  return x < 0.5
    ? out.lerpColors(SHALLOW_COLOUR, MIDDLE_COLOUR, x * 2)
    : out.lerpColors(MIDDLE_COLOUR, DEEP_COLOUR, x * 2 - 1);
}

/** Dots and normals for up to `capacity` contacts, refilled at every update. */
class ContactLayer {
  private readonly lines: THREE.LineSegments;
  private readonly points: THREE.Points;
  private readonly linePositions: Float32Array;
  private readonly lineColours: Float32Array;
  private readonly pointPositions: Float32Array;
  private readonly pointColours: Float32Array;
  private readonly colour = new THREE.Color();
  /** Contacts added since begin(). */
  count = 0;

  constructor(
    capacity: number,
    dotSize: number,
    private readonly bothWays: boolean,
    group: THREE.Group,
  ) {
    capacity = Math.max(capacity, 1);
    this.linePositions = new Float32Array(capacity * 6);
    this.lineColours = new Float32Array(capacity * 6);
    this.pointPositions = new Float32Array(capacity * 3);
    this.pointColours = new Float32Array(capacity * 3);
    const lineGeometry = new THREE.BufferGeometry();
    lineGeometry.setAttribute("position", new THREE.BufferAttribute(this.linePositions, 3));
    lineGeometry.setAttribute("color", new THREE.BufferAttribute(this.lineColours, 3));
    this.lines = new THREE.LineSegments(
      lineGeometry,
      new THREE.LineBasicMaterial({ vertexColors: true, depthTest: false }),
    );
    const pointGeometry = new THREE.BufferGeometry();
    pointGeometry.setAttribute("position", new THREE.BufferAttribute(this.pointPositions, 3));
    pointGeometry.setAttribute("color", new THREE.BufferAttribute(this.pointColours, 3));
    this.points = new THREE.Points(
      pointGeometry,
      new THREE.PointsMaterial({ size: dotSize, sizeAttenuation: false, vertexColors: true, depthTest: false }),
    );
    // Drawn over the road and the wheels (or the car bodies) that hide them.
    this.lines.renderOrder = this.points.renderOrder = 1;
    this.lines.frustumCulled = this.points.frustumCulled = false;
    group.add(this.lines, this.points);
  }

  begin(): void {
    this.count = 0;
  }

  add(point: THREE.Vector3, normal: THREE.Vector3, depth: number): void {
    const { x, y, z } = point;
    const { x: nx, y: ny, z: nz } = normal;
    const length = depth * LENGTH_PER_DEPTH;
    const back = this.bothWays ? length : 0;
    const c = depthColour(depth, this.colour);
    const n = this.count++;
    this.linePositions.set(
      [x - nx * back, y - ny * back, z - nz * back, x + nx * length, y + ny * length, z + nz * length],
      n * 6,
    );
    this.lineColours.set([c.r, c.g, c.b, c.r, c.g, c.b], n * 6);
    this.pointPositions.set([x, y, z], n * 3);
    this.pointColours.set([c.r, c.g, c.b], n * 3);
  }

  end(): void {
    for (const object of [this.lines, this.points]) {
      const geometry = object.geometry;
      geometry.setDrawRange(0, object === this.lines ? this.count * 2 : this.count);
      geometry.attributes.position.needsUpdate = true;
      geometry.attributes.color.needsUpdate = true;
    }
  }
}

/** Moves what was recorded with a car at one update to where the car is drawn now. */
class Carry {
  private readonly turn = new THREE.Quaternion();
  private readonly from = new THREE.Vector3();
  private readonly to = new THREE.Vector3();

  /** From the car's recorded pose at frame f to `drawn`, its pose at the sample. */
  set(track: CarTrack, f: number, drawn: THREE.Object3D): void {
    this.from.fromArray(track.position, f * 3);
    this.turn
      .fromArray(track.quaternion, f * 4)
      .normalize()
      .invert()
      .premultiply(drawn.quaternion);
    this.to.copy(drawn.position);
  }

  point(p: THREE.Vector3): THREE.Vector3 {
    return p.sub(this.from).applyQuaternion(this.turn).add(this.to);
  }

  direction(n: THREE.Vector3): THREE.Vector3 {
    return n.applyQuaternion(this.turn);
  }
}

/** The most entries any frame has in a list indexed by `start`. */
function mostPerFrame(start: Uint32Array): number {
  let most = 0;
  for (let f = 0; f + 1 < start.length; ++f) most = Math.max(most, start[f + 1] - start[f]);
  return most;
}

export class ContactsView {
  readonly group = new THREE.Group();
  private readonly road: ContactLayer;
  private readonly between: ContactLayer;
  private readonly carries: Carry[];
  private readonly point = new THREE.Vector3();
  private readonly normal = new THREE.Vector3();
  private readonly other = new THREE.Vector3();

  constructor(private readonly recording: Recording) {
    const road = recording.cars.reduce((sum, car) => sum + mostPerFrame(car.contactStart), 0);
    this.road = new ContactLayer(road, ROAD_DOT, false, this.group);
    this.between = new ContactLayer(mostPerFrame(recording.carContactStart), CAR_DOT, true, this.group);
    this.carries = recording.cars.map(() => new Carry());
  }

  /** The nearest update's contacts, carried with the cars as `drawn` (car k's pose at s). */
  update(s: Sample, drawn: readonly THREE.Object3D[]): void {
    const f = s.fraction < 0.5 ? s.index : s.index + 1;
    const r = this.recording;
    r.cars.forEach((car, k) => this.carries[k].set(car, f, drawn[k]));
    const { point, normal } = this;
    this.road.begin();
    r.cars.forEach((car, k) => {
      for (let c = car.contactStart[f]; c < car.contactStart[f + 1]; ++c) {
        point.fromArray(car.contacts, c * 8);
        normal.fromArray(car.contacts, c * 8 + 3);
        this.road.add(this.carries[k].point(point), this.carries[k].direction(normal), car.contacts[c * 8 + 6]);
      }
    });
    this.road.end();
    // A contact between cars pushes both: its point goes with each car, and is drawn halfway
    // between where each takes it; its normal, the direction to move car a, turns with a.
    this.between.begin();
    for (let c = r.carContactStart[f]; c < r.carContactStart[f + 1]; ++c) {
      const at = c * CAR_CONTACT_WIDTH;
      const [a, b] = [r.carContacts[at], r.carContacts[at + 1]];
      point.fromArray(r.carContacts, at + 4);
      this.carries[b].point(this.other.copy(point));
      this.carries[a].point(point).add(this.other).multiplyScalar(0.5);
      normal.fromArray(r.carContacts, at + 7);
      this.between.add(point, this.carries[a].direction(normal), r.carContacts[at + 10]);
    }
    this.between.end();
  }
}
