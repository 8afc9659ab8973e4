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

// The room the scene file's camera stands in (the bounds of the objects around it, from the
// server): an orbit or the wheel that would take the camera out of it, a little off its walls,
// pulls the camera in towards the orbit's centre instead, unless `leave` (Alt held, or the box
// ticked). Outside, the camera sees the walls from behind, or nothing. Flying goes anywhere.
function keepInRoom(before, center, leave) {
  const room = preview.state && preview.state.enclosure;
  if (!room || leave) return;
  const margin = 0.02 * Math.min(...sub(room.max, room.min));
  const lo = room.min.map((x) => x + margin), hi = room.max.map((x) => x - margin);
  const within = (p) => p.every((x, i) => x >= lo[i] && x <= hi[i]);
  if (!within(before.position) || within(camera.position)) return;
  if (!within(center)) {
    camera = before; // no line back in through the centre: the move is not made
    return;
  }
  const d = sub(camera.position, center);
  let s = 1;
  d.forEach((x, i) => {
    if (x > 0) s = Math.min(s, (hi[i] - center[i]) / x);
    if (x < 0) s = Math.min(s, (lo[i] - center[i]) / x);
  });
  const moved = sub(add(center, scale(d, s)), camera.position);
  camera.position = add(camera.position, moved);
  camera.look_at = add(camera.look_at, moved);
}

function orbit(dx, dy, leave) {
  const before = { ...camera };
  const center = orbitCenter();
  turnAbout(center, [0, 1, 0], -dx * 0.01);
  turnAbout(center, right(), -dy * 0.01);
  keepInRoom(before, center, leave);
}

function look(dx, dy) {
  turnAbout(camera.position, [0, 1, 0], -dx * 0.005);
  turnAbout(camera.position, right(), -dy * 0.005);
}

function dolly(amount, leave) {
  const before = { ...camera };
  const center = orbitCenter();
  const offset = scale(sub(camera.position, center), Math.exp(amount));
  const moved = sub(add(center, offset), camera.position);
  camera.position = add(camera.position, moved);
  camera.look_at = add(camera.look_at, moved);
  keepInRoom(before, center, leave);
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

// Why the last move was refused (a camera inside a horizon), shown over the notices until the
// camera moves again.
let refusedMove = "";

async function sendCamera() {
  if (inFlight || !dirty) return;
  inFlight = true;
  dirty = false;
  try {
    await post("/view", camera);
    refusedMove = "";
  } catch (e) {
    refusedMove = `The camera cannot go there, so it stays where it was: ${e.message}`;
    dirty = false;
    camera = null; // take the server's camera back at the next poll
  }
  inFlight = false;
  showNotices();
  if (dirty) sendCamera();
}

// ---- mouse and keys -------------------------------------------------------------------------
let drag = null;
canvas.addEventListener("contextmenu", (e) => e.preventDefault());
const leaving = (e) => e.altKey || $("free").checked;
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
  if (drag.look) look(dx, dy);
  else orbit(dx, dy, leaving(e));
  moved();
});
window.addEventListener("mouseup", () => (drag = null));
canvas.addEventListener("wheel", (e) => {
  e.preventDefault();
  if (!camera) return;
  dolly(Math.max(-1, Math.min(1, e.deltaY * 0.001)), leaving(e));
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
// The server gives each parameter's value and the range it can take with the others as they are
// (|spin| ≤ mass, …), so a slider offers only values the server accepts. While the user moves a
// slider, or its value is on the way, the slider and its label show the user's value; then both
// show the server's, which is the old one if the value was refused (a range gone stale).
let sliderNames = "";
const editing = new Set(); // names of the sliders the user is moving or has just set
let settingsInFlight = Promise.resolve();

function sendSettings(body) {
  const sent = settingsInFlight.then(() => post("/settings", body));
  settingsInFlight = sent.catch(() => {});
  return sent;
}

// A value to send: 4 significant digits (a file reads `mass = 0.6`, not 0.6000000000000001),
// kept within the range.
function tidy(x, min, max) {
  return Math.min(max, Math.max(min, Number(x.toPrecision(4))));
}

function buildSliders(state) {
  const names = JSON.stringify([state.spacetime, state.parameters.map((p) => p.name)]);
  if (names === sliderNames) return;
  sliderNames = names;
  editing.clear();
  const box = $("sliders");
  box.textContent = "";
  for (const p of state.parameters) {
    const label = document.createElement("label");
    label.htmlFor = "param-" + p.name;
    label.append(`${p.name}: `);
    const shown = document.createElement("span");
    shown.id = `param-${p.name}-value`;
    label.append(shown);
    const input = document.createElement("input");
    // step "any": the thumb sits exactly at the server's value, which the label shows.
    Object.assign(input, { type: "range", id: "param-" + p.name, min: p.min, max: p.max, step: "any" });
    input.value = p.value;
    const chosen = () => tidy(Number(input.value), Number(input.min), Number(input.max));
    input.addEventListener("input", () => {
      editing.add(p.name);
      shown.textContent = chosen().toPrecision(4);
    });
    input.addEventListener("change", async () => {
      editing.add(p.name);
      const value = chosen();
      shown.textContent = value.toPrecision(4);
      try {
        await sendSettings({ parameters: { [p.name]: value } });
        // The value stands until the state that has it arrives: a state read before it was
        // accepted must not pull the thumb back.
        const state = await fetchState();
        if (state) showState(state);
      } catch (e) {
        say(`${p.name} ${value} refused: ${e.message}`);
      }
      editing.delete(p.name);
      if (preview.state) showSliders(preview.state);
    });
    box.append(label, input);
  }
}

function showSliders(state) {
  for (const p of state.parameters) {
    const input = $("param-" + p.name);
    if (!input || editing.has(p.name)) continue;
    if (Number(input.min) !== p.min) input.min = p.min;
    if (Number(input.max) !== p.max) input.max = p.max;
    input.value = p.value;
    $(`param-${p.name}-value`).textContent = Number(p.value).toPrecision(4);
  }
  const spp = $("spp");
  if (state.spp && document.activeElement !== spp) spp.value = Math.round(Math.log2(state.spp));
  $("spp-value").textContent = state.spp || "";
  $("spp-label").textContent = state.integrator === "photon" ? "iterations (photon mapping)" : "samples per pixel";
}

$("spp").addEventListener("input", () => ($("spp-value").textContent = 2 ** Number($("spp").value)));
$("spp").addEventListener("change", () => sendSettings({ spp: 2 ** Number($("spp").value) }).catch((e) => say(e.message)));

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
  refusedMove = "";
  button("/reset", {});
});
$("save-view").addEventListener("click", () => button("/save-view", { name: $("view-name").value }));

