// Each car as its ellipsoids, posed per frame between recorded updates (positions
// interpolated linearly, orientations by slerp), wheels lifted by their suspension.
import * as THREE from "three";
import type { CarTrack } from "./recording";
import { lerpAt, type Sample } from "./sample";

const BODY_COLOURS = [0xd8432e, 0x2f7fd8, 0xe0b21a, 0x8a4fd0, 0x2fae6a, 0xe06fb0, 0x5a5a5a, 0xf08a24];
const WHEEL_COLOUR = 0x1d1d1f;
const UNIT_SPHERE = new THREE.SphereGeometry(1, 32, 16);

// Past the eight, hues a golden angle apart, so that no two cars of a big field look alike.
export function carColour(k: number): number {
  if (k < BODY_COLOURS.length) return BODY_COLOURS[k];
  return new THREE.Color().setHSL((k * 0.381966) % 1, 0.65, 0.5).getHex();
}

export class CarView {
  readonly group = new THREE.Group();
  private readonly parts: THREE.Mesh[] = [];
  private readonly qa = new THREE.Quaternion();
  private readonly qb = new THREE.Quaternion();

  constructor(
    private readonly track: CarTrack,
    k: number,
  ) {
    const body = new THREE.MeshStandardMaterial({ color: carColour(k), roughness: 0.5, metalness: 0.1 });
    const wheel = new THREE.MeshStandardMaterial({ color: WHEEL_COLOUR, roughness: 0.9 });
    if (!track.shapeKnown) {
      body.transparent = true;
      body.opacity = 0.6;
    }
    for (const e of track.ellipsoids) {
      const part = new THREE.Mesh(UNIT_SPHERE, e.role !== "body" ? wheel : body);
      part.scale.set(...e.semiAxes);
      const [w, x, y, z] = e.orientation;
      part.quaternion.set(x, y, z, w).normalize();
      part.userData.wheel = e.role !== "body";
      this.parts.push(part);
      this.group.add(part);
    }
    this.group.name = `car ${k}`;
  }

  /** Poses the car at the sample. */
  pose(s: Sample): void {
    const t = this.track;
    this.group.position.set(lerpAt(t.position, 3, 0, s), lerpAt(t.position, 3, 1, s), lerpAt(t.position, 3, 2, s));
    const i = s.index * 4;
    this.qa.set(t.quaternion[i], t.quaternion[i + 1], t.quaternion[i + 2], t.quaternion[i + 3]);
    if (s.fraction > 0) {
      this.qb.set(t.quaternion[i + 4], t.quaternion[i + 5], t.quaternion[i + 6], t.quaternion[i + 7]);
      this.qa.slerp(this.qb, s.fraction);
    }
    this.group.quaternion.copy(this.qa);
    const count = t.ellipsoids.length;
    t.ellipsoids.forEach((e, j) => {
      const lift = lerpAt(t.suspension, count, j, s);
      this.parts[j].position.set(e.center[0], e.center[1] + lift, e.center[2]);
    });
  }
}
