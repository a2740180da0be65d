// One recording on screen: the scene (track, cars, contacts), the cameras, the clock, the
// HUD, the car list and the charts, kept in step with each other.
import * as THREE from "three";
import { CAMERA_KEYS, CameraRig, type CameraMode } from "./cameras";
import { carColour, CarView } from "./car_view";
import { Chart } from "./chart";
import { ContactsView } from "./contacts_view";
import type { Layout } from "./layout";
import { Playback } from "./playback";
import { CAR_CONTACT_WIDTH, type Recording } from "./recording";
import { lerpAt, sampleAt, type Sample } from "./sample";
import { addLights } from "./track_view";
import { VehicleHud } from "./vehicle_hud";

export class ReplayView {
  private readonly scene = new THREE.Scene();
  private readonly cars: CarView[];
  /** Each car's posed group, which the contacts follow. */
  private readonly carGroups: THREE.Object3D[];
  private readonly contacts: ContactsView;
  private readonly rig: CameraRig;
  readonly playback: Playback;
  private readonly speedChart: Chart;
  private readonly updateChart: Chart;
  private readonly vehicleHud: VehicleHud;
  private selected = 0;
  private dirty = true;
  private lastWall = 0;
  private frameHandle = 0;
  private readonly onResize = () => this.resize();
  private readonly onKey = (e: KeyboardEvent) => this.key(e);

  constructor(
    private readonly recording: Recording,
    track: THREE.Object3D | null,
    private readonly renderer: THREE.WebGLRenderer,
    private readonly ui: Layout,
  ) {
    this.scene.background = new THREE.Color(0x8fb4dc);
    addLights(this.scene);
    if (track) this.scene.add(track);
    else this.scene.add(new THREE.GridHelper(2000, 200, 0x555555, 0x777777));
    this.cars = recording.cars.map((car, k) => new CarView(car, k));
    this.carGroups = this.cars.map((car) => car.group);
    this.scene.add(...this.carGroups);
    this.contacts = new ContactsView(recording);
    this.scene.add(this.contacts.group);
    this.rig = new CameraRig(renderer.domElement, () => (this.dirty = true));
    const time = recording.time;
    this.playback = new Playback(time[0], time[time.length - 1], recording.dt);

    this.vehicleHud = new VehicleHud(ui.vehicle);
    const seek = (t: number) => this.seek(t);
    this.speedChart = new Chart(time, seek);
    this.updateChart = new Chart(time, seek);
    ui.charts.replaceChildren(this.speedChart.canvas, this.updateChart.canvas);
    this.updateChart.show(
      recording.updateUs ? { label: "update time", unit: "us", colour: "#f0a23a", values: recording.updateUs } : null,
    );
    ui.title.textContent = `${recording.name} — ${recording.scene || "recording"} (v${recording.version})`;
    ui.scrub.min = String(this.playback.start);
    ui.scrub.max = String(this.playback.end);
    ui.scrub.oninput = () => this.seek(Number(ui.scrub.value));
    ui.play.onclick = () => this.togglePlay();
    ui.back.onclick = () => this.step(-1);
    ui.forward.onclick = () => this.step(1);
    ui.rate.value = "1";
    ui.rate.onchange = () => (this.playback.rate = Number(ui.rate.value));
    this.buildCarList();
    this.selectCar(0);
    this.setCamera("chase");
    window.addEventListener("resize", this.onResize);
    window.addEventListener("keydown", this.onKey);
    this.resize();
  }

  /** Stops drawing and lets go of the scene (before another recording replaces it). */
  dispose(): void {
    cancelAnimationFrame(this.frameHandle);
    window.removeEventListener("resize", this.onResize);
    window.removeEventListener("keydown", this.onKey);
    this.scene.traverse((o) => {
      if (o instanceof THREE.Mesh || o instanceof THREE.LineSegments || o instanceof THREE.Points) o.geometry.dispose();
    });
  }

  /** Draws the first frame, then keeps drawing; resolves once the first frame is drawn. */
  start(): Promise<void> {
    this.draw();
    return new Promise((resolve) => {
      const loop = (wall: number) => {
        const seconds = this.lastWall ? (wall - this.lastWall) / 1000 : 0;
        this.lastWall = wall;
        if (this.playback.playing) {
          this.playback.advance(Math.min(seconds, 0.25));
          this.dirty = true;
        }
        if (this.dirty) this.draw();
        this.frameHandle = requestAnimationFrame(loop);
      };
      this.frameHandle = requestAnimationFrame(loop);
      resolve();
    });
  }

  seek(t: number): void {
    this.playback.seek(t);
    this.dirty = true;
    this.updateHud(sampleAt(this.recording.time, this.playback.t));
  }

