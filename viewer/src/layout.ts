// The page's elements, built once. Test hooks (data-testid) are part of the viewer's
// contract: docs/viewer.md lists them.
import css from "./style.css";

function element<K extends keyof HTMLElementTagNameMap>(
  tag: K,
  attributes: Record<string, string> = {},
  text = "",
): HTMLElementTagNameMap[K] {
  const e = document.createElement(tag);
  for (const [k, v] of Object.entries(attributes)) e.setAttribute(k, v);
  if (text) e.textContent = text;
  return e;
}

function hudRow(label: string, testid: string, unit: string): [HTMLElement, HTMLElement] {
  const row = element("div", { class: "row" });
  const value = element("span", { class: "value", "data-testid": testid }, "-");
  const right = element("span");
  right.append(value, unit ? ` ${unit}` : "");
  row.append(element("span", {}, label), right);
  return [row, value];
}

export interface Layout {
  view: HTMLElement;
  title: HTMLElement;
  time: HTMLElement;
  speed: HTMLElement;
  lap: HTMLElement;
  updateUs: HTMLElement;
  inputs: HTMLElement;
  hash: HTMLElement;
  camera: HTMLElement;
  contacts: HTMLElement;
  carContacts: HTMLElement;
  vehicle: HTMLElement;
  cars: HTMLElement;
  play: HTMLButtonElement;
  back: HTMLButtonElement;
  forward: HTMLButtonElement;
  scrub: HTMLInputElement;
  rate: HTMLSelectElement;
  clock: HTMLElement;
  charts: HTMLElement;
  error: HTMLElement;
  errorText: HTMLElement;
  drop: HTMLElement;
}

export function buildLayout(): Layout {
  const style = element("style");
  style.textContent = css;
  document.head.append(style);

  const view = element("div", { id: "view" });
  const hud = element("div", { id: "hud", class: "panel", "data-testid": "hud" });
  const title = element("div", { class: "title" });
  const [timeRow, time] = hudRow("time", "hud-time", "s");
  const [speedRow, speed] = hudRow("speed", "hud-speed", "km/h");
  const [lapRow, lap] = hudRow("lap", "hud-lap", "");
  const [usRow, updateUs] = hudRow("update", "hud-update-us", "us");
  const [inputsRow, inputs] = hudRow("throttle brake steer", "hud-inputs", "");
  const [hashRow, hash] = hudRow("state hash", "hud-hash", "");
  const [contactsRow, contacts] = hudRow("contacts", "hud-contacts", "");
  const [carContactsRow, carContacts] = hudRow("car contacts", "hud-car-contacts", "");
  const [cameraRow, camera] = hudRow("camera", "hud-camera", "");
  const vehicle = element("div", { class: "vehicle", "data-testid": "hud-vehicle" });
  vehicle.hidden = true;
  hud.append(
    title,
    timeRow,
    speedRow,
    lapRow,
    usRow,
    inputsRow,
    contactsRow,
    carContactsRow,
    hashRow,
    cameraRow,
    vehicle,
  );
  const cars = element("div", { id: "cars", class: "panel", "data-testid": "car-list" });
  const help = element(
    "div",
    { id: "help", class: "panel" },
    "space play/pause · ←/→ step · 1 chase · 2 orbit · 3 top · drop a recording (and its .glb) to open it",
  );

  const bottom = element("div", { id: "bottom" });
  const timeline = element("div", { id: "timeline" });
  const back = element("button", { title: "step back (←)", "data-testid": "step-back" }, "◀▮");
  const play = element("button", { title: "play/pause (space)", "data-testid": "play" }, "▶");
  const forward = element("button", { title: "step forward (→)", "data-testid": "step-forward" }, "▮▶");
  const scrub = element("input", { type: "range", min: "0", max: "1", step: "any", "data-testid": "scrub" });
  const rate = element("select", { title: "playback speed", "data-testid": "rate" });
  for (const r of [0.25, 0.5, 1, 2, 4]) rate.append(element("option", { value: String(r) }, `${r}x`));
  rate.value = "1";
  const clock = element("span", { class: "clock" });
  timeline.append(back, play, forward, scrub, rate, clock);
  const charts = element("div", { style: "display: contents" });
  bottom.append(timeline, charts);

  const error = element("div", { id: "error", role: "alert", "data-testid": "error" });
  const errorBox = element("div");
  const errorText = element("pre");
  errorBox.append(element("h1", {}, "This recording cannot be shown"), errorText);
  error.append(errorBox);
  const drop = element("div", { id: "drop" }, "Drop a trackphys recording (.jsonl) and its track (.glb)");

  view.append(hud, cars, help);
  document.body.append(view, bottom, error, drop);
  return {
    view,
    title,
    time,
    speed,
    lap,
    updateUs,
    inputs,
    hash,
    camera,
    contacts,
    carContacts,
    vehicle,
    cars,
    play,
    back,
    forward,
    scrub,
    rate,
    clock,
    charts,
    error,
    errorText,
    drop,
  };
}
