// The replay viewer in a real browser (docs/testing.md, "Browser tests"): Debian's
// chromium, headless, WebGL through SwiftShader, driven by playwright-core.
//
//   node browser_test.mjs --trackphys BIN --demo RECORDING.jsonl --work DIR [--screenshot PNG]
//
// RECORDING is the demo's drive (one lap of the seed-7 track); the page is made from it
// here with `trackphys view`, as are pages of hand-made recordings, of a 10-minute one
// (the lap repeated) and of a gt car's drive and a race of gt cars, all written into DIR.
// Prints each check (ok / FAIL) and the load and frame times; exits 1 if any check failed.
import assert from "node:assert/strict";
import { execFileSync } from "node:child_process";
import { copyFileSync, mkdirSync, readFileSync, writeFileSync } from "node:fs";
import { dirname, join } from "node:path";
import { parseArgs } from "node:util";
import {
    canvasPixels,
    distinctColours,
    dropFiles,
    hud,
    vehicleHud,
    launchBrowser,
    meanDifference,
    openGuardedPage,
    waitReady,
} from "./page_probe.mjs";
import {
    carContactNamingNoCar,
    fastPairRecording,
    handMadeSpeed,
    malformedRecording,
    multiCarRecording,
    reversingRecording,
    sideBySideRecording,
    vehicleMissingAWheel,
    versionOneRecording,
} from "./recordings.mjs";

const { values: args } = parseArgs({
    options: {
        trackphys: { type: "string" },
        demo: { type: "string" },
        work: { type: "string" },
        screenshot: { type: "string" },
    },
});
assert.ok(args.trackphys && args.demo && args.work, "usage: --trackphys BIN --demo RECORDING --work DIR");
mkdirSync(args.work, { recursive: true });

function makePage(recording, name) {
    const page = join(args.work, `${name}.html`);
    execFileSync(args.trackphys, ["view", recording, "--out", page], { stdio: "pipe" });
    return page;
}

function writeRecording(name, text) {
    const file = join(args.work, `${name}.jsonl`);
    writeFileSync(file, text);
    return file;
}

// The demo recording's speed (km/h) of car 0 at the update that ends at t.
const demoLines = readFileSync(args.demo, "utf8").trimEnd().split("\n");
const demoDt = JSON.parse(demoLines[0]).dt;
function demoSpeedKmh(t) {
    const frame = JSON.parse(demoLines[Math.round(t / demoDt)]);
    assert.ok(Math.abs(frame.t - t) < demoDt / 2, `the demo's frame for ${t} s is at ${frame.t} s`);
    return frame.cars[0].v * 3.6;
}

// A recording's frame at the update that ends at t, checked to be that one.
function frameAt(lines, t) {
    const dt = JSON.parse(lines[0]).dt;
    const frame = JSON.parse(lines[Math.round(t / dt)]);
    assert.ok(Math.abs(frame.t - t) < dt / 2, `the frame for ${t} s is at ${frame.t} s`);
    return frame;
}

// Runs `trackphys command... --record DIR/name.jsonl`; returns the recording's path.
function record(name, command) {
    const file = join(args.work, `${name}.jsonl`);
    execFileSync(args.trackphys, [...command, "--record", file], { stdio: "pipe" });
    return file;
}

// The HUD must show car k's vehicle at t as the recording has it, to the digits it shows.
async function expectVehicle(page, lines, k, t, what) {
    const want = frameAt(lines, t).cars[k].vehicle;
    assert.ok(want, `${what}: the recording has no vehicle for car ${k}`);
    const shown = await vehicleHud(page);
    assert.ok(shown.shown, `${what}: the HUD's vehicle part is hidden`);
    const close = (got, expected, digits) => Math.abs(got - expected) <= 0.5 * 10 ** -digits + 1e-6;
    assert.ok(close(shown.rpm, want.rpm, 0), `${what}: rpm ${shown.rpm}, recorded ${want.rpm}`);
    assert.equal(shown.gear, want.gear === -1 ? "R" : String(want.gear), `${what}: gear ${want.gear}`);
    assert.equal(shown.wheels.length, want.wheels.length, `${what}: wheels`);
    const digits = [3, 2, 0, 1]; // slip ratio, slip angle, load, spin as the HUD rounds them
    want.wheels.forEach((wheel, w) =>
        wheel.forEach((value, c) =>
            assert.ok(
                close(shown.wheels[w][c], value, digits[c]),
                `${what}: wheel ${w} channel ${c} shows ${shown.wheels[w][c]}, recorded ${value}`,
            ),
        ),
    );
}

