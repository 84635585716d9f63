#include "sweep/sweep_dashboard_page.hpp"

namespace mjarm {

namespace {

// window.mjarmDashboard holds what the page computed, for tests: shownRows (after the filters),
// heat (the heat map's cells), parameters, metrics.
constexpr const char* kPage = R"html(<!doctype html>
<html lang="en"><head><meta charset="utf-8"><title>mjarm sweep</title>
<style>
body { font: 13px sans-serif; margin: 16px; color: #222; }
h1 { font-size: 18px; } h2 { font-size: 15px; margin-top: 24px; }
table { border-collapse: collapse; } td, th { border: 1px solid #ccc; padding: 2px 6px; text-align: right; }
th { background: #f2f2f2; } td.text { text-align: left; }
.charts { display: flex; flex-wrap: wrap; gap: 16px; }
svg text { font: 11px sans-serif; }
#trials { max-height: 480px; overflow: auto; display: block; }
tr.failed td { background: #fff1f0; }
</style></head><body>
<h1 id="title"></h1><div id="summary"></div>
<h2>Success per axis (95 % Wilson intervals)</h2><div class="charts" id="axes"></div>
<h2>Heat map</h2><label>rows <select id="heat-y"></select></label> <label>columns <select id="heat-x"></select></label>
<div id="heat"></div>
<h2>Metrics</h2><div class="charts" id="metrics"></div>
<h2>Trials</h2>
<label>filter <input id="filter" placeholder="any text"></label>
<label>verdict <select id="verdict"><option value="">all</option></select></label>
<label>outcome <select id="outcome"><option value="">all</option><option value="1">success</option><option value="0">failure</option></select></label>
<span id="shown"></span><table id="trials"></table>
<script type="application/json" id="data">@DATA@</script>
<script>
"use strict";
const data = JSON.parse(document.getElementById("data").textContent);
const state = window.mjarmDashboard = { parameters: data.parameters, metrics: data.metrics, shownRows: 0, heat: [] };
const col = (name) => data.columns.indexOf(name);
const svgNS = "http://www.w3.org/2000/svg";
function el(tag, attrs, text) {
  const e = document.createElementNS(svgNS, tag);
  for (const [k, v] of Object.entries(attrs || {})) e.setAttribute(k, v);
  if (text !== undefined) e.textContent = text;
  return e;
}
const fmt = (v) => typeof v === "number" ? (Number.isInteger(v) ? String(v) : v.toPrecision(4)) : typeof v === "string" ? v : JSON.stringify(v);
const pct = (r) => (100 * r).toFixed(1) + " %";
const rateText = (s) => s.successes + "/" + s.trials + " = " + pct(s.rate) + " [" + pct(s.low) + ", " + pct(s.high) + "]";

const r = data.report;
document.getElementById("title").textContent = "sweep " + r.scenario + " (plan " + r.hash + ")";
document.getElementById("summary").textContent = "success " + rateText(r.success) +
  (r.success.trials < r.planned ? " of " + r.planned + " planned" : "") + "; verdicts: " +
  Object.entries(r.verdicts).map(([k, v]) => k + " " + v).join(", ");

// success per axis: a chart (rate with its interval per value) and the table beside it
for (const p of data.parameters) {
  const groups = r.groups.filter((g) => g.parameter === p);
  const w = 80 + 80 * groups.length, h = 180, left = 40, bottom = 150, top = 10;
  const svg = el("svg", { width: w, height: h + 20 });
  for (const y of [0, 0.5, 1]) {
    svg.append(el("line", { x1: left, x2: w - 10, y1: bottom - y * (bottom - top), y2: bottom - y * (bottom - top), stroke: "#ddd" }));
    svg.append(el("text", { x: 4, y: bottom - y * (bottom - top) + 4 }, pct(y)));
  }
  const xs = groups.map((_, i) => left + 40 + 80 * i), ys = groups.map((g) => bottom - g.success.rate * (bottom - top));
  svg.append(el("polyline", { points: xs.map((x, i) => x + "," + ys[i]).join(" "), fill: "none", stroke: "#36c", "stroke-width": 2 }));
  groups.forEach((g, i) => {
    const lo = bottom - g.success.low * (bottom - top), hi = bottom - g.success.high * (bottom - top);
    svg.append(el("line", { x1: xs[i], x2: xs[i], y1: lo, y2: hi, stroke: "#36c" }));
    svg.append(el("circle", { cx: xs[i], cy: ys[i], r: 3, fill: "#36c" }));
    svg.append(el("text", { x: xs[i], y: bottom + 14, "text-anchor": "middle" }, fmt(g.value)));
  });
  svg.append(el("text", { x: left, y: h + 14 }, p));
  const box = document.createElement("div");
  box.append(svg);
  const table = document.createElement("table");
  table.innerHTML = "<tr><th>" + p + "</th><th>success</th></tr>";
  for (const g of groups) {
    const tr = table.insertRow();
    tr.insertCell().textContent = fmt(g.value);
    tr.insertCell().textContent = rateText(g.success);
  }
  box.append(table);
  document.getElementById("axes").append(box);
}

// heat map over two chosen axes: numeric axes with more than 8 values in 8 equal bins
function binsOf(p) {
  const values = data.rows.map((row) => row[col(p)]);
  const distinct = [...new Set(values.map((v) => JSON.stringify(v)))].map((v) => JSON.parse(v));
  if (distinct.length <= 8 || !distinct.every((v) => typeof v === "number")) {
    distinct.sort((a, b) => (a < b ? -1 : a > b ? 1 : 0));
    return { labels: distinct.map(fmt), index: (v) => distinct.findIndex((d) => JSON.stringify(d) === JSON.stringify(v)) };
  }
  const lo = Math.min(...distinct), hi = Math.max(...distinct), n = 8, step = (hi - lo) / n;
  const labels = [...Array(n).keys()].map((k) => fmt(lo + k * step) + "–" + fmt(lo + (k + 1) * step));
  return { labels, index: (v) => Math.min(n - 1, Math.floor((v - lo) / step)) };
}
function drawHeat() {
  const py = document.getElementById("heat-y").value, px = document.getElementById("heat-x").value;
  const by = binsOf(py), bx = binsOf(px), cells = [];
  for (let i = 0; i < by.labels.length; ++i) for (let j = 0; j < bx.labels.length; ++j) cells.push({ row: i, column: j, successes: 0, trials: 0 });
  for (const row of data.rows) {
    const c = cells[by.index(row[col(py)]) * bx.labels.length + bx.index(row[col(px)])];
    c.trials += 1;
    c.successes += row[col("success")] ? 1 : 0;
  }
  state.heat = cells;
  const cw = 90, ch = 28, left = 120, top = 20;
  const svg = el("svg", { width: left + cw * bx.labels.length + 10, height: top + ch * by.labels.length + 30 });
  bx.labels.forEach((l, j) => svg.append(el("text", { x: left + j * cw + 4, y: 14 }, l)));
  by.labels.forEach((l, i) => svg.append(el("text", { x: 4, y: top + i * ch + 18 }, l)));
  for (const c of cells) {
    const rate = c.trials ? c.successes / c.trials : NaN;
    const fill = c.trials ? "hsl(" + (120 * rate).toFixed(0) + ",70%,60%)" : "#eee";
    svg.append(el("rect", { x: left + c.column * cw, y: top + c.row * ch, width: cw - 2, height: ch - 2, fill }));
    svg.append(el("text", { x: left + c.column * cw + 6, y: top + c.row * ch + 18 }, c.trials ? c.successes + "/" + c.trials : "–"));
  }
  svg.append(el("text", { x: left, y: top + ch * by.labels.length + 20 }, py + " (rows) × " + px + " (columns): successes / trials"));
  const box = document.getElementById("heat");
  box.textContent = "";
  box.append(svg);
}
for (const id of ["heat-y", "heat-x"]) {
  const select = document.getElementById(id);
  for (const p of data.parameters) select.append(new Option(p, p));
  select.onchange = drawHeat;
}
if (data.parameters.length > 1) document.getElementById("heat-x").value = data.parameters[1];
if (data.parameters.length > 0) drawHeat();

// each metric's distribution: a histogram with its median and 95th percentile
for (const m of data.metrics) {
  const values = data.rows.map((row) => row[col(m.name)]).filter((v) => typeof v === "number" && isFinite(v));
  const summary = r.metrics[m.name] || {};
  const w = 260, h = 140, bottom = 110, n = 20;
  const svg = el("svg", { width: w, height: h });
  svg.append(el("text", { x: 4, y: 12 }, m.name + (m.unit ? " [" + m.unit + "]" : "") + ", " + values.length + " trials"));
  if (values.length > 0) {
    const lo = Math.min(...values), hi = Math.max(...values), span = hi - lo || 1;
    const counts = new Array(n).fill(0);
    for (const v of values) counts[Math.min(n - 1, Math.floor(((v - lo) / span) * n))] += 1;
    const most = Math.max(...counts), x = (v) => 10 + ((v - lo) / span) * (w - 20);
    counts.forEach((c, k) => svg.append(el("rect", { x: 10 + k * (w - 20) / n, y: bottom - 85 * c / most, width: (w - 20) / n - 1, height: 85 * c / most, fill: "#7a9" })));
    for (const [name, colour] of [["median", "#c33"], ["p95", "#c83"]])
      if (typeof summary[name] === "number") svg.append(el("line", { x1: x(summary[name]), x2: x(summary[name]), y1: 20, y2: bottom, stroke: colour }));
    svg.append(el("text", { x: 10, y: bottom + 14 }, fmt(lo)));
    svg.append(el("text", { x: w - 60, y: bottom + 14 }, fmt(hi)));
    svg.append(el("text", { x: 10, y: bottom + 28 }, "median " + fmt(summary.median) + " (red), p95 " + fmt(summary.p95) + " (orange)"));
  }
  document.getElementById("metrics").append(svg);
}

// the trials, filtered; a recorded trial links to its replay, recording and video
const verdicts = document.getElementById("verdict");
for (const v of Object.keys(r.verdicts)) verdicts.append(new Option(v, v));
function drawTrials() {
  const text = document.getElementById("filter").value.toLowerCase();
  const verdict = verdicts.value, outcome = document.getElementById("outcome").value;
  const shown = data.rows.filter((row) =>
    (!verdict || row[col("verdict")] === verdict) &&
    (!outcome || String(row[col("success")] ? 1 : 0) === outcome) &&
    (!text || row.some((v) => JSON.stringify(v).toLowerCase().includes(text))));
  state.shownRows = shown.length;
  const table = document.getElementById("trials");
  table.textContent = "";
  const head = table.insertRow();
  for (const c of data.columns.concat(["links"])) { const th = document.createElement("th"); th.textContent = c; head.append(th); }
  for (const row of shown.slice(0, 1000)) {
    const tr = table.insertRow();
    if (!row[col("success")]) tr.className = "failed";
    for (const v of row) { const td = tr.insertCell(); td.textContent = v === null ? "" : fmt(v); if (typeof v === "string") td.className = "text"; }
    const td = tr.insertCell();
    const links = data.links[String(row[col("trial")])] || {};
    for (const [name, href] of Object.entries(links)) { const a = document.createElement("a"); a.href = href; a.textContent = name; td.append(a, " "); }
  }
  document.getElementById("shown").textContent = shown.length + " of " + data.rows.length + " trials" + (shown.length > 1000 ? " (the first 1000 listed)" : "");
}
for (const id of ["filter", "verdict", "outcome"]) document.getElementById(id).oninput = drawTrials;
drawTrials();
</script></body></html>
)html";

}  // namespace

const std::string& sweep_dashboard_page() {
  static const std::string page(kPage);
  return page;
}

}  // namespace mjarm
