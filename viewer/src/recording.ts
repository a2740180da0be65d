// Parses a trackphys recording (JSON Lines, versions 1 and 2: docs/recording.md) into
// typed arrays, one set per car, so that a 10-minute drive stays a few tens of MB.

export type EllipsoidRole = "body" | "front_wheel" | "rear_wheel";

/** One ellipsoid of a car, in its body frame (+X left, +Y up, +Z forward). */
export interface CarEllipsoid {
  center: [number, number, number];
  semiAxes: [number, number, number];
  /** w, x, y, z: body from ellipsoid. */
  orientation: [number, number, number, number];
  role: EllipsoidRole;
}

/** What a car's vehicle model (gt, formula) reported, indexed by frame. */
export interface VehicleTrack {
  rpm: Float32Array;
  gear: Int32Array;
  /** WHEEL_CHANNELS per wheel per frame, wheels in the order of the car's wheel ellipsoids. */
  wheels: Float32Array;
  wheelCount: number;
}

/** A wheel's channels, in the recording's order: slip ratio, slip angle (deg), load (N), spin (rad/s). */
export const WHEEL_CHANNELS = 4;

/** Everything one car did, indexed by frame. */
export interface CarTrack {
  ellipsoids: CarEllipsoid[];
  /** Ellipsoids are a stand-in (version 1 recordings carry no car shapes). */
  shapeKnown: boolean;
  position: Float64Array; // 3 per frame
  quaternion: Float64Array; // 4 per frame, x, y, z, w (three.js order)
  speed: Float64Array; // m/s
  suspension: Float32Array; // one per ellipsoid per frame (m)
  inputs: Float32Array | null; // throttle, brake, steer per frame
  laps: Int32Array | null;
  contactStart: Uint32Array; // frame f's contacts are [contactStart[f], contactStart[f+1])
  contacts: Float32Array; // 8 per contact: point, normal, depth, ellipsoid (-1 unknown)
  vehicle: VehicleTrack | null;
}

/** A contact between cars: car a, car b (a < b), a's ellipsoid, b's, point, normal (moving a along it separates them), depth. */
export const CAR_CONTACT_WIDTH = 11;

export interface Recording {
  name: string;
  version: number;
  dt: number;
  scene: string;
  /** The track mesh's file name relative to the recording, or null. */
  trackMesh: string | null;
  frameCount: number;
  time: Float64Array;
  updateUs: Float32Array | null;
  /** Each frame's World::state_hash, 16 hex digits ("" where a frame has none). */
  hash: string[];
  cars: CarTrack[];
  carContactStart: Uint32Array; // frame f's contacts between cars are [carContactStart[f], carContactStart[f+1])
  carContacts: Float32Array; // CAR_CONTACT_WIDTH per contact
}

/** A recording that cannot be read; the message says where and why, for the page. */
export class RecordingError extends Error {}

// Version 1 recordings have no car shapes: each car is drawn as one ellipsoid of a
// typical car's size, marked as a stand-in.
const STAND_IN_CAR: CarEllipsoid[] = [
  { center: [0, 0, 0], semiAxes: [0.95, 0.5, 2.2], orientation: [1, 0, 0, 0], role: "body" },
];

type Json = Record<string, unknown>;

function fail(line: number, why: string): never {
  throw new RecordingError(line === 0 ? why : `line ${line}: ${why}`);
}

function isObject(value: unknown): value is Json {
  return typeof value === "object" && value !== null && !Array.isArray(value);
}

function numbers(value: unknown, count: number, line: number, what: string): number[] {
  if (!Array.isArray(value) || value.length !== count || !value.every(Number.isFinite))
    fail(line, `${what} must be ${count} finite numbers`);
  return value as number[];
}

function finite(value: unknown, line: number, what: string): number {
  if (typeof value !== "number" || !Number.isFinite(value)) fail(line, `${what} must be a finite number`);
  return value;
}

function parseEllipsoids(value: unknown, car: number): CarEllipsoid[] {
  const what = `car_ellipsoids[${car}]`;
  if (!Array.isArray(value) || value.length === 0) fail(1, `${what} must be a non-empty array`);
  return value.map((e: unknown, i: number) => {
    if (!isObject(e)) fail(1, `${what}[${i}] must be an object`);
    const role = e.role;
    if (role !== "body" && role !== "front_wheel" && role !== "rear_wheel")
      fail(1, `${what}[${i}].role must be body, front_wheel or rear_wheel`);
    const q = e.orientation === undefined ? [1, 0, 0, 0] : numbers(e.orientation, 4, 1, `${what}[${i}].orientation`);
    return {
      center: numbers(e.center, 3, 1, `${what}[${i}].center`) as [number, number, number],
      semiAxes: numbers(e.semi_axes, 3, 1, `${what}[${i}].semi_axes`) as [number, number, number],
      orientation: q as [number, number, number, number],
      role,
    };
  });
}