const nextFrames = (page) =>
    page.evaluate(() => new Promise((r) => requestAnimationFrame(() => requestAnimationFrame(r))));

async function setHash(page, hash) {
    await page.evaluate((h) => (location.hash = h), hash);
    await nextFrames(page);
}

function expectSpeed(shown, expected, what) {
    assert.ok(
        Math.abs(shown - expected) <= 1,
        `${what}: the HUD shows ${shown} km/h, the recording ${expected.toFixed(2)} km/h`,
    );
}

/** Share of the central pixels whose hue is within 20 degrees of rgb's (and saturated). */
function centreHueShare(pixels, w, h, rgb) {
    const hue = (r, g, b) => {
        const max = Math.max(r, g, b);
        const min = Math.min(r, g, b);
        if (max - min < 40) return null; // grey: road, grid, wheels
        const d = max - min;
        const x = max === r ? (g - b) / d : max === g ? 2 + (b - r) / d : 4 + (r - g) / d;
        return (((x * 60) % 360) + 360) % 360;
    };
    const want = hue(...rgb);
    let hits = 0;
    let total = 0;
    for (let y = Math.floor(h * 0.3); y < h * 0.8; ++y) {
        for (let x = Math.floor(w * 0.3); x < w * 0.7; ++x) {
            const i = (y * w + x) * 4;
            const got = hue(pixels[i], pixels[i + 1], pixels[i + 2]);
            total++;
            if (got !== null && Math.min(Math.abs(got - want), 360 - Math.abs(got - want)) < 20) hits++;
        }
    }
    return hits / total;
}

let failures = 0;
async function check(name, body) {
    try {
        await body();
        console.log(`ok   ${name}`);
    } catch (error) {
        failures++;
        console.log(`FAIL ${name}\n     ${String(error.message).split("\n").join("\n     ")}`);
    }
}

async function withPage(browser, body) {
    const guarded = await openGuardedPage(browser);
    try {
        await body(guarded);
        assert.deepEqual(guarded.problems, [], "console errors, exceptions or requests");
    } finally {
        await guarded.context.close();
    }
}

const browser = await launchBrowser();
const demoPage = makePage(args.demo, "demo");
console.log(`demo page    ${demoPage}: ${(readFileSync(demoPage).length / 1e6).toFixed(1)} MB`);

await check("the demo's replay is ready within 10 s, with no error and no request", () =>
    withPage(browser, async ({ page, open }) => {
        const start = await open(demoPage);
        const ms = await waitReady(page, start);
        const phases = await page.evaluate(() =>
            performance
                .getEntriesByType("measure")
                .map((m) => `${m.name.replace("trackphys ", "")} ${Math.round(m.duration)} ms`),
        );
        console.log(`load time    ${ms} ms to the ready flag (${phases.join(", ")})`);
    }),
);

await check("the canvas is not blank and frames at different times differ", () =>
    withPage(browser, async ({ page, open }) => {
        await waitReady(page, await open(demoPage, "#t=10"));
        const early = await canvasPixels(page);
        await setHash(page, "#t=45");
        const late = await canvasPixels(page);
        assert.ok(distinctColours(early) > 100, `only ${distinctColours(early)} colours at 10 s`);
        assert.ok(meanDifference(early, late) > 3, `frames at 10 s and 45 s differ by ${meanDifference(early, late)}`);
    }),
);

