// The contacts at the nearest recorded update: each car's with the road, and those between
// cars. A dot at each point and the normal drawn as a line whose length grows with the
// depth, both coloured by depth; a contact between cars has a larger dot and its line runs
// both ways from the point, since it pushes both cars.
import * as THREE from "three";
import { CAR_CONTACT_WIDTH, type Recording } from "./recording";
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

  /** v[at..at+2] the point, v[at+3..at+5] the unit normal, v[at+6] the depth. */
  add(v: Float32Array, at: number): void {
    const [x, y, z, nx, ny, nz, depth] = v.subarray(at, at + 7);
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

  constructor(private readonly recording: Recording) {
    const road = recording.cars.reduce((sum, car) => sum + mostPerFrame(car.contactStart), 0);
    this.road = new ContactLayer(road, ROAD_DOT, false, this.group);
    this.between = new ContactLayer(mostPerFrame(recording.carContactStart), CAR_DOT, true, this.group);
  }

  update(s: Sample): void {
    const f = s.fraction < 0.5 ? s.index : s.index + 1;
    this.road.begin();
    for (const car of this.recording.cars)
      for (let c = car.contactStart[f]; c < car.contactStart[f + 1]; ++c) this.road.add(car.contacts, c * 8);
    this.road.end();
    const r = this.recording;
    this.between.begin();
    for (let c = r.carContactStart[f]; c < r.carContactStart[f + 1]; ++c)
      this.between.add(r.carContacts, c * CAR_CONTACT_WIDTH + 4);
    this.between.end();
  }
}
