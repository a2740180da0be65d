// Hand-made recordings for the browser tests: several cars, cars touching, version 1, and
// malformed ones (a line cut off, a vehicle short of a wheel, a contact naming no car). Cars run along straight lines on flat
// ground, so every value the page shows can be computed here.

const DT = 0.01;

function header(version, cars, extra = {}) {
    return JSON.stringify({ format: "trackphys-recording", version, dt: DT, cars, scene: "hand-made", ...extra });
}

/** A body and four wheels, in the body frame. */
function carEllipsoids() {
    const wheel = (x, z, role) => ({
        center: [x, -0.15, z],
        semi_axes: [0.15, 0.35, 0.35],
        orientation: [1, 0, 0, 0],
        role,
    });
    return [
        wheel(0.9, 1.45, "front_wheel"),
        wheel(-0.9, 1.45, "front_wheel"),
        wheel(0.9, -1.35, "rear_wheel"),
        wheel(-0.9, -1.35, "rear_wheel"),
        { center: [0, 0.2, 0], semi_axes: [0.9, 0.4, 2.0], orientation: [1, 0, 0, 0], role: "body" },
    ];
}

/** Car k's speed (m/s) at time t: each car its own constant acceleration. */
export function handMadeSpeed(k, t) {
    return 5 + (k + 1) * 2 * t;
}

function position(k, t) {
    // Driving along +Z, 60 m apart sideways, so that a camera following one sees no other.
    return [k * 60, 0.5, 5 * t + (k + 1) * t * t];
}

function frameCar(k, t, version) {
    const p = position(k, t);
    const car = { p, q: [1, 0, 0, 0], v: handMadeSpeed(k, t), contacts: [] };
    const contact = [p[0], 0, p[2], 0, 1, 0, 0.004 + 0.002 * k];
    car.contacts.push(version === 1 ? contact : [...contact, 4]);
    if (version === 2) {
        car.s = [0.01, 0.01, 0.01, 0.01, 0];
        car.in = [1, 0, 0];
        car.lap = 0;
    }
    return car;
}

function frames(cars, count, version) {
    const lines = [];
    for (let i = 1; i <= count; ++i) {
        const t = i * DT;
        const frame = { t, hash: i.toString(16).padStart(16, "0") };
        if (version === 2) frame.us = 50 + (i % 7);
        frame.cars = Array.from({ length: cars }, (_, k) => frameCar(k, t, version));
        lines.push(JSON.stringify(frame));
    }
    return lines;
}

export function multiCarRecording(cars, seconds) {
    const shapes = Array.from({ length: cars }, carEllipsoids);
    return (
        [header(2, cars, { car_ellipsoids: shapes }), ...frames(cars, Math.round(seconds / DT), 2)].join("\n") + "\n"
    );
}

export function versionOneRecording(seconds) {
    return [header(1, 1), ...frames(1, Math.round(seconds / DT), 1)].join("\n") + "\n";
}

/** One car with a vehicle model over `seconds`: first gear for the first half, then reverse
 * (VehicleState::reverse_gear, -1). */
export function reversingRecording(seconds) {
    const [head, ...lines] = multiCarRecording(1, seconds).trimEnd().split("\n");
    const withGears = lines.map((line) => {
        const f = JSON.parse(line);
        const gear = f.t <= seconds / 2 ? 1 : -1;
        f.cars[0].vehicle = { rpm: 1500, gear, wheels: [0, 1, 2, 3].map(() => [0, 0, 3000, 10]) };
        return JSON.stringify(f);
    });
    return [head, ...withGears].join("\n") + "\n";
}

/** One car whose first frame's vehicle lists three of its four wheels (line 2). */
export function vehicleMissingAWheel() {
    const [head, frame] = multiCarRecording(1, 0.01).trimEnd().split("\n");
    const f = JSON.parse(frame);
    f.cars[0].vehicle = { rpm: 3000, gear: 1, wheels: [0, 1, 2].map(() => [0, 0, 3000, 10]) };
    return `${head}\n${JSON.stringify(f)}\n`;
}

/** Two cars side by side, car 1 2.2 m to the left of car 0, whose bodies touch from 0.3 s
 * to 0.6 s: each of those frames lists one contact between them, 2 cm deep, which `without`
 * leaves out (the same recording otherwise). */
export function sideBySideRecording(seconds, { without = false } = {}) {
    const [head, ...lines] = multiCarRecording(2, seconds).trimEnd().split("\n");
    const touching = lines.map((line) => {
        const f = JSON.parse(line);
        const [a, b] = f.cars;
        b.p = [a.p[0] + 2.2, a.p[1], a.p[2]];
        if (!without && f.t >= 0.3 && f.t <= 0.6)
            f.car_contacts = [[0, 1, 4, 4, a.p[0] + 1.1, a.p[1], a.p[2], -1, 0, 0, 0.02]];
        return JSON.stringify(f);
    });
    return [head, ...touching].join("\n") + "\n";
}

/** Two cars side by side at `speed` (m/s) along +Z, car 1 2.2 m to the left of car 0, their
 * bodies touching all along: every frame lists each car's contact with the road under its
 * centre and one between them, 2 cm deep, halfway; `without` leaves all contacts out. */
export function fastPairRecording(speed, seconds, { without = false } = {}) {
    const [head, ...lines] = multiCarRecording(2, seconds).trimEnd().split("\n");
    const fast = lines.map((line) => {
        const f = JSON.parse(line);
        f.cars.forEach((car, k) => {
            car.p = [2.2 * k, 0.5, speed * f.t];
            car.v = speed;
            car.contacts = without ? [] : [[car.p[0], 0, car.p[2], 0, 1, 0, 0.004, 4]];
        });
        if (!without) f.car_contacts = [[0, 1, 4, 4, 1.1, 0.5, speed * f.t, -1, 0, 0, 0.02]];
        return JSON.stringify(f);
    });
    return [head, ...fast].join("\n") + "\n";
}

/** Two cars whose first frame lists a contact between car 0 and a car 2 (line 2). */
export function carContactNamingNoCar() {
    const [head, frame] = multiCarRecording(2, 0.01).trimEnd().split("\n");
    const f = JSON.parse(frame);
    f.car_contacts = [[0, 2, 0, 0, 0, 0, 0, 1, 0, 0, 0.01]];
    return `${head}\n${JSON.stringify(f)}\n`;
}

/** A good header and first frame, then a frame cut off in the middle (line 3). */
export function malformedRecording() {
    const good = multiCarRecording(1, 0.01).trimEnd();
    return `${good}\n{"t":0.02,"hash":"0000000000000002","cars":[{"p":[0,0.5\n`;
}