interface Header {
  version: number;
  dt: number;
  scene: string;
  trackMesh: string | null;
  shapes: CarEllipsoid[][];
}

function parseHeader(text: string): Header {
  let h: unknown;
  try {
    h = JSON.parse(text);
  } catch (e) {
    fail(0, `not a trackphys recording: its first line is not JSON (${(e as Error).message})`);
  }
  if (!isObject(h) || h.format !== "trackphys-recording")
    fail(0, 'not a trackphys recording: the first line must be a header with "format":"trackphys-recording"');
  const version = h.version;
  if (version !== 1 && version !== 2)
    fail(1, `unknown recording version ${JSON.stringify(version)} (this viewer reads 1 and 2)`);
  const dt = finite(h.dt, 1, "dt");
  const cars = h.cars;
  if (typeof cars !== "number" || !Number.isInteger(cars) || cars < 1) fail(1, "cars must be a whole number >= 1");
  let shapes: CarEllipsoid[][];
  let trackMesh: string | null = null;
  if (version === 2) {
    if (!Array.isArray(h.car_ellipsoids) || h.car_ellipsoids.length !== cars)
      fail(1, `car_ellipsoids must list the ellipsoids of all ${cars} cars`);
    shapes = h.car_ellipsoids.map(parseEllipsoids);
    if (h.track !== undefined) {
      if (!isObject(h.track) || typeof h.track.mesh !== "string") fail(1, "track.mesh must be a file name");
      trackMesh = h.track.mesh;
    }
  } else {
    shapes = Array.from({ length: cars }, () => STAND_IN_CAR);
  }
  return { version, dt, scene: typeof h.scene === "string" ? h.scene : "", trackMesh, shapes };
}

// Grows as frames arrive; trimmed to size at the end.
class Column<T extends Float64Array | Float32Array | Int32Array | Uint32Array> {
  data: T;
  length = 0;
  constructor(private readonly make: (n: number) => T) {
    this.data = make(1024);
  }
  push(...values: number[]): void {
    if (this.length + values.length > this.data.length) {
      const bigger = this.make(Math.max(this.data.length * 2, this.length + values.length));
      bigger.set(this.data);
      this.data = bigger;
    }
    for (const v of values) this.data[this.length++] = v;
  }
  trimmed(): T {
    return this.data.subarray(0, this.length) as T;
  }
}

class CarColumns {
  position = new Column((n) => new Float64Array(n));
  quaternion = new Column((n) => new Float64Array(n));
  speed = new Column((n) => new Float64Array(n));
  suspension = new Column((n) => new Float32Array(n));
  inputs = new Column((n) => new Float32Array(n));
  laps = new Column((n) => new Int32Array(n));
  contactStart = new Column((n) => new Uint32Array(n));
  contacts = new Column((n) => new Float32Array(n));
  rpm = new Column((n) => new Float32Array(n));
  gear = new Column((n) => new Int32Array(n));
  wheels = new Column((n) => new Float32Array(n));
  hasInputs = true;
  hasLaps = true;
  hasVehicle = true;
  readonly wheelCount: number;
  constructor(
    readonly ellipsoids: CarEllipsoid[],
    readonly shapeKnown: boolean,
  ) {
    this.contactStart.push(0);
    this.wheelCount = ellipsoids.filter((e) => e.role !== "body").length;
  }

  private addVehicle(vehicle: unknown, line: number, k: number): void {
    const what = `cars[${k}].vehicle`;
    if (!isObject(vehicle)) fail(line, `${what} must be an object`);
    this.rpm.push(finite(vehicle.rpm, line, `${what}.rpm`));
    const gear = vehicle.gear;
    if (typeof gear !== "number" || !Number.isInteger(gear)) fail(line, `${what}.gear must be a whole number`);
    this.gear.push(gear);
    const wheels = vehicle.wheels;
    if (!Array.isArray(wheels) || wheels.length !== this.wheelCount)
      fail(line, `${what}.wheels must list the car's ${this.wheelCount} wheels`);
    wheels.forEach((w: unknown, i: number) =>
      this.wheels.push(...numbers(w, WHEEL_CHANNELS, line, `${what}.wheels[${i}]`)),
    );
  }

  add(car: unknown, line: number, k: number, version: number): void {
    if (!isObject(car)) fail(line, `cars[${k}] must be an object`);
    const p = numbers(car.p, 3, line, `cars[${k}].p`);
    const q = numbers(car.q, 4, line, `cars[${k}].q`);
    this.position.push(p[0], p[1], p[2]);
    this.quaternion.push(q[1], q[2], q[3], q[0]);
    this.speed.push(finite(car.v, line, `cars[${k}].v`));
    const count = this.ellipsoids.length;
    const s = car.s === undefined ? new Array<number>(count).fill(0) : numbers(car.s, count, line, `cars[${k}].s`);
    this.suspension.push(...s);
    if (car.in === undefined) this.hasInputs = false;
    else this.inputs.push(...numbers(car.in, 3, line, `cars[${k}].in`));
    if (typeof car.lap === "number") this.laps.push(car.lap);
    else this.hasLaps = false;
    if (car.vehicle === undefined) this.hasVehicle = false;
    else this.addVehicle(car.vehicle, line, k);
    if (!Array.isArray(car.contacts)) fail(line, `cars[${k}].contacts must be an array`);
    const width = version === 1 ? 7 : 8;
    car.contacts.forEach((c: unknown, i: number) => {
      const values = numbers(c, width, line, `cars[${k}].contacts[${i}]`);
      this.contacts.push(...values);
      if (width === 7) this.contacts.push(-1);
    });
    this.contactStart.push(this.contacts.length / 8);
  }