  pause(): void {
    this.playback.playing = false;
    this.dirty = true;
  }

  carCount(): number {
    return this.cars.length;
  }

  selectCar(k: number): void {
    this.selected = k;
    for (const button of this.ui.cars.querySelectorAll("button"))
      button.setAttribute("aria-pressed", String(button.dataset.car === String(k)));
    const car = this.recording.cars[k];
    const kmh = Float32Array.from(car.speed, (v) => v * 3.6);
    this.speedChart.show({ label: `car ${k} speed`, unit: "km/h", colour: "#5fb0ff", values: kmh });
    if (this.rig.mode === "orbit") this.rig.setMode("orbit", this.cars[k].group);
    this.vehicleHud.show(car);
    this.dirty = true;
    this.updateHud(sampleAt(this.recording.time, this.playback.t));
  }

  private setCamera(mode: CameraMode): void {
    this.rig.setMode(mode, this.cars[this.selected].group);
    this.ui.camera.textContent = mode;
  }

  private togglePlay(): void {
    this.playback.toggle();
    this.lastWall = 0;
    this.dirty = true;
  }

  private step(n: number): void {
    this.playback.step(n);
    this.dirty = true;
  }

  private key(e: KeyboardEvent): void {
    if (e.key === " ") this.togglePlay();
    else if (e.key === "ArrowRight") this.step(e.shiftKey ? 100 : 1);
    else if (e.key === "ArrowLeft") this.step(e.shiftKey ? -100 : -1);
    else if (CAMERA_KEYS[e.key]) this.setCamera(CAMERA_KEYS[e.key]);
    else return;
    e.preventDefault();
  }

  private buildCarList(): void {
    const buttons = this.recording.cars.map((_, k) => {
      const button = document.createElement("button");
      button.dataset.car = String(k);
      button.dataset.testid = `car-${k}`;
      const swatch = document.createElement("span");
      swatch.className = "swatch";
      swatch.style.background = `#${carColour(k).toString(16).padStart(6, "0")}`;
      button.append(swatch, `car ${k}`);
      button.onclick = () => this.selectCar(k);
      return button;
    });
    this.ui.cars.replaceChildren(...buttons);
    this.ui.cars.hidden = buttons.length < 2;
  }

  private resize(): void {
    const { clientWidth: width, clientHeight: height } = this.ui.view;
    this.renderer.setSize(width, height, false);
    this.rig.resize(width, height);
    this.speedChart.draw();
    this.updateChart.draw();
    this.dirty = true;
  }

  private draw(): void {
    const s = sampleAt(this.recording.time, this.playback.t);
    for (const car of this.cars) car.pose(s);
    this.contacts.update(s, this.carGroups);
    this.rig.follow(this.cars[this.selected].group);
    this.renderer.render(this.scene, this.rig.camera);
    this.updateHud(s);
    this.dirty = false;
  }

  /** How many of frame f's contacts between cars the followed car is in. */
  private carContactsOfSelected(f: number): number {
    const r = this.recording;
    let n = 0;
    for (let c = r.carContactStart[f]; c < r.carContactStart[f + 1]; ++c) {
      const at = c * CAR_CONTACT_WIDTH;
      if (r.carContacts[at] === this.selected || r.carContacts[at + 1] === this.selected) ++n;
    }
    return n;
  }

  private updateHud(s: Sample): void {
    const r = this.recording;
    const car = r.cars[this.selected];
    const ui = this.ui;
    const nearest = s.fraction < 0.5 ? s.index : s.index + 1;
    ui.time.textContent = this.playback.t.toFixed(2);
    ui.speed.textContent = (lerpAt(car.speed, 1, 0, s) * 3.6).toFixed(1);
    ui.lap.textContent = car.laps ? String(car.laps[nearest] + 1) : "-";
    ui.updateUs.textContent = r.updateUs ? r.updateUs[nearest].toFixed(1) : "-";
    ui.inputs.textContent = car.inputs
      ? Array.from(car.inputs.subarray(nearest * 3, nearest * 3 + 3), (v) => v.toFixed(2)).join(" ")
      : "-";
    ui.hash.textContent = r.hash[nearest] || "-";
    ui.contacts.textContent = String(car.contactStart[nearest + 1] - car.contactStart[nearest]);
    ui.carContacts.textContent = String(this.carContactsOfSelected(nearest));
    this.vehicleHud.update(nearest);
    ui.play.textContent = this.playback.playing ? "❚❚" : "▶";
    ui.scrub.value = String(this.playback.t);
    ui.clock.textContent = `${this.playback.t.toFixed(2)} / ${this.playback.end.toFixed(2)} s`;
    this.speedChart.setCursor(nearest);
    this.updateChart.setCursor(nearest);
  }
}
