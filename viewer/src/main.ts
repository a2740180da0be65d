// The viewer's entry point: reads the recording and track embedded in the page (or dropped
// onto it), shows them, and answers the URL fragment #t=SECONDS&car=K (docs/viewer.md).
import * as THREE from "three";
import { embeddedBytes } from "./embedded";
import { trackFromGlb } from "./glb_track";
import { buildLayout, type Layout } from "./layout";
import { parseRecording, type Recording } from "./recording";
import { ReplayView } from "./replay_view";
import { trackFromEmbedded, type TrackData } from "./track_data";
import { makeTrackMesh } from "./track_view";

const ui: Layout = buildLayout();
let renderer: THREE.WebGLRenderer | null = null;
let current: ReplayView | null = null;

function showError(message: string): void {
  ui.errorText.textContent = message;
  ui.error.classList.add("shown");
  document.body.dataset.error = "1";
}

/** #t=SECONDS&car=K: seek there and pause (either part may be left out). */
function applyHash(view: ReplayView): void {
  const params = new URLSearchParams(location.hash.replace(/^#/, ""));
  const car = params.get("car");
  if (car !== null) {
    const k = Number(car);
    if (Number.isInteger(k) && k >= 0 && k < view.carCount()) view.selectCar(k);
  }
  const t = params.get("t");
  if (t !== null && Number.isFinite(Number(t))) {
    view.pause();
    view.seek(Number(t));
  }
}

async function show(recording: Recording, track: TrackData | null): Promise<void> {
  delete document.body.dataset.ready;
  current?.dispose();
  current = null;
  if (!renderer) {
    renderer = new THREE.WebGLRenderer({ antialias: false, preserveDrawingBuffer: true });
    renderer.setPixelRatio(window.devicePixelRatio); // sharp on high-DPI screens, as the charts
  }
  ui.view.prepend(renderer.domElement);
  const mesh = track ? makeTrackMesh(track.positions, track.indices) : null;
  const view = new ReplayView(recording, mesh, renderer, ui);
  current = view;
  applyHash(view);
  await view.start();
  ui.error.classList.remove("shown");
  delete document.body.dataset.error;
  document.body.dataset.ready = "1";
}

// The longest string Chromium holds (2^29 - 24 UTF-16 units). TextDecoder returns "" for a
// longer text without a word, which the parser then called an empty file.
const MAX_TEXT_BYTES = 536_870_888;

/** A recording's bytes as text, refused by name when the browser cannot hold it. */
function recordingText(bytes: ArrayBuffer, name: string): string {
  if (bytes.byteLength > MAX_TEXT_BYTES)
    throw new Error(
      `${name}: ${(bytes.byteLength / 2 ** 20).toFixed(0)} MiB is more than a browser holds as ` +
        `text (512 MiB): record fewer cars, laps or seconds`,
    );
  return new TextDecoder().decode(bytes);
}

/** Runs one loading phase and records it as a performance measure (the browser tests print them). */
async function phase<T>(name: string, work: () => T | Promise<T>): Promise<T> {
  const start = performance.now();
  const result = await work();
  performance.measure(`trackphys ${name}`, { start, end: performance.now() });
  return result;
}

async function loadEmbedded(): Promise<void> {
  const recording = await phase("decode recording", () => embeddedBytes("trackphys-recording"));
  if (!recording) {
    showError("This page carries no recording: drop a trackphys recording (.jsonl) onto it.");
    return;
  }
  const name = recording.element.dataset.name ?? "recording";
  const parsed = await phase("parse recording", () => parseRecording(recordingText(recording.bytes, name), name));
  const trackPayload = await phase("decode track", () => embeddedBytes("trackphys-track"));
  const track = trackPayload
    ? trackFromEmbedded(
        trackPayload.bytes,
        Number(trackPayload.element.dataset.vertices),
        Number(trackPayload.element.dataset.triangles),
      )
    : null;
  await phase("build scene and draw", () => show(parsed, track));
}

/** A dropped recording, with its track if a .glb file was dropped with it. */
async function loadDropped(files: File[]): Promise<void> {
  const recordingFile = files.find((f) => !f.name.toLowerCase().endsWith(".glb"));
  if (!recordingFile) throw new Error("drop a recording (.jsonl), optionally with its track (.glb)");
  const recording = parseRecording(
    recordingText(await recordingFile.arrayBuffer(), recordingFile.name),
    recordingFile.name,
  );
  const glb = files.find((f) => f.name.toLowerCase().endsWith(".glb"));
  await show(recording, glb ? await trackFromGlb(await glb.arrayBuffer()) : null);
}

function describe(error: unknown): string {
  return error instanceof Error ? error.message : String(error);
}

window.addEventListener("hashchange", () => {
  if (current) applyHash(current);
});
window.addEventListener("dragover", (e) => {
  e.preventDefault();
  ui.drop.classList.add("shown");
});
window.addEventListener("dragleave", () => ui.drop.classList.remove("shown"));
window.addEventListener("drop", (e) => {
  e.preventDefault();
  ui.drop.classList.remove("shown");
  delete document.body.dataset.ready; // until the dropped recording is drawn
  const files = Array.from(e.dataTransfer?.files ?? []);
  loadDropped(files).catch((error) => {
    showError(describe(error));
    // A refused drop leaves the replay before it running: a click goes back to it.
    if (current) {
      ui.errorText.textContent += "\n\n(click to go back to the replay)";
      ui.error.addEventListener("click", backToReplay, { once: true });
    }
  });
});

function backToReplay(): void {
  ui.error.classList.remove("shown");
  delete document.body.dataset.error;
  document.body.dataset.ready = "1";
}

loadEmbedded().catch((error) => showError(describe(error)));