  finish(): CarTrack {
    return {
      ellipsoids: this.ellipsoids,
      shapeKnown: this.shapeKnown,
      position: this.position.trimmed(),
      quaternion: this.quaternion.trimmed(),
      speed: this.speed.trimmed(),
      suspension: this.suspension.trimmed(),
      inputs: this.hasInputs ? this.inputs.trimmed() : null,
      laps: this.hasLaps ? this.laps.trimmed() : null,
      contactStart: this.contactStart.trimmed(),
      contacts: this.contacts.trimmed(),
      vehicle: this.hasVehicle
        ? {
            rpm: this.rpm.trimmed(),
            gear: this.gear.trimmed(),
            wheels: this.wheels.trimmed(),
            wheelCount: this.wheelCount,
          }
        : null,
    };
  }
}

/** A frame's car_contacts (absent: none touched) onto `into`, each checked to name two of the header's cars and their ellipsoids. */
function addCarContacts(value: unknown, shapes: CarEllipsoid[][], line: number, into: Column<Float32Array>): void {
  if (value === undefined) return;
  if (!Array.isArray(value)) fail(line, "car_contacts must be an array");
  const index = (x: number, below: number) => Number.isInteger(x) && x >= 0 && x < below;
  value.forEach((c: unknown, i: number) => {
    const what = `car_contacts[${i}]`;
    const v = numbers(c, CAR_CONTACT_WIDTH, line, what);
    const [a, b, ea, eb] = v;
    if (!(index(a, shapes.length) && index(b, shapes.length) && a < b))
      fail(line, `${what} must name two of the ${shapes.length} cars, the lower first`);
    if (!(index(ea, shapes[a].length) && index(eb, shapes[b].length)))
      fail(line, `${what} must name an ellipsoid of each car`);
    if (!(v[10] > 0)) fail(line, `${what}'s depth must be > 0`);
    into.push(...v);
  });
}

/** Reads a whole recording; throws RecordingError naming the line and the problem. */
export function parseRecording(text: string, name: string): Recording {
  const lines = text.split("\n");
  if (lines[lines.length - 1] === "") lines.pop();
  if (lines.length === 0) fail(0, "the file is empty");
  const header = parseHeader(lines[0]);
  const cars = header.shapes.map((shape) => new CarColumns(shape, header.version === 2));
  const time = new Column((n) => new Float64Array(n));
  const updateUs = new Column((n) => new Float32Array(n));
  let hasUpdateUs = true;
  const hash: string[] = [];
  const carContacts = new Column((n) => new Float32Array(n));
  const carContactStart = new Column((n) => new Uint32Array(n));
  carContactStart.push(0);
  for (let i = 1; i < lines.length; ++i) {
    const line = i + 1;
    let frame: unknown;
    try {
      frame = JSON.parse(lines[i]);
    } catch (e) {
      fail(line, `not JSON (${(e as Error).message})`);
    }
    if (!isObject(frame)) fail(line, "a frame must be an object");
    const t = finite(frame.t, line, "t");
    if (time.length > 0 && !(t > time.data[time.length - 1])) fail(line, "t must increase from frame to frame");
    time.push(t);
    hash.push(typeof frame.hash === "string" ? frame.hash : "");
    if (typeof frame.us === "number") updateUs.push(frame.us);
    else hasUpdateUs = false;
    if (!Array.isArray(frame.cars) || frame.cars.length !== cars.length)
      fail(line, `cars must list all ${cars.length} cars of the header`);
    frame.cars.forEach((car: unknown, k: number) => cars[k].add(car, line, k, header.version));
    addCarContacts(frame.car_contacts, header.shapes, line, carContacts);
    carContactStart.push(carContacts.length / CAR_CONTACT_WIDTH);
  }
  if (time.length === 0) fail(0, "the recording has a header but no frames");
  return {
    name,
    version: header.version,
    dt: header.dt,
    scene: header.scene,
    trackMesh: header.trackMesh,
    frameCount: time.length,
    time: time.trimmed(),
    updateUs: hasUpdateUs ? updateUs.trimmed() : null,
    hash,
    cars: cars.map((c) => c.finish()),
    carContactStart: carContactStart.trimmed(),
    carContacts: carContacts.trimmed(),
  };
}
