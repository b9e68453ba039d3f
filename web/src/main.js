// knitforge report viewer: reads the design data embedded in report.html
// (<script type="application/json" id="knitforge-data">, written by
// src/knitforge/report/report_html.cpp) and builds the page. Works from file://
// without any network access: everything is in the one HTML file.
import cssText from "./style.css";
import { createView3d } from "./view3d.js";
import { createMapView } from "./mapview.js";
import { jsonNode } from "./tables.js";
import { knitterSummary } from "./summary.js";

// State for tests and for the load-time measurement (tests/web/).
const state = { ready: false, firstFrameMs: null, error: null };
window.knitforgeReport = state;

function el(tag, attrs = {}, ...children) {
  const e = document.createElement(tag);
  for (const [k, v] of Object.entries(attrs)) {
    if (k === "class") e.className = v;
    else e.setAttribute(k, v);
  }
  e.append(...children);
  return e;
}

function panel(title, id, wide) {
  const sec = el("section", { class: "panel" + (wide ? " wide" : ""), id });
  sec.append(el("h2", {}, title));
  return sec;
}

function fmtBytes(n) {
  if (n < 1024) return n + " B";
  if (n < 1024 * 1024) return (n / 1024).toFixed(1) + " kB";
  return (n / 1024 / 1024).toFixed(1) + " MB";
}

function build(data) {
  const style = document.createElement("style");
  style.textContent = cssText;
  document.head.append(style);
  document.title = `knitforge report: ${data.title}`;

  const header = el("header", {}, el("h1", {}, `knitforge report: ${data.title}`));
  const files = data.files.map((f) => `${f.name} (${fmtBytes(f.bytes)})`).join(" \u00b7 ");
  header.append(el("div", { class: "files" }, files ? "files: " + files : "no files"));
  const main = el("main");
  document.body.append(header, main);

  const done = [];
  const summary = data.metrics ? knitterSummary(data.metrics.machine, data.metrics, data.files) : null;
  if (summary) {
    const sec = panel("For the knitter", "panel-summary", true);
    sec.append(summary);
    main.append(sec);
  }
  const has3d = data.target || data.stitch_mesh || data.relaxed || data.predicted || data.yarn || data.wales;
  if (has3d) {
    const sec = panel("3D view", "panel-3d", !data.map);
    const layers = el("div", { class: "group", id: "layers" }, el("span", {}, "show"));
    const modes = el("div", { class: "group", id: "colour-modes" });
    const fitBtn = el("button", { type: "button", id: "fit-3d" }, "fit");
    sec.append(el("div", { class: "toolbar" }, layers, modes, fitBtn));
    const box = el("div", { class: "canvas-box", id: "view3d-box" });
    const legend = el("div", { class: "legend", id: "legend-3d" });
    const note = el("div", { class: "note", id: "note-3d" }, "drag: rotate \u00b7 right-drag: pan \u00b7 wheel: zoom");
    sec.append(box, legend, note);
    main.append(sec);
    done.push(() => {
      const firstFrame = new Promise((resolve) => {
        const v = createView3d(box, data, layers, modes, legend, resolve);
        state.view3d = v;
        if (!v) resolve();
        else {
          fitBtn.addEventListener("click", v.fit);
          if (v.yarnInfo && !v.yarnInfo.tubes) {
            note.append(` \u00b7 yarn drawn as lines (${v.yarnInfo.points.toLocaleString("en-US")} points)` +
              (v.yarnInfo.hiddenAtStart ? ", hidden at start: tick 'yarn (lines)' to show it" : ""));
          }
        }
      });
      return firstFrame;
    });
  }
  if (data.map) {
    const sec = panel(`Knitting map (${data.map.rows} courses \u00d7 ${data.map.cols} wales)`, "panel-map", !has3d);
    const fitBtn = el("button", { type: "button", id: "fit-map" }, "fit");
    sec.append(el("div", { class: "toolbar" }, el("span", { class: "note" }, "wheel: zoom \u00b7 drag: pan \u00b7 hover: cell"), fitBtn));
    const box = el("div", { class: "canvas-box", id: "map-box" });
    const tooltip = el("div", { class: "tooltip", id: "map-tooltip" });
    tooltip.style.display = "none";
    box.append(tooltip);
    sec.append(box);
    main.append(sec);
    done.push(() => {
      const m = createMapView(box, tooltip, data.map);
      state.mapView = m;
      fitBtn.addEventListener("click", m.fit);
    });
  }
  const findings = data.metrics && Array.isArray(data.metrics.diagnostics) ? data.metrics.diagnostics : null;
  if (findings && findings.length) {
    const sec = panel(`Findings of the virtual machine (${findings.length})`, "panel-findings", true);
    const table = el("table", { class: "kv findings", id: "findings-table" });
    table.append(el("tr", {}, el("th", {}, "line"), el("th", {}, "severity"), el("th", {}, "check"),
      el("th", {}, "on the fabric"), el("th", {}, "message")));
    for (const d of findings.slice(0, 500)) {
      table.append(el("tr", { class: d.severity },
        el("td", { class: "num" }, String(d.line)), el("td", {}, d.severity), el("td", {}, `${d.rule}/${d.check}`),
        el("td", {}, d.position ? `stitch ${d.stitch}` : "\u2013"), el("td", {}, d.message)));
    }
    sec.append(el("div", { class: "tree" }, table));
    if (findings.length > 500) sec.append(el("div", { class: "note" }, `${findings.length - 500} more in report.json`));
    main.append(sec);
  }
  if (data.metrics !== undefined && data.metrics !== null) {
    const sec = panel("Metrics (report.json)", "panel-metrics", false);
    sec.append(el("div", { class: "tree" }, jsonNode(data.metrics)));
    main.append(sec);
  }
  if (data.knitout) {
    const sec = panel("Knitting program (knitout.k)", "panel-knitout", false);
    sec.append(el("div", { class: "tree" }, jsonNode(data.knitout)));
    main.append(sec);
  }
  if (data.notes && data.notes.length) {
    const sec = panel("Notes", "panel-notes", true);
    for (const n of data.notes) sec.append(el("div", { class: "note" }, n));
    main.append(sec);
  }
  return Promise.all(done.map((f) => f()));
}

function start() {
  try {
    const node = document.getElementById("knitforge-data");
    if (!node) throw new Error("the page holds no design data (no #knitforge-data element)");
    const t0 = performance.now();
    const data = JSON.parse(node.textContent);
    state.timings = { start: t0, parsed: performance.now() };
    if (data.format !== "knitforge-report") throw new Error("the embedded data is not a knitforge report");
    const built = build(data);
    state.timings.built = performance.now();
    built.then(() => {
      state.firstFrameMs = performance.now();
      state.ready = true;
    });
  } catch (e) {
    state.error = String(e && e.message ? e.message : e);
    document.body.append(el("p", { class: "error" }, "knitforge report: " + state.error));
    console.error(e);
  }
}

if (document.readyState === "loading") document.addEventListener("DOMContentLoaded", start);
else start();
