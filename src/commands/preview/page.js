// nullpath preview page: polls /state, draws each new /frame.png on the canvas, and sends the
// camera (/view), sliders (/settings) and buttons (/save-view, /render, /reset) to the server.
// `window.preview` exposes what the page shows, for the headless-browser test.
"use strict";

const $ = (id) => document.getElementById(id);
const canvas = $("view");
const context = canvas.getContext("2d");
const preview = (window.preview = { framesShown: 0, frame: null, state: null, camera: null });

// ---- vectors --------------------------------------------------------------------------------
const add = (a, b) => a.map((x, i) => x + b[i]);
const sub = (a, b) => a.map((x, i) => x - b[i]);
const scale = (a, s) => a.map((x) => x * s);
const dot = (a, b) => a.reduce((s, x, i) => s + x * b[i], 0);
const cross = (a, b) => [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]];
const length = (a) => Math.sqrt(dot(a, a));
const normalize = (a) => scale(a, 1 / (length(a) || 1));
// Rodrigues: `v` turned by `angle` about the unit `axis`.
function rotate(v, axis, angle) {
  const c = Math.cos(angle), s = Math.sin(angle);
  return add(add(scale(v, c), scale(cross(axis, v), s)), scale(axis, dot(axis, v) * (1 - c)));
}

// ---- the camera -----------------------------------------------------------------------------
let camera = null; // {position, look_at, up, fov}, as the server has it or as the user moved it
let dirty = false; // moved here and not yet sent
let inFlight = false;

const forward = () => normalize(sub(camera.look_at, camera.position));
const right = () => normalize(cross(forward(), camera.up));
const distance = () => length(sub(camera.look_at, camera.position));

// What an orbit turns about: in curved spacetime the point of the view line nearest the hole
// (the world origin), else the point looked at.
function orbitCenter() {
  const curved = preview.state && preview.state.spacetime && preview.state.spacetime !== "minkowski";
  const t = -dot(camera.position, forward());
  return curved && t > 1e-3 ? add(camera.position, scale(forward(), t)) : camera.look_at;
}

// The camera turned rigidly about `center` by `angle` about `axis`.
function turnAbout(center, axis, angle) {
  const f = forward();
  camera.position = add(center, rotate(sub(camera.position, center), axis, angle));
  const d = distance();
  camera.look_at = add(camera.position, scale(rotate(f, axis, angle), d));
  camera.up = rotate(camera.up, axis, angle);
}

function orbit(dx, dy) {
  const center = orbitCenter();
  turnAbout(center, [0, 1, 0], -dx * 0.01);
  turnAbout(center, right(), -dy * 0.01);
}

function look(dx, dy) {
  turnAbout(camera.position, [0, 1, 0], -dx * 0.005);
  turnAbout(camera.position, right(), -dy * 0.005);
}

function dolly(amount) {
  const center = orbitCenter();
  const offset = scale(sub(camera.position, center), Math.exp(amount));
  const moved = sub(add(center, offset), camera.position);
  camera.position = add(camera.position, moved);
  camera.look_at = add(camera.look_at, moved);
}

function fly(direction) {
  const step = 0.03 * length(sub(camera.position, orbitCenter())) + 0.02;
  const move = scale(direction, step);
  camera.position = add(camera.position, move);
  camera.look_at = add(camera.look_at, move);
}

function moved() {
  dirty = true;
  sendCamera();
}

async function post(path, body) {
  const response = await fetch(path, {
    method: "POST",
    headers: { "Content-Type": "application/json" },
    body: JSON.stringify(body),
  });
  const text = await response.text();
  if (!response.ok) throw new Error(text.trim());
  return JSON.parse(text).message;
}

function say(text) {
  $("message").textContent = text;
}

async function sendCamera() {
  if (inFlight || !dirty) return;
  inFlight = true;
  dirty = false;
  try {
    await post("/view", camera);
  } catch (e) {
    say(e.message);
    dirty = false;
    camera = null; // take the server's camera back at the next poll
  }
  inFlight = false;
  if (dirty) sendCamera();
}

// ---- mouse and keys -------------------------------------------------------------------------
let drag = null;
canvas.addEventListener("contextmenu", (e) => e.preventDefault());
canvas.addEventListener("mousedown", (e) => {
  canvas.focus();
  if (!camera) return;
  drag = { x: e.clientX, y: e.clientY, look: e.shiftKey || e.button === 2 };
  e.preventDefault();
});
window.addEventListener("mousemove", (e) => {
  if (!drag || !camera) return;
  const dx = e.clientX - drag.x, dy = e.clientY - drag.y;
  drag.x = e.clientX;
  drag.y = e.clientY;
  if (dx === 0 && dy === 0) return;
  (drag.look ? look : orbit)(dx, dy);
  moved();
});
window.addEventListener("mouseup", () => (drag = null));
canvas.addEventListener("wheel", (e) => {
  e.preventDefault();
  if (!camera) return;
  dolly(Math.max(-1, Math.min(1, e.deltaY * 0.001)));
  moved();
}, { passive: false });
canvas.addEventListener("keydown", (e) => {
  if (!camera) return;
  const directions = {
    w: () => forward(), s: () => scale(forward(), -1), d: () => right(), a: () => scale(right(), -1),
    e: () => normalize(camera.up), q: () => scale(normalize(camera.up), -1),
  };
  const direction = directions[e.key.toLowerCase()];
  if (!direction) return;
  e.preventDefault();
  fly(direction());
  moved();
});

