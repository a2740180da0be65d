// The three cameras, all following the selected car: chase (behind and above it, in its
// frame), orbit (the mouse turns and zooms around it) and top (straight down, north up).
import * as THREE from "three";
import { OrbitControls } from "three/examples/jsm/controls/OrbitControls.js";

export type CameraMode = "chase" | "orbit" | "top";
export const CAMERA_KEYS: Record<string, CameraMode> = { "1": "chase", "2": "orbit", "3": "top" };

const CHASE_OFFSET = new THREE.Vector3(0, 2.6, -8.5); // body frame: behind and above
const CHASE_LOOK = new THREE.Vector3(0, 0.8, 6); // ahead of the car
const TOP_HEIGHT = 60; // m above the car: the car and 100 m of road around it

export class CameraRig {
  readonly camera = new THREE.PerspectiveCamera(55, 1, 0.1, 20000);
  mode: CameraMode = "chase";
  private readonly orbit: OrbitControls;
  private readonly lastTarget = new THREE.Vector3();
  private readonly v = new THREE.Vector3();

  constructor(
    element: HTMLElement,
    private readonly onChange: () => void,
  ) {
    this.orbit = new OrbitControls(this.camera, element);
    this.orbit.enabled = false;
    // Stay above the car's horizon: from below, the road hides the car.
    this.orbit.maxPolarAngle = Math.PI * 0.48;
    // Within the far plane: zoomed out past it, the view was empty sky.
    this.orbit.minDistance = 2;
    this.orbit.maxDistance = 5000;
    this.orbit.addEventListener("change", onChange);
  }

  setMode(mode: CameraMode, car: THREE.Object3D): void {
    this.mode = mode;
    this.orbit.enabled = mode === "orbit";
    this.camera.up.set(0, 1, 0);
    if (mode === "orbit") {
      // Start where the chase camera would be, then leave the view to the mouse.
      this.placeChase(car);
      this.orbit.target.copy(car.position);
      this.lastTarget.copy(car.position);
      this.orbit.update();
    }
    this.follow(car);
    this.onChange();
  }

  resize(width: number, height: number): void {
    this.camera.aspect = width / Math.max(height, 1);
    this.camera.updateProjectionMatrix();
  }

  /** Moves the camera with the car it follows. */
  follow(car: THREE.Object3D): void {
    if (this.mode === "chase") {
      this.placeChase(car);
    } else if (this.mode === "orbit") {
      // Carry the camera along by the target's motion, keeping the user's angle and distance.
      this.v.subVectors(car.position, this.lastTarget);
      this.camera.position.add(this.v);
      this.orbit.target.copy(car.position);
      this.lastTarget.copy(car.position);
      this.orbit.update();
    } else {
      this.camera.up.set(0, 0, -1);
      this.camera.position.set(car.position.x, car.position.y + TOP_HEIGHT, car.position.z);
      this.camera.lookAt(car.position);
    }
  }

  private placeChase(car: THREE.Object3D): void {
    this.camera.up.set(0, 1, 0);
    this.camera.position.copy(CHASE_OFFSET).applyQuaternion(car.quaternion).add(car.position);
    this.camera.lookAt(this.v.copy(CHASE_LOOK).applyQuaternion(car.quaternion).add(car.position));
  }
}