await check("#t= seeks on a fresh load and on a hash change, showing the recorded speed", () =>
    withPage(browser, async ({ page, open }) => {
        await waitReady(page, await open(demoPage, "#t=30"));
        let shown = await hud(page);
        assert.equal(shown.time, 30);
        expectSpeed(shown.speed, demoSpeedKmh(30), "fresh load at 30 s");
        const frame = frameAt(demoLines, 30);
        assert.equal(shown.hash, frame.hash, "the state hash at 30 s");
        assert.equal(shown.inputs, frame.cars[0].in.map((v) => v.toFixed(2)).join(" "), "the inputs at 30 s");
        await setHash(page, "#t=61.37");
        shown = await hud(page);
        assert.equal(shown.time, 61.37);
        expectSpeed(shown.speed, demoSpeedKmh(61.37), "hash change to 61.37 s");
        await nextFrames(page);
        assert.equal((await hud(page)).time, 61.37, "a seek pauses");
    }),
);

await check("playing moves time on; keys step and switch cameras (frame times printed)", () =>
    withPage(browser, async ({ page, open }) => {
        await waitReady(page, await open(demoPage, "#t=5"));
        await page.keyboard.press("Space");
        const stamps = await page.evaluate(
            () =>
                new Promise((resolve) => {
                    const seen = [];
                    const tick = (t) => {
                        seen.push(t);
                        if (t - seen[0] < 4000) requestAnimationFrame(tick);
                        else resolve(seen);
                    };
                    requestAnimationFrame(tick);
                }),
        );
        await page.keyboard.press("Space");
        const played = (await hud(page)).time;
        assert.ok(played > 6, `after 4 s of playing the time is ${played} s`);
        const frames = stamps
            .slice(1)
            .map((t, i) => t - stamps[i])
            .sort((a, b) => a - b);
        const at = (q) => frames[Math.min(frames.length - 1, Math.floor(q * frames.length))].toFixed(1);
        const mean = frames.reduce((a, b) => a + b, 0) / frames.length;
        console.log(
            `frame times  ${frames.length} frames while playing: mean ${mean.toFixed(1)} ms, p50 ${at(0.5)}, p95 ${at(0.95)}, max ${at(1)} ms`,
        );
        await page.keyboard.press("ArrowRight");
        await nextFrames(page);
        assert.equal((await hud(page)).time, Math.round(played * 100 + 1) / 100, "→ steps one update");
        for (const [key, camera] of [
            ["3", "top"],
            ["2", "orbit"],
            ["1", "chase"],
        ]) {
            await page.keyboard.press(key);
            assert.equal((await hud(page)).camera, camera, `key ${key}`);
        }
        if (args.screenshot) {
            await setHash(page, "#t=20");
            await page.screenshot({ path: args.screenshot });
            console.log(`screenshot   ${args.screenshot}`);
        }
    }),
);

await check("in a 640 x 400 window the HUD leaves the followed car in view", () =>
    withPage(browser, async ({ page, open }) => {
        await page.setViewportSize({ width: 640, height: 400 });
        await waitReady(page, await open(demoPage, "#t=20"));
        const box = (selector) => page.locator(selector).boundingBox();
        const hudBox = await box('[data-testid="hud"]');
        const view = await box("#view");
        const [cx, cy] = [view.x + view.width / 2, view.y + view.height / 2];
        const covers =
            cx >= hudBox.x && cx <= hudBox.x + hudBox.width && cy >= hudBox.y && cy <= hudBox.y + hudBox.height;
        assert.ok(
            !covers,
            `the HUD (${JSON.stringify(hudBox)}) covers the view's centre (${cx}, ${cy}), where the car is`,
        );
        assert.ok(!(await page.locator("#help").isVisible()), "the help line is shown in a small window");
    }),
);

await check("a gt drive's HUD shows its rpm, gear and wheels from the file; the demo's has none", () =>
    withPage(browser, async ({ page, open }) => {
        const drive = record("gt_drive", ["drive", "--car-preset", "gt", "--seconds", "6"]);
        const lines = readFileSync(drive, "utf8").trimEnd().split("\n");
        await waitReady(page, await open(makePage(drive, "gt_drive"), "#t=1.5"));
        await expectVehicle(page, lines, 0, 1.5, "gt drive at 1.5 s");
        await setHash(page, "#t=5.25");
        await expectVehicle(page, lines, 0, 5.25, "gt drive at 5.25 s");
        await page.screenshot({ path: join(args.work, "gt_drive.png") });
        await waitReady(page, await open(demoPage, "#t=30"));
        assert.equal((await vehicleHud(page)).shown, false, "the arcade demo shows a vehicle part");
    }),
);