// The render this page started and whose "rendering to …" the message line shows, until the
// state says it has ended; then the line says how.
let renderJob = null;
$("render").addEventListener("click", async () => {
  try {
    const response = await fetch("/render", {
      method: "POST",
      headers: { "Content-Type": "application/json" },
      body: JSON.stringify({ output: $("output-name").value, overwrite: $("overwrite").checked }),
    });
    const text = await response.text();
    if (!response.ok) throw new Error(text.trim());
    const answer = JSON.parse(text);
    renderJob = answer.job;
    say(answer.message);
  } catch (e) {
    say(e.message);
  }
});

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

function showNotices() {
  const notices = (preview.state && !preview.state.error && preview.state.notices) || [];
  const text = [refusedMove, ...notices].filter(Boolean).join("\n");
  const box = $("notice");
  box.textContent = text;
  box.style.display = text ? "block" : "none";
}

// The newest generation shown: a state read before a change and answered after it is stale.
let newestGeneration = 0;

function showState(state) {
  if (state.generation < newestGeneration) return;
  newestGeneration = state.generation;
  preview.state = state;
  $("scene").textContent = state.scene;
  const error = $("error");
  error.textContent = state.error || "";
  error.style.display = state.error ? "block" : "none";
  const job = state.render;
  if (job && job.id === renderJob && job.state !== "running") {
    say(job.message); // "wrote …", or why it failed ("cannot write image …", "the render failed: …")
    renderJob = null;
  }
  showNotices();
  if (state.error) {
    $("status").textContent = "the scene cannot be shown: fix the file and it reloads";
    return;
  }
  if (state.camera && !dirty && !inFlight && !drag) camera = state.camera;
  preview.camera = camera;
  buildSliders(state);
  showSliders(state);
  const f = state.frame;
  const jobText = job && job.state === "running" ? ` · rendering ${job.output}: ${Math.round(100 * job.progress)}%` : "";
  const first = preview.firstFrameMs === undefined ? "" : ` · first frame after ${preview.firstFrameMs} ms`;
  const per = f && f.spp > 0 ? `, ${(f.seconds / f.spp).toFixed(2)} s each` : "";
  const unit = state.integrator === "photon" ? "iterations" : "spp";
  const frameText = f ? `${f.width}×${f.height}, ${f.spp} ${unit}${per}${f.done ? " (done)" : ""}` : "rendering…";
  $("status").textContent = frameText + first + jobText;
  if (f && (!preview.frame || preview.frame.version !== f.version)) showFrame();
}

// The server's state, or null (and the status line says so) if it cannot be read.
async function fetchState() {
  try {
    const response = await fetch("/state", { cache: "no-store" });
    if (response.ok) return await response.json();
  } catch (e) {
    $("status").textContent = "the preview server is not answering";
  }
  return null;
}

async function poll() {
  const state = await fetchState();
  if (state) showState(state);
  setTimeout(poll, 150);
}
// The frame is asked for at once, not only after the first state arrives.
showFrame();
poll();
