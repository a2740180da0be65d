// The contacts of every car at the nearest recorded update: a dot at each point and its
// normal drawn as a line whose length grows with the depth, both coloured by depth.
import * as THREE from "three";
import type { Recording } from "./recording";
import type { Sample } from "./sample";

/** Line length per metre of depth: a 1 cm overlap draws a 30 cm normal. */
const LENGTH_PER_DEPTH = 30;
/** The depth drawn fully red (m). */
const DEEP = 0.05;
const SHALLOW_COLOUR = new THREE.Color(0x39d353);
const MIDDLE_COLOUR = new THREE.Color(0xffd43b);
const DEEP_COLOUR = new THREE.Color(0xff2d2d);

export function depthColour(depth: number, out: THREE.Color): THREE.Color {
  const x = Math.min(Math.max(depth / DEEP, 0), 1);
  return x < 0.5
    ? out.lerpColors(SHALLOW_COLOUR, MIDDLE_COLOUR, x * 2)
    : out.lerpColors(MIDDLE_COLOUR, DEEP_COLOUR, x * 2 - 1);
}

export class ContactsView {
  readonly group = new THREE.Group();
  private readonly lines: THREE.LineSegments;
  private readonly points: THREE.Points;
  private readonly linePositions: Float32Array;
  private readonly lineColours: Float32Array;
  private readonly pointPositions: Float32Array;
  private readonly pointColours: Float32Array;
  /** Contacts drawn by the last update(), for the HUD. */
  count = 0;

  constructor(private readonly recording: Recording) {
    let capacity = 0;
    for (const car of recording.cars) {
      for (let f = 0; f < recording.frameCount; ++f)
        capacity = Math.max(capacity, car.contactStart[f + 1] - car.contactStart[f]);
    }
    capacity = Math.max(capacity * recording.cars.length, 1);
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
      new THREE.PointsMaterial({ size: 6, sizeAttenuation: false, vertexColors: true, depthTest: false }),
    );
    // Drawn over the road and the wheels that hide them.
    this.lines.renderOrder = this.points.renderOrder = 1;
    this.lines.frustumCulled = this.points.frustumCulled = false;
    this.group.add(this.lines, this.points);
  }

  update(s: Sample): void {
    const f = s.fraction < 0.5 ? s.index : s.index + 1;
    const colour = new THREE.Color();
    let n = 0;
    for (const car of this.recording.cars) {
      for (let c = car.contactStart[f]; c < car.contactStart[f + 1]; ++c, ++n) {
        const v = car.contacts.subarray(c * 8, c * 8 + 8);
        const length = v[6] * LENGTH_PER_DEPTH;
        depthColour(v[6], colour);
        this.linePositions.set(
          [v[0], v[1], v[2], v[0] + v[3] * length, v[1] + v[4] * length, v[2] + v[5] * length],
          n * 6,
        );
        this.lineColours.set([colour.r, colour.g, colour.b, colour.r, colour.g, colour.b], n * 6);
        this.pointPositions.set([v[0], v[1], v[2]], n * 3);
        this.pointColours.set([colour.r, colour.g, colour.b], n * 3);
      }
    }
    this.count = n;
    for (const object of [this.lines, this.points]) {
      const geometry = object.geometry;
      geometry.setDrawRange(0, object === this.lines ? n * 2 : n);
      geometry.attributes.position.needsUpdate = true;
      geometry.attributes.color.needsUpdate = true;
    }
  }
}