await check("a car in reverse shows gear R, a forward gear its number", () =>
    withPage(browser, async ({ page, open }) => {
        const reversing = makePage(writeRecording("reversing", reversingRecording(1)), "reversing");
        await waitReady(page, await open(reversing, "#t=0.3"));
        assert.equal((await vehicleHud(page)).gear, "1", "forwards at 0.3 s");
        await setHash(page, "#t=0.8");
        assert.equal((await vehicleHud(page)).gear, "R", "in reverse at 0.8 s");
    }),
);

await check("a race of gt cars records every car's vehicle; the HUD follows the car picked", () =>
    withPage(browser, async ({ page, open }) => {
        const scenario = join(args.work, "gt_race.json");
        writeFileSync(scenario, JSON.stringify({ track: { seed: 7 }, car: { model: "gt" }, cars: 2, seconds: 4 }));
        const race = record("gt_race", ["race", "--scenario", scenario]);
        const lines = readFileSync(race, "utf8").trimEnd().split("\n");
        await waitReady(page, await open(makePage(race, "gt_race"), "#t=3&car=1"));
        await expectVehicle(page, lines, 1, 3, "race, car 1 at 3 s");
        await page.locator('[data-testid="car-list"] button').nth(0).click();
        await nextFrames(page);
        await expectVehicle(page, lines, 0, 3, "race, car 0 picked at 3 s");
    }),
);

await check("a recording of three cars lists them all and follows the one picked", () =>
    withPage(browser, async ({ page, open }) => {
        const multi = makePage(writeRecording("three_cars", multiCarRecording(3, 5)), "three_cars");
        await waitReady(page, await open(multi, "#t=2&car=2"));
        const buttons = page.locator('[data-testid="car-list"] button');
        assert.equal(await buttons.count(), 3);
        assert.ok(await page.locator('[data-testid="car-list"]').isVisible(), "the car list is shown");
        expectSpeed((await hud(page)).speed, handMadeSpeed(2, 2) * 3.6, "car 2 at 2 s");
        const yellow = centreHueShare(await canvasPixels(page), 96, 54, [0xe0, 0xb2, 0x1a]);
        assert.ok(yellow > 0.05, `car 2 (yellow) fills ${(yellow * 100).toFixed(1)}% of the view's centre`);
        await buttons.nth(0).click();
        await nextFrames(page);
        expectSpeed((await hud(page)).speed, handMadeSpeed(0, 2) * 3.6, "car 0 picked at 2 s");
        const pixels = await canvasPixels(page);
        const red = centreHueShare(pixels, 96, 54, [0xd8, 0x43, 0x2e]);
        const stillYellow = centreHueShare(pixels, 96, 54, [0xe0, 0xb2, 0x1a]);
        assert.ok(
            red > 0.05 && stillYellow < 0.01,
            `after picking car 0: red ${(red * 100).toFixed(1)}%, yellow ${(stillYellow * 100).toFixed(1)}%`,
        );
    }),
);

await check("contacts between cars show in the HUD of both cars and on the canvas", () =>
    withPage(browser, async ({ page, open }) => {
        const touching = makePage(writeRecording("side_by_side", sideBySideRecording(1)), "side_by_side");
        const never = makePage(
            writeRecording("side_by_side_apart", sideBySideRecording(1, { without: true })),
            "side_by_side_apart",
        );
        const pixels = () => canvasPixels(page, 384, 216);
        await waitReady(page, await open(touching, "#t=0.45"));
        assert.equal((await hud(page)).carContacts, 1, "car 0 at 0.45 s");
        const drawn = await pixels();
        await setHash(page, "#t=0.1");
        assert.equal((await hud(page)).carContacts, 0, "car 0 at 0.1 s");
        const before = await pixels();
        await waitReady(page, await open(never, "#t=0.45"));
        assert.equal((await hud(page)).carContacts, 0, "the recording without them at 0.45 s");
        const difference = meanDifference(drawn, await pixels());
        assert.ok(difference > 0, "the contact between the cars is not drawn");
        await setHash(page, "#t=0.1");
        assert.equal(meanDifference(before, await pixels()), 0, "the pages differ where no cars touch");
        await waitReady(page, await open(touching, "#t=0.45&car=1"));
        assert.equal((await hud(page)).carContacts, 1, "car 1 at 0.45 s");
        console.log(`car contact  drawn: the canvas differs by ${difference.toFixed(3)} per channel`);
    }),
);

