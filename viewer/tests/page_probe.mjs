// Opening a replay page in Debian's chromium, headless, WebGL through SwiftShader, with
// every request outside the page itself refused and recorded, and every console error and
// uncaught exception collected.
import { chromium } from "playwright-core";
import { pathToFileURL } from "node:url";

export async function launchBrowser() {
    return chromium.launch({
        executablePath: process.env.TRACKPHYS_CHROMIUM ?? "/usr/bin/chromium",
        args: ["--use-angle=swiftshader", "--enable-unsafe-swiftshader"],
    });
}

/** A new page with its guards; `problems` lists what must stay empty. */
export async function openGuardedPage(browser) {
    const context = await browser.newContext({ viewport: { width: 1280, height: 800 } });
    const page = await context.newPage();
    const problems = [];
    let allowed = null;
    await context.route("**/*", (route) => {
        const url = route.request().url();
        if (url.split("#")[0] === allowed) return route.continue();
        problems.push(`network request: ${url}`);
        return route.abort();
    });
    page.on("request", (request) => {
        if (request.url().split("#")[0] !== allowed) problems.push(`request: ${request.url()}`);
    });
    page.on("console", (message) => {
        if (message.type() === "error") problems.push(`console error: ${message.text()}`);
    });
    page.on("pageerror", (error) => problems.push(`uncaught exception: ${error.message}`));
    const open = async (file, fragment = "") => {
        allowed = pathToFileURL(file).href;
        const start = Date.now();
        await page.goto(allowed + fragment);
        return start;
    };
    return { context, page, problems, open };
}

/** Waits for the ready flag; returns ms since `start`. */
export async function waitReady(page, start, timeout = 10000) {
    await page.waitForFunction(() => document.body.dataset.ready === "1", null, { timeout, polling: 20 });
    return Date.now() - start;
}

/** The WebGL canvas scaled down to w x h RGBA pixels (the renderer preserves its buffer). */
export async function canvasPixels(page, w = 96, h = 54) {
    return page.evaluate(
        ([w, h]) => {
            const source = document.querySelector("#view canvas");
            const small = document.createElement("canvas");
            small.width = w;
            small.height = h;
            const g = small.getContext("2d");
            g.drawImage(source, 0, 0, w, h);
            return Array.from(g.getImageData(0, 0, w, h).data);
        },
        [w, h],
    );
}

export function distinctColours(pixels) {
    const seen = new Set();
    for (let i = 0; i < pixels.length; i += 4) seen.add((pixels[i] << 16) | (pixels[i + 1] << 8) | pixels[i + 2]);
    return seen.size;
}

/** Mean absolute difference per channel (0..255). */
export function meanDifference(a, b) {
    let sum = 0;
    for (let i = 0; i < a.length; ++i) if (i % 4 !== 3) sum += Math.abs(a[i] - b[i]);
    return sum / ((a.length * 3) / 4);
}

export async function hud(page) {
    const text = (id) => page.locator(`[data-testid="${id}"]`).textContent();
    return {
        time: Number(await text("hud-time")),
        speed: Number(await text("hud-speed")),
        camera: await text("hud-camera"),
        contacts: Number(await text("hud-contacts")),
        carContacts: Number(await text("hud-car-contacts")),
        inputs: await text("hud-inputs"),
        hash: await text("hud-hash"),
    };
}

/** The HUD's vehicle part: shown or not, rpm, gear (as shown: "R" for reverse) and per wheel
 * the four numbers. */
export async function vehicleHud(page) {
    return page.evaluate(() => {
        const root = document.querySelector('[data-testid="hud-vehicle"]');
        const text = (id) => document.querySelector(`[data-testid="${id}"]`)?.textContent;
        const number = (id) => Number(text(id));
        const wheels = [];
        for (let w = 0; document.querySelector(`[data-testid="hud-wheel-${w}-load"]`); ++w)
            wheels.push(["slip-ratio", "slip-angle", "load", "spin"].map((c) => number(`hud-wheel-${w}-${c}`)));
        return { shown: !root.hidden, rpm: number("hud-rpm"), gear: text("hud-gear"), wheels };
    });
}

/** Drops files ([name, text or Buffer]) onto the page as a user's drag-and-drop would. */
export async function dropFiles(page, files) {
    // Binary contents cross into the page as base64.
    const encoded = files.map(([name, contents]) =>
        typeof contents === "string" ? [name, contents, false] : [name, contents.toString("base64"), true],
    );
    const transfer = await page.evaluateHandle((files) => {
        const data = new DataTransfer();
        for (const [name, contents, binary] of files)
            data.items.add(new File([binary ? Uint8Array.fromBase64(contents) : contents], name));
        return data;
    }, encoded);
    await page.dispatchEvent("body", "drop", { dataTransfer: transfer });
}
