// The HUD's vehicle part for the followed car: engine speed, gear, and per wheel its slip
// ratio, slip angle, load (with a bar) and spin, as the recording has them (a car with a
// vehicle model only; hidden for the others). Test hooks: docs/viewer.md.
import { WHEEL_CHANNELS, type CarEllipsoid, type CarTrack, type VehicleTrack } from "./recording";

// Each channel's HUD column, in the recording's order: its header, test hook and decimals.
const COLUMNS = [
  { header: "slip", testid: "slip-ratio", digits: 3 },
  { header: "angle °", testid: "slip-angle", digits: 2 },
  { header: "load N", testid: "load", digits: 0 },
  { header: "spin rad/s", testid: "spin", digits: 1 },
];
const LOAD = 2; // the column with a bar
const REVERSE_GEAR = -1; // VehicleState::reverse_gear

/** A gear as a driver reads it: "R" for reverse, the number of a forward gear (the model has
 * no neutral: its gears are reverse and 1 to the top one). */
export function gearLabel(gear: number): string {
  return gear === REVERSE_GEAR ? "R" : String(gear);
}

// v to that many decimals, without the "-0.000" of a tiny negative value.
function fixed(v: number, digits: number): string {
  const text = v.toFixed(digits);
  return Number(text) === 0 ? (0).toFixed(digits) : text;
}

/** Wheel names as --telemetry's CSV has them: f/r for the axle, l/r for the side (+X is
 * left); "wheel K" when two would share a name. */
export function wheelNames(ellipsoids: CarEllipsoid[]): string[] {
  const names = ellipsoids
    .filter((e) => e.role !== "body")
    .map((e) => (e.role === "front_wheel" ? "f" : "r") + (e.center[0] > 0 ? "l" : "r"));
  return new Set(names).size === names.length ? names : names.map((_, k) => `wheel ${k}`);
}

function element(tag: "td" | "th" | "span", text: string, testid?: string): HTMLElement {
  const e = document.createElement(tag);
  e.textContent = text;
  if (testid) e.dataset.testid = testid;
  return e;
}

export class VehicleHud {
  private vehicle: VehicleTrack | null = null;
  private readonly rpm = element("span", "-", "hud-rpm");
  private readonly gear = element("span", "-", "hud-gear");
  private values: HTMLElement[] = []; // WHEEL_CHANNELS per wheel
  private loadBars: HTMLElement[] = [];
  private loadScale = 1; // N at a full bar: the car's largest recorded wheel load

  constructor(private readonly root: HTMLElement) {}

  /** Shows car's wheels (or hides the part for a car without a vehicle model). */
  show(car: CarTrack): void {
    this.vehicle = car.vehicle;
    this.root.hidden = !car.vehicle;
    if (!car.vehicle) return;
    const engine = document.createElement("div");
    engine.className = "engine";
    engine.append("rpm ", this.rpm, " gear ", this.gear);
    const table = document.createElement("table");
    const head = document.createElement("tr");
    head.append(element("th", ""), ...COLUMNS.map((c) => element("th", c.header)));
    table.append(head);
    this.values = [];
    this.loadBars = [];
    wheelNames(car.ellipsoids).forEach((name, w) => {
      const row = document.createElement("tr");
      row.append(element("th", name));
      COLUMNS.forEach((column, c) => {
        const value = element("span", "-", `hud-wheel-${w}-${column.testid}`);
        this.values.push(value);
        const td = document.createElement("td");
        td.append(value);
        if (c === LOAD) {
          const bar = document.createElement("div");
          bar.className = "load-bar";
          this.loadBars.push(bar);
          td.append(bar);
        }
        row.append(td);
      });
      table.append(row);
    });
    let largest = 0;
    for (let i = LOAD; i < car.vehicle.wheels.length; i += WHEEL_CHANNELS)
      largest = Math.max(largest, car.vehicle.wheels[i]);
    this.loadScale = largest > 0 ? largest : 1;
    this.root.replaceChildren(engine, table);
  }

  /** Fills in frame f's values. */
  update(f: number): void {
    const v = this.vehicle;
    if (!v) return;
    this.rpm.textContent = fixed(v.rpm[f], 0);
    this.gear.textContent = gearLabel(v.gear[f]);
    const base = f * v.wheelCount * WHEEL_CHANNELS;
    this.values.forEach((e, i) => (e.textContent = fixed(v.wheels[base + i], COLUMNS[i % WHEEL_CHANNELS].digits)));
    this.loadBars.forEach((bar, w) => {
      const load = v.wheels[base + w * WHEEL_CHANNELS + LOAD];
      bar.style.width = `${Math.min(100, Math.max(0, (100 * load) / this.loadScale)).toFixed(1)}%`;
    });
  }
}