await check("between updates the contacts go with the cars (1080 km/h, 3 m an update)", () =>
    withPage(browser, async ({ page, open }) => {
        const speed = 300;
        const drawn = makePage(writeRecording("fast_pair", fastPairRecording(speed, 1)), "fast_pair");
        const none = makePage(
            writeRecording("fast_pair_none", fastPairRecording(speed, 1, { without: true })),
            "fast_pair_none",
        );
        const [w, h] = [384, 216];
        // The mean position of the pixels the contacts change: the page with them against
        // the same recording without them, at time t.
        const contactsAt = async (t) => {
            await waitReady(page, await open(drawn, `#t=${t}`));
            const shown = await canvasPixels(page, w, h);
            await waitReady(page, await open(none, `#t=${t}`));
            const bare = await canvasPixels(page, w, h);
            let [sx, sy, n] = [0, 0, 0];
            for (let i = 0; i < shown.length; i += 4) {
                const change =
                    Math.abs(shown[i] - bare[i]) +
                    Math.abs(shown[i + 1] - bare[i + 1]) +
                    Math.abs(shown[i + 2] - bare[i + 2]);
                if (change < 60) continue;
                sx += (i / 4) % w;
                sy += Math.floor(i / 4 / w);
                n++;
            }
            assert.ok(n > 0, `no contact drawn at ${t} s`);
            return [sx / n, sy / n];
        };
        // At an update, and 0.45 of the way to the next one, whose contacts are still the
        // nearest: the chase camera follows car 0, so contacts that go with the cars stay put
        // on the screen, where contacts left at the update would be 1.35 m behind.
        const [x0, y0] = await contactsAt(0.5);
        const [x1, y1] = await contactsAt(0.5045);
        const moved = Math.hypot(x1 - x0, y1 - y0);
        console.log(`fast contacts moved ${moved.toFixed(2)} px on the screen between updates`);
        assert.ok(moved < 2, `the contacts moved ${moved.toFixed(1)} px from (${x0.toFixed(1)}, ${y0.toFixed(1)})`);
    }),
);

await check("a version-1 recording opens; a dropped recording replaces it", () =>
    withPage(browser, async ({ page, open }) => {
        const v1 = makePage(writeRecording("version_1", versionOneRecording(3)), "version_1");
        await waitReady(page, await open(v1, "#t=1.5"));
        expectSpeed((await hud(page)).speed, handMadeSpeed(0, 1.5) * 3.6, "version 1 at 1.5 s");
        assert.equal(await page.locator('[data-testid="car-list"] button').count(), 1);
        await dropFiles(page, [["dropped.jsonl", multiCarRecording(2, 1)]]);
        await page.waitForFunction(() => document.querySelectorAll('[data-testid="car-list"] button').length === 2);
        await waitReady(page, Date.now());
    }),
);

await check("a recording dropped with its .glb track shows the track", () =>
    withPage(browser, async ({ page, open }) => {
        const v1 = makePage(writeRecording("version_1", versionOneRecording(3)), "version_1");
        await waitReady(page, await open(v1));
        const empty = distinctColours(await canvasPixels(page));
        const mesh = JSON.parse(demoLines[0]).track.mesh;
        const glb = readFileSync(join(dirname(args.demo), mesh));
        await dropFiles(page, [
            ["demo.jsonl", demoLines.join("\n") + "\n"],
            [mesh, glb],
        ]);
        await page.waitForFunction(() => document.body.dataset.ready === "1", null, {
            timeout: 30000,
        });
        await setHash(page, "#t=20");
        const shown = await hud(page);
        expectSpeed(shown.speed, demoSpeedKmh(20), "the dropped demo at 20 s");
        const pixels = await canvasPixels(page);
        // The track's elevation colours and shading, against a grid and sky before.
        assert.ok(
            distinctColours(pixels) > 2 * empty,
            `${distinctColours(pixels)} colours, ${empty} without the track`,
        );
    }),
);

