#include "teleop/web_viewer_page.hpp"

namespace mjarm {

namespace {

// The page's state is on window.mjarmLive for tests: connected, greeting, frames (count), last
// (the newest frame as numbers), refusedSends.
constexpr const char* kPage = R"html(<!doctype html>
<html lang="en"><head><meta charset="utf-8"><title>mjarm live view</title>
<link rel="icon" href="data:,">
<style>
body { margin: 0; font: 13px sans-serif; display: flex; height: 100vh; background: #1d2024; color: #ddd; }
#view { flex: 1; }
#panel { width: 290px; padding: 10px; overflow-y: auto; background: #272b30; }
label { display: block; margin-top: 8px; }
input[type=range] { width: 100%; }
.value { float: right; font-family: monospace; }
#status { font-family: monospace; white-space: pre; margin-top: 12px; }
</style></head>
<body><canvas id="view"></canvas>
<div id="panel"><b id="title">mjarm live view</b> <span id="link">connecting…</span>
<div id="sliders"></div><label id="mode-label">mode <select id="mode"></select></label>
<button id="reset">reset</button><div id="status"></div>
<p>Drag to turn the view, scroll to zoom.</p></div>
<script>
"use strict";
const live = window.mjarmLive = { connected: false, greeting: null, frames: 0, last: null };
const canvas = document.getElementById("view"), ctx = canvas.getContext("2d");
let azimuth = 0.8, elevation = 0.45, zoom = 1.0;
const ws = new WebSocket("ws://" + location.host + "/ws" + location.search);
ws.binaryType = "arraybuffer";
ws.onopen = () => { live.connected = true; document.getElementById("link").textContent = "connected"; };
ws.onclose = () => { live.connected = false; document.getElementById("link").textContent = "disconnected"; };
ws.onmessage = (event) => {
  if (typeof event.data === "string") { greet(JSON.parse(event.data)); return; }
  live.last = Array.from(new Float32Array(event.data));
  live.frames += 1;
  draw();
};
const pending = {};
function send(name, value) { pending[name] = value; }
setInterval(() => {  // at most 30 messages per second per slider
  for (const name of Object.keys(pending)) {
    ws.send(JSON.stringify({ set: name, value: pending[name] }));
    delete pending[name];
  }
}, 33);
function greet(g) {
  live.greeting = g;
  document.getElementById("title").textContent = g.model;
  const box = document.getElementById("sliders");
  box.textContent = "";
  for (const s of g.sliders) {
    const label = document.createElement("label");
    const shown = document.createElement("span");
    shown.className = "value";
    shown.textContent = s.value.toFixed(3);
    const input = document.createElement("input");
    Object.assign(input, { type: "range", min: s.lower, max: s.upper, step: (s.upper - s.lower) / 1000, value: s.value, id: "slider-" + s.name });
    input.oninput = () => { shown.textContent = Number(input.value).toFixed(3); send(s.name, Number(input.value)); };
    label.append(s.name, shown, input);
    box.append(label);
  }
  const mode = document.getElementById("mode");
  mode.textContent = "";
  const panel = g.sliders.length > 0;  // the passive form is watched, not steered
  document.getElementById("mode-label").hidden = !panel;
  document.getElementById("reset").hidden = !panel;
  for (const m of g.modes) mode.append(new Option(m, m, false, m === g.mode));
  mode.onchange = () => send("mode", mode.value);
}
document.getElementById("reset").onclick = () => ws.send(JSON.stringify({ reset: true }));
function project(x, y, z) {  // orbit camera around the origin, z up
  const ca = Math.cos(azimuth), sa = Math.sin(azimuth), ce = Math.cos(elevation), se = Math.sin(elevation);
  const u = -sa * x + ca * y, v = -se * (ca * x + sa * y) + ce * z;
  const scale = 0.6 * Math.min(canvas.width, canvas.height) * zoom;
  return [canvas.width / 2 + scale * u, canvas.height * 0.75 - scale * v];
}
function draw() {
  canvas.width = canvas.clientWidth; canvas.height = canvas.clientHeight;
  ctx.fillStyle = "#1d2024"; ctx.fillRect(0, 0, canvas.width, canvas.height);
  const f = live.last, g = live.greeting;
  if (!f || !g) return;
  const head = g.frame.header_floats, per = g.frame.body_floats;
  const at = (k) => k === 0 ? [0, 0, 0] : f.slice(head + per * (k - 1), head + per * (k - 1) + 3);
  ctx.strokeStyle = "#555"; ctx.beginPath();  // the floor's axes, 0.5 m
  for (const [a, b] of [[[0, 0, 0], [0.5, 0, 0]], [[0, 0, 0], [0, 0.5, 0]]]) { ctx.moveTo(...project(...a)); ctx.lineTo(...project(...b)); }
  ctx.stroke();
  ctx.strokeStyle = "#9ab"; ctx.lineWidth = 4; ctx.beginPath();
  g.bodies.forEach((body, i) => { ctx.moveTo(...project(...at(body.parent))); ctx.lineTo(...project(...at(i + 1))); });
  ctx.stroke();
  let status = "t " + f[0].toFixed(2) + " s";
  if (head >= 8) {  // the viewer's panel: end effector, target, gripper (the passive form has none)
    const dot = (p, colour, r) => { ctx.fillStyle = colour; ctx.beginPath(); ctx.arc(...project(...p), r, 0, 7); ctx.fill(); };
    dot(f.slice(4, 7), "#e44", 6);  // target
    dot(f.slice(1, 4), "#4e4", 4);  // end effector
    status += "\nend effector " + f.slice(1, 4).map((v) => v.toFixed(3)).join(" ") +
      "\ntarget       " + f.slice(4, 7).map((v) => v.toFixed(3)).join(" ") + "\ngripper " + f[7].toFixed(2);
  }
  document.getElementById("status").textContent = status;
}
let drag = null;
canvas.onmousedown = (e) => { drag = [e.clientX, e.clientY]; };
window.onmouseup = () => { drag = null; };
window.onmousemove = (e) => {
  if (!drag) return;
  azimuth -= (e.clientX - drag[0]) * 0.01;
  elevation = Math.max(-1.5, Math.min(1.5, elevation + (e.clientY - drag[1]) * 0.01));
  drag = [e.clientX, e.clientY];
  draw();
};
canvas.onwheel = (e) => { zoom *= Math.exp(-e.deltaY * 0.001); draw(); e.preventDefault(); };
</script></body></html>
)html";

}  // namespace

const std::string& web_viewer_page() {
  static const std::string page(kPage);
  return page;
}

nlohmann::json web_viewer_bodies(const mjModel& model) {
  nlohmann::json bodies = nlohmann::json::array();
  for (int b = 1; b < model.nbody; ++b) {
    const char* name = mj_id2name(&model, mjOBJ_BODY, b);
    bodies.push_back({{"name", name != nullptr ? name : ""}, {"parent", model.body_parentid[b]}});
  }
  return bodies;
}

}  // namespace mjarm