// ---- sliders --------------------------------------------------------------------------------
let sliderKey = "";
let settingsInFlight = Promise.resolve();

function sendSettings(body) {
  settingsInFlight = settingsInFlight.then(() => post("/settings", body).catch((e) => say(e.message)));
}

function buildSliders(state) {
  const key = JSON.stringify([state.spacetime, state.parameters.map((p) => [p.name, p.min, p.max])]);
  if (key === sliderKey) return;
  sliderKey = key;
  const box = $("sliders");
  box.textContent = "";
  for (const p of state.parameters) {
    const label = document.createElement("label");
    label.htmlFor = "param-" + p.name;
    label.innerHTML = `${p.name}: <span id="param-${p.name}-value"></span>`;
    const input = document.createElement("input");
    Object.assign(input, { type: "range", id: "param-" + p.name, min: p.min, max: p.max });
    input.step = (p.max - p.min) / 1000;
    input.value = p.value;
    input.addEventListener("change", () => {
      sendSettings({ parameters: { [p.name]: Number(input.value) } });
    });
    input.addEventListener("input", () => ($(`param-${p.name}-value`).textContent = input.value));
    box.append(label, input);
  }
}

function showSliders(state) {
  for (const p of state.parameters) {
    const input = $("param-" + p.name);
    if (input && document.activeElement !== input) input.value = p.value;
    const shown = $(`param-${p.name}-value`);
    if (shown) shown.textContent = Number(p.value).toPrecision(4);
  }
  const spp = $("spp");
  if (state.spp && document.activeElement !== spp) spp.value = Math.round(Math.log2(state.spp));
  $("spp-value").textContent = state.spp || "";
}

$("spp").addEventListener("input", () => ($("spp-value").textContent = 2 ** Number($("spp").value)));
$("spp").addEventListener("change", () => sendSettings({ spp: 2 ** Number($("spp").value) }));

// ---- buttons --------------------------------------------------------------------------------
async function button(path, body) {
  try {
    say(await post(path, body));
  } catch (e) {
    say(e.message);
  }
}
$("reset").addEventListener("click", () => {
  camera = null;
  button("/reset", {});
});
$("save-view").addEventListener("click", () => button("/save-view", { name: $("view-name").value }));
$("render").addEventListener("click", () =>
  button("/render", { output: $("output-name").value, overwrite: $("overwrite").checked }),
);

// ---- state and frames -----------------------------------------------------------------------
let fetchingFrame = false;

async function showFrame() {
  if (fetchingFrame) return;
  fetchingFrame = true;
  try {
    const response = await fetch("/frame.png", { cache: "no-store" });
    if (response.status === 200) {
      const bitmap = await createImageBitmap(await response.blob());
      const height = Math.round((canvas.width * bitmap.height) / bitmap.width);
      if (canvas.height !== height) canvas.height = height;
      context.imageSmoothingEnabled = true;
      context.drawImage(bitmap, 0, 0, canvas.width, canvas.height);
      preview.framesShown += 1;
      // Milliseconds from opening the page to its first frame.
      if (preview.firstFrameMs === undefined) preview.firstFrameMs = Math.round(performance.now());
      preview.frame = {
        version: Number(response.headers.get("X-Frame-Version")),
        generation: Number(response.headers.get("X-Frame-Generation")),
        spp: Number(response.headers.get("X-Frame-Spp")),
        done: response.headers.get("X-Frame-Done") === "1",
        width: bitmap.width,
        height: bitmap.height,
      };
    }
  } catch (e) {
    // The next poll tries again.
  }
  fetchingFrame = false;
}

function showState(state) {
  preview.state = state;
  $("scene").textContent = state.scene;
  const error = $("error");
  error.textContent = state.error || "";
  error.style.display = state.error ? "block" : "none";
  if (state.error) {
    $("status").textContent = "the scene cannot be shown: fix the file and it reloads";
    return;
  }
  if (state.camera && !dirty && !inFlight && !drag) camera = state.camera;
  preview.camera = camera;
  buildSliders(state);
  showSliders(state);
  const f = state.frame;
  const job = state.render;
  const jobText = job ? ` · render ${job.output}: ${job.state} ${Math.round(100 * job.progress)}% ${job.message}` : "";
  const first = preview.firstFrameMs === undefined ? "" : ` · first frame after ${preview.firstFrameMs} ms`;
  const frameText = f ? `${f.width}×${f.height}, ${f.spp} spp${f.done ? " (done)" : ""}` : "rendering…";
  $("status").textContent = frameText + first + jobText;
  if (f && (!preview.frame || preview.frame.version !== f.version)) showFrame();
}

async function poll() {
  try {
    const response = await fetch("/state", { cache: "no-store" });
    if (response.ok) showState(await response.json());
  } catch (e) {
    $("status").textContent = "the preview server is not answering";
  }
  setTimeout(poll, 150);
}
// The frame is asked for at once, not only after the first state arrives.
showFrame();
poll();