await check("a malformed recording is refused by view and, dropped, shows a readable error", () =>
    withPage(browser, async ({ page, open }) => {
        // `trackphys view` names the bad line as the page does, and writes no page.
        const malformed = writeRecording("malformed", malformedRecording());
        assert.throws(
            () => makePage(malformed, "malformed"),
            (e) => /line 3: not a JSON object/.test(String(e.stderr)),
        );
        const v1 = makePage(writeRecording("version_1", versionOneRecording(3)), "version_1");
        await waitReady(page, await open(v1));
        await dropFiles(page, [["malformed.jsonl", malformedRecording()]]);
        const error = page.locator('[data-testid="error"]');
        await error.waitFor({ state: "visible", timeout: 10000 });
        assert.match(await error.textContent(), /line 3: not JSON/);
        await dropFiles(page, [["notes.txt", "hello"]]);
        await page.waitForFunction(() =>
            document.querySelector('[data-testid="error"]').textContent.includes("not a trackphys recording"),
        );
        const noCar = writeRecording("car_contact_naming_no_car", carContactNamingNoCar());
        assert.throws(
            () => makePage(noCar, "car_contact_naming_no_car"),
            (e) => /line 2: car_contacts\[0\] must name two of the 2 cars, the lower first/.test(String(e.stderr)),
        );
        await dropFiles(page, [["no_car.jsonl", carContactNamingNoCar()]]);
        await page.waitForFunction(() =>
            document
                .querySelector('[data-testid="error"]')
                .textContent.includes("line 2: car_contacts[0] must name two of the 2 cars, the lower first"),
        );
        await dropFiles(page, [["short_of_a_wheel.jsonl", vehicleMissingAWheel()]]);
        await page.waitForFunction(() =>
            document
                .querySelector('[data-testid="error"]')
                .textContent.includes("line 2: cars[0].vehicle.wheels must list the car's 4 wheels"),
        );
        // The replay before the refused drops still runs: a click on the message goes back.
        await error.click();
        await error.waitFor({ state: "hidden", timeout: 10000 });
        await waitReady(page, Date.now());
        assert.equal(await page.locator('[data-testid="car-list"] button').count(), 1);
    }),
);

await check("a 10-minute recording (the demo's lap repeated) still opens", () =>
    withPage(browser, async ({ page, open }) => {
        // Each repeat's frames shifted by the lap's duration: 60,000 updates of a real drive.
        const frames = demoLines.slice(1).map((line) => JSON.parse(line));
        const lap = frames[frames.length - 1].t;
        const lines = [demoLines[0]];
        for (let k = 0; lines.length <= 60000; ++k)
            for (const frame of frames)
                if (lines.length <= 60000) lines.push(JSON.stringify({ ...frame, t: frame.t + k * lap }));
        const recording = join(args.work, "ten_minutes.jsonl");
        writeFileSync(recording, lines.join("\n") + "\n");
        // Beside the demo recording's track mesh, which the header names relatively.
        const mesh = JSON.parse(demoLines[0]).track.mesh;
        copyFileSync(join(dirname(args.demo), mesh), join(args.work, mesh));
        const pageFile = makePage(recording, "ten_minutes");
        const ms = await waitReady(page, await open(pageFile, "#t=599"), 60000);
        console.log(
            `10 minutes   ${lines.length - 1} updates, page ${(readFileSync(pageFile).length / 1e6).toFixed(1)} MB, ready in ${ms} ms`,
        );
        assert.equal((await hud(page)).time, 599);
    }),
);

await browser.close();
console.log(failures === 0 ? "all browser checks passed" : `${failures} browser check(s) failed`);
process.exit(failures === 0 ? 0 : 1);
