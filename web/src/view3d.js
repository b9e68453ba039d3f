// The 3D view: target surface, stitch mesh, relaxed and predicted shapes (coloured by a
// per-stitch quantity), yarn (tubes, or lines above a size limit) and wale
// curves, with orbit controls. Renders on demand (only when something changes).
import * as THREE from "three";
import { OrbitControls } from "three/examples/jsm/controls/OrbitControls.js";
import {
  STITCH_TYPE_NAMES, STITCH_TYPE_COLOURS, categorical, viridis, viridisCss, css,
} from "./colours.js";

/// Above this many yarn points in total the yarn is drawn as lines, not tubes.
export const TUBE_POINT_LIMIT = 40000;
/// Above this many stitches the stitch outlines start hidden.
const EDGE_STITCH_LIMIT = 40000;

function decodePositions(ints, scale) {
  const out = new Float32Array(ints.length);
  for (let i = 0; i < ints.length; ++i) out[i] = ints[i] * scale;
  return out;
}

/// Non-indexed triangles of a stitch mesh (quads split along corner 0-2) and,
/// for every rendered vertex, the stitch it belongs to.
function buildStitchGeometry(sm, scale) {
  const pos = decodePositions(sm.positions, scale);
  const corners = sm.corners;
  const ns = corners.length / 4;
  let nv = 0;
  for (let s = 0; s < ns; ++s) nv += corners[4 * s + 3] < 0 ? 3 : 6;
  const p = new Float32Array(nv * 3);
  const owner = new Int32Array(nv);
  let k = 0;
  const put = (v, s) => {
    p[3 * k] = pos[3 * v];
    p[3 * k + 1] = pos[3 * v + 1];
    p[3 * k + 2] = pos[3 * v + 2];
    owner[k++] = s;
  };
  for (let s = 0; s < ns; ++s) {
    const a = corners[4 * s], b = corners[4 * s + 1], c = corners[4 * s + 2], d = corners[4 * s + 3];
    put(a, s); put(b, s); put(c, s);
    if (d >= 0) { put(a, s); put(c, s); put(d, s); }
  }
  const geometry = new THREE.BufferGeometry();
  geometry.setAttribute("position", new THREE.BufferAttribute(p, 3));
  geometry.setAttribute("color", new THREE.BufferAttribute(new Float32Array(nv * 3), 3));
  geometry.computeVertexNormals();
  return { geometry, owner, numStitches: ns, positions: pos };
}

/// The stitch outlines (every stitch's sides; an interior side is drawn by
/// both its stitches).
function buildEdgeGeometry(sm, pos) {
  const corners = sm.corners;
  const ns = corners.length / 4;
  let n = 0;
  for (let s = 0; s < ns; ++s) n += corners[4 * s + 3] < 0 ? 6 : 8;
  const idx = pos.length / 3 > 65535 ? new Uint32Array(n) : new Uint16Array(n);
  let k = 0;
  for (let s = 0; s < ns; ++s) {
    const m = corners[4 * s + 3] < 0 ? 3 : 4;
    for (let i = 0; i < m; ++i) {
      idx[k++] = corners[4 * s + i];
      idx[k++] = corners[4 * s + ((i + 1) % m)];
    }
  }
  const eg = new THREE.BufferGeometry();
  eg.setAttribute("position", new THREE.BufferAttribute(pos, 3));
  eg.setIndex(new THREE.BufferAttribute(idx, 1));
  return eg;
}

function buildTriMesh(m, scale) {
  const g = new THREE.BufferGeometry();
  g.setAttribute("position", new THREE.BufferAttribute(decodePositions(m.positions, scale), 3));
  const n = m.positions.length / 3;
  g.setIndex(n > 65535 ? new THREE.Uint32BufferAttribute(m.triangles, 1) : new THREE.Uint16BufferAttribute(m.triangles, 1));
  g.computeVertexNormals();
  return g;
}

/// A triangle mesh as separate triangles (three corners each, no index), so
/// that a triangle can have a colour of its own: the garment of a cloth run
/// coloured by a per-frame field (per triangle or per vertex).
function buildFieldMesh(m, scale) {
  const g = new THREE.BufferGeometry();
  g.setAttribute("position", new THREE.BufferAttribute(new Float32Array(m.triangles.length * 3), 3));
  g.setAttribute("color", new THREE.BufferAttribute(new Float32Array(m.triangles.length * 3), 3));
  setCornerPositions(g, m.triangles, m.positions, scale);
  return g;
}

/// Writes vertex positions (integers in units of `scale`) to the corners of
/// a geometry of buildFieldMesh().
function setCornerPositions(geometry, triangles, ints, scale) {
  const attr = geometry.getAttribute("position");
  const arr = attr.array;
  for (let c = 0; c < triangles.length; ++c) {
    const v = 3 * triangles[c];
    arr[3 * c] = ints[v] * scale;
    arr[3 * c + 1] = ints[v + 1] * scale;
    arr[3 * c + 2] = ints[v + 2] * scale;
  }
  attr.needsUpdate = true;
  geometry.computeVertexNormals();
}

/// The value of a per-frame field (report_data()'s animation fields) at frame
/// k for corner c of the triangles (null where there is none).
export function fieldValue(field, k, triangles, c) {
  const f = field.frames[Math.min(k, field.frames.length - 1)];
  const v = f[field.per === "triangle" ? Math.floor(c / 3) : triangles[c]];
  return v === null || v === undefined ? null : v * field.step;
}

/// The legend of a per-frame field: viridis over its range of all frames.
export function fieldLegend(field) {
  return {
    kind: "ramp", title: `${field.label} (${field.unit})`, lo: field.range[0], hi: field.range[1],
    note: field.measure || "",
  };
}

/// Colours (rgb 0..1, three per corner) of a field at frame k; corners
/// without a value are grey; `field` null gives the garment's plain colour.
function setFieldColours(geometry, triangles, field, k) {
  const attr = geometry.getAttribute("color");
  const arr = attr.array;
  const lo = field ? field.range[0] : 0;
  const span = field && field.range[1] > lo ? field.range[1] - lo : 1;
  for (let c = 0; c < triangles.length; ++c) {
    const v = field ? fieldValue(field, k, triangles, c) : null;
    const rgb = !field ? [159, 197, 168] : v === null ? [200, 200, 200] : viridis((v - lo) / span);
    arr[3 * c] = rgb[0] / 255;
    arr[3 * c + 1] = rgb[1] / 255;
    arr[3 * c + 2] = rgb[2] / 255;
  }
  attr.needsUpdate = true;
}

/// The colour modes a stitch mesh offers: id, label, and a function giving
/// per-stitch colours (Float32Array rgb 0..1) and a legend description.
export function colourModes(sm) {
  const modes = [{ id: "type", label: "stitch type" }];
  if (sm.course && sm.course.some((v) => v >= 0)) modes.push({ id: "course", label: "course" });
  if (sm.wale && sm.wale.some((v) => v >= 0)) modes.push({ id: "wale", label: "wale" });
  modes.push({ id: "direction", label: "direction" });
  if (sm.yarn) modes.push({ id: "yarn", label: "yarn" });
  for (const name of Object.keys(sm.scalars || {})) modes.push({ id: "scalar:" + name, label: name.replace(/_/g, " ") });
  return modes;
}

function sequential(values, title) {
  let lo = Infinity, hi = -Infinity;
  for (const v of values) {
    if (v === null || !Number.isFinite(v) || v < -0.5e300) continue;
    if (v < lo) lo = v;
    if (v > hi) hi = v;
  }
  if (!(lo <= hi)) { lo = 0; hi = 1; }
  const span = hi > lo ? hi - lo : 1;
  const rgb = values.map((v) => (v === null || !Number.isFinite(v) ? [200, 200, 200] : viridis((v - lo) / span)));
  return { rgb, legend: { kind: "ramp", title, lo, hi } };
}

/// Per-stitch colours (0..255) for a mode, and the legend.
export function stitchColours(sm, mode) {
  const ns = sm.corners.length / 4;
  if (mode === "type") {
    const rgb = Array.from(sm.type, (t) => STITCH_TYPE_COLOURS[t] || [128, 128, 128]);
    const present = new Set(sm.type);
    return {
      rgb,
      legend: { kind: "swatches", items: STITCH_TYPE_NAMES.map((n, i) => ({ label: n, rgb: STITCH_TYPE_COLOURS[i] })).filter((_, i) => present.has(i)) },
    };
  }
  if (mode === "course" || mode === "wale") {
    const vals = Array.from(sm[mode], (v) => (v >= 0 ? v : null));
    return sequential(vals, mode);
  }
  if (mode === "direction") {
    const rgb = Array.from(sm.direction, (d) => (d > 0 ? [166, 206, 227] : [31, 120, 180]));
    return { rgb, legend: { kind: "swatches", items: [{ label: "left to right", rgb: [166, 206, 227] }, { label: "right to left", rgb: [31, 120, 180] }] } };
  }
  if (mode === "yarn") {
    const y = sm.yarn || new Array(ns).fill(0);
    const ids = [...new Set(y)].sort((a, b) => a - b);
    return { rgb: Array.from(y, categorical), legend: { kind: "swatches", items: ids.map((i) => ({ label: "yarn " + i, rgb: categorical(i) })) } };
  }
  if (mode.startsWith("scalar:")) {
    const name = mode.slice(7);
    return sequential(Array.from(sm.scalars[name]), name.replace(/_/g, " "));
  }
  throw new Error("unknown colour mode " + mode);
}

function fmt(v) {
  if (Number.isInteger(v)) return String(v);
  return Number(v.toPrecision(4)).toString();
}

export function renderLegend(el, legend) {
  el.textContent = "";
  if (!legend) return;
  if (legend.kind === "swatches") {
    for (const it of legend.items) {
      const span = document.createElement("span");
      const sw = document.createElement("span");
      sw.className = "swatch";
      sw.style.background = css(it.rgb);
      span.append(sw, it.label);
      el.append(span);
    }
  } else {
    const span = document.createElement("span");
    const ramp = document.createElement("span");
    ramp.className = "ramp";
    ramp.style.background = viridisCss();
    span.append(`${legend.title}: ${fmt(legend.lo)}`, ramp, fmt(legend.hi));
    el.append(span);
    if (legend.note) {
      const note = document.createElement("span");
      note.className = "note";
      note.dataset.legend = "measure";
      note.textContent = legend.note;
      el.append(note);
    }
  }
}

/// A polyline as a three.js curve, parametrised by point index (so a tube
/// with n-1 segments passes through every point; no arc-length tables).
class PolylineCurve extends THREE.Curve {
  constructor(points) {
    super();
    this.points = points;
  }
  getPoint(t, target = new THREE.Vector3()) {
    const n = this.points.length - 1;
    const x = Math.min(Math.max(t, 0), 1) * n;
    const i = Math.min(Math.floor(x), n - 1);
    return target.copy(this.points[i]).lerp(this.points[i + 1], x - i);
  }
  getPointAt(u, target) {
    return this.getPoint(u, target);
  }
  getTangent(t, target = new THREE.Vector3()) {
    const n = this.points.length - 1;
    const i = Math.round(Math.min(Math.max(t, 0), 1) * n);
    // Average of the segments around point i (one-sided at the ends).
    const a = this.points[Math.max(i - 1, 0)], b = this.points[Math.min(i + 1, n)];
    target.subVectors(b, a);
    if (target.lengthSq() === 0) target.set(1, 0, 0);
    return target.normalize();
  }
  getTangentAt(u, target) {
    return this.getTangent(u, target);
  }
}

function polylineGroup(sets, scale, colourOf, radius, forceLines) {
  const group = new THREE.Group();
  let total = 0;
  for (const p of sets.polylines) total += p.length / 3;
  const tubes = !forceLines && total <= TUBE_POINT_LIMIT && radius > 0;
  sets.polylines.forEach((ints, i) => {
    if (ints.length < 6) return;
    const pos = decodePositions(ints, scale);
    const rgb = colourOf(i);
    const colour = new THREE.Color(rgb[0] / 255, rgb[1] / 255, rgb[2] / 255);
    if (tubes) {
      const pts = [];
      for (let k = 0; k < pos.length; k += 3) pts.push(new THREE.Vector3(pos[k], pos[k + 1], pos[k + 2]));
      const geo = new THREE.TubeGeometry(new PolylineCurve(pts), pts.length - 1, radius, 6, false);
      group.add(new THREE.Mesh(geo, new THREE.MeshLambertMaterial({ color: colour })));
    } else {
      const geo = new THREE.BufferGeometry();
      geo.setAttribute("position", new THREE.BufferAttribute(pos, 3));
      group.add(new THREE.Line(geo, new THREE.LineBasicMaterial({ color: colour })));
    }
  });
  group.userData.tubes = tubes;
  group.userData.points = total;
  return group;
}

function meanEdgeLength(sm, scale) {
  const c = sm.corners, p = sm.positions;
  let sum = 0, n = 0;
  for (let s = 0; s < c.length / 4 && n < 20000; ++s) {
    const a = c[4 * s], b = c[4 * s + 1];
    const dx = p[3 * a] - p[3 * b], dy = p[3 * a + 1] - p[3 * b + 1], dz = p[3 * a + 2] - p[3 * b + 2];
    sum += Math.sqrt(dx * dx + dy * dy + dz * dz) * scale;
    ++n;
  }
  return n ? sum / n : 0;
}

/// Builds the 3D view in `box` (a positioned div) and returns its controls.
/// `layersEl`, `modesEl`, `legendEl` receive the toolbar and legend.
export function createView3d(box, data, layersEl, modesEl, legendEl, onFirstFrame) {
  const scale = data.scale;
  const canvas = document.createElement("canvas");
  canvas.id = "view3d";
  box.append(canvas);
  let renderer;
  try {
    // Multisampling costs much on large scenes with software rendering.
    const big = (data.stitch_mesh ? data.stitch_mesh.corners.length / 4 : 0) > 20000 ||
      (data.yarn ? data.yarn.polylines.reduce((n, p) => n + p.length / 3, 0) : 0) > 100000;
    renderer = new THREE.WebGLRenderer({ canvas, antialias: !big, preserveDrawingBuffer: true });
  } catch (e) {
    box.innerHTML = `<p class="error">This browser cannot show the 3D view (WebGL unavailable: ${e.message}).</p>`;
    return null;
  }
  renderer.setPixelRatio(window.devicePixelRatio || 1);
  renderer.setClearColor(0xffffff, 1);
  const scene = new THREE.Scene();
  const camera = new THREE.PerspectiveCamera(40, 1, 0.1, 1e6);
  scene.add(camera);
  scene.add(new THREE.AmbientLight(0xffffff, 0.55));
  const light = new THREE.DirectionalLight(0xffffff, 1.6);
  light.position.set(0.3, 0.5, 1);
  camera.add(light);
  const controls = new OrbitControls(camera, canvas);

  const layers = [];  // {id, label, object, visible}
  const stitchLayers = [];  // {sm, built, mesh}
  const addLayer = (id, label, object, visible) => {
    object.visible = visible;
    scene.add(object);
    layers.push({ id, label, object });
  };

  const sm = data.stitch_mesh;
  const relaxedStitch = data.relaxed && data.relaxed.kind === "stitch_mesh" ? data.relaxed : null;
  const predictedStitch = data.predicted && data.predicted.kind === "stitch_mesh" ? data.predicted : null;
  const mainSm = sm || relaxedStitch || predictedStitch;

  // Outlines are built when first shown (they are hidden on large meshes).
  const showEdges = (layer, on) => {
    if (on && !layer.edges) {
      const mat = new THREE.LineBasicMaterial({ color: 0x33404d, transparent: true, opacity: 0.45 });
      layer.edges = new THREE.LineSegments(buildEdgeGeometry(layer.sm, layer.built.positions), mat);
      layer.group.add(layer.edges);
    }
    if (layer.edges) layer.edges.visible = on;
  };

  const makeStitchLayer = (s, id, label, visible) => {
    const built = buildStitchGeometry(s, scale);
    const mat = new THREE.MeshLambertMaterial({
      vertexColors: true, side: THREE.DoubleSide, flatShading: true,
      polygonOffset: true, polygonOffsetFactor: 1, polygonOffsetUnits: 1,
    });
    const group = new THREE.Group();
    const mesh = new THREE.Mesh(built.geometry, mat);
    group.add(mesh);
    addLayer(id, label, group, visible);
    const layer = { sm: s, label, built, mesh, group, edges: null, legend: null, hasMode: false };
    stitchLayers.push(layer);
    if (built.numStitches <= EDGE_STITCH_LIMIT) showEdges(layer, true);
  };

  // A cloth run's layers are the body and the garment.
  const cloth = !!(data.metrics && data.metrics.command === "cloth");
  if (data.target) {
    const mat = new THREE.MeshLambertMaterial({
      color: 0xb8bec6, side: THREE.DoubleSide, transparent: !!mainSm, opacity: mainSm ? 0.35 : 1, depthWrite: !mainSm,
    });
    addLayer("target", cloth ? "body" : "target surface", new THREE.Mesh(buildTriMesh(data.target, scale), mat), true);
  }
  if (sm) makeStitchLayer(sm, "stitch_mesh", "stitch mesh", true);
  // The garment of a cloth run with its per-frame fields (stress, sliding).
  const animFields = data.relaxed && data.relaxed.kind === "mesh" && data.animation && data.animation.layers &&
    data.animation.layers.relaxed && data.animation.layers.relaxed.fields;
  let fieldMesh = null;
  if (data.relaxed) {
    if (relaxedStitch) makeStitchLayer(relaxedStitch, "relaxed", "relaxed", !sm);
    else if (animFields && Object.keys(animFields).length) {
      const mat = new THREE.MeshLambertMaterial({ vertexColors: true, side: THREE.DoubleSide });
      fieldMesh = new THREE.Mesh(buildFieldMesh(data.relaxed, scale), mat);
      addLayer("relaxed", cloth ? "garment" : "relaxed", fieldMesh, !sm);
    } else {
      const mat = new THREE.MeshLambertMaterial({ color: 0x9fc5a8, side: THREE.DoubleSide });
      addLayer("relaxed", cloth ? "garment" : "relaxed", new THREE.Mesh(buildTriMesh(data.relaxed, scale), mat), !sm);
    }
  }
  // The converged predicted shape of a design (predicted.ply), hidden at
  // start when the stitch mesh or the relaxed shape is shown.
  if (data.predicted) {
    const shown = !sm && !data.relaxed;
    if (predictedStitch) makeStitchLayer(predictedStitch, "predicted", "predicted", shown);
    else {
      const mat = new THREE.MeshLambertMaterial({ color: 0xe0b07a, side: THREE.DoubleSide });
      addLayer("predicted", "predicted", new THREE.Mesh(buildTriMesh(data.predicted, scale), mat), shown);
    }
  }
  let yarnInfo = null;
  if (data.yarn && data.yarn.polylines.length) {
    const edge = mainSm ? meanEdgeLength(mainSm, scale) : 0;
    const radius = data.yarn_radius > 0 ? data.yarn_radius : edge > 0 ? 0.12 * edge : 0.3;
    const ids = data.yarn.names.map((n) => {
      const m = /(\d+)\s*$/.exec(n);
      return m ? Number(m[1]) : 0;
    });
    let points = 0;
    for (const p of data.yarn.polylines) points += p.length / 3;
    const tubes = points <= TUBE_POINT_LIMIT;
    const build = () => polylineGroup(data.yarn, scale, (i) => categorical(ids[i]), radius, false);
    // A large yarn (drawn as lines) is built when first shown, so that the
    // page opens quickly; it starts hidden unless nothing else is there.
    const shown = tubes || layers.length === 0;
    yarnInfo = { tubes, points, hiddenAtStart: !shown };
    const holder = new THREE.Group();
    if (shown) holder.add(build());
    else holder.userData.build = build;
    addLayer("yarn", tubes ? "yarn" : "yarn (lines)", holder, shown);
  }
  if (data.wales && data.wales.polylines.length) {
    addLayer("wales", "wale curves", polylineGroup(data.wales, scale, () => [20, 20, 20], 0, true), true);
  }
  // Findings of the virtual machine placed on the fabric (report.json
  // "diagnostics" with a "position", written by `simulate --report`).
  const placed = data.metrics && Array.isArray(data.metrics.diagnostics)
    ? data.metrics.diagnostics.filter((d) => Array.isArray(d.position)) : [];
  if (placed.length) {
    const edge = mainSm ? meanEdgeLength(mainSm, scale) : 1;
    const group = new THREE.Group();
    const geo = new THREE.SphereGeometry(0.45 * edge, 12, 8);
    const mats = {
      error: new THREE.MeshLambertMaterial({ color: 0xd0021b }),
      warning: new THREE.MeshLambertMaterial({ color: 0xf5a623 }),
    };
    for (const d of placed) {
      const m = new THREE.Mesh(geo, mats[d.severity] || mats.warning);
      m.position.set(d.position[0], d.position[1], d.position[2]);
      group.add(m);
    }
    addLayer("findings", `findings (${placed.length})`, group, true);
  }

  // Rendering is on demand and coalesced: any number of changes before the
  // next animation frame give one render.
  let pending = false, first = true;
  const renderNow = () => renderer.render(scene, camera);
  const render = () => {
    if (pending) return;
    pending = true;
    requestAnimationFrame(() => {
      pending = false;
      renderNow();
      if (first) {
        first = false;
        // The frame is on screen when the next one can start.
        requestAnimationFrame(() => onFirstFrame && onFirstFrame());
      }
    });
  };

  // Layer toggles.
  for (const layer of layers) {
    const label = document.createElement("label");
    const cb = document.createElement("input");
    cb.type = "checkbox";
    cb.checked = layer.object.visible;
    cb.dataset.layer = layer.id;
    cb.addEventListener("change", () => {
      const o = layer.object;
      if (cb.checked && o.userData.build) {
        o.add(o.userData.build());
        delete o.userData.build;
      }
      o.visible = cb.checked;
      if (currentMode && stitchLayers.some((l) => l.group === o)) renderLegend(legendEl, stitchLegend());
      render();
    });
    label.append(cb, layer.label);
    layersEl.append(label);
  }
  // The animation (cloth runs: animation.glb moves the garment and the body
  // layers): a play button and a frame slider; the page opens at the last frame.
  let animation = null;
  const anim = data.animation && data.animation.layers;
  const moving = [];
  if (anim) {
    for (const l of layers) {
      const a = anim[l.id];
      if (a && l.object.isMesh && a.frames.length) moving.push({ object: l.object, geometry: l.object.geometry, a });
    }
  }
  // The field the garment is coloured by (null: plain) and the frame shown.
  let field = null, fieldFrame = anim && anim.relaxed ? anim.relaxed.frames.length - 1 : 0;
  const colourGarment = () => {
    if (!fieldMesh) return;
    setFieldColours(fieldMesh.geometry, data.relaxed.triangles, field ? animFields[field] : null, fieldFrame);
    render();
  };
  if (moving.length) {
    const times = moving[0].a.times;
    const n = times.length;
    const wrap = document.createElement("span");
    wrap.className = "animation";
    const play = document.createElement("button");
    play.type = "button";
    play.dataset.animation = "play";
    play.textContent = "play";
    const slider = document.createElement("input");
    slider.type = "range";
    slider.min = "0";
    slider.max = String(n - 1);
    slider.step = "1";
    slider.value = String(n - 1);
    slider.dataset.animation = "frame";
    const label = document.createElement("span");
    label.dataset.animation = "time";
    const setFrame = (k) => {
      k = Math.max(0, Math.min(n - 1, k | 0));
      for (const m of moving) {
        const f = m.a.frames[Math.min(k, m.a.frames.length - 1)];
        if (m.object === fieldMesh) {
          setCornerPositions(m.geometry, data.relaxed.triangles, f, scale);
          continue;
        }
        const attr = m.geometry.getAttribute("position");
        const arr = attr.array;
        for (let i = 0; i < f.length; ++i) arr[i] = f[i] * scale;
        attr.needsUpdate = true;
        m.geometry.computeVertexNormals();
      }
      fieldFrame = k;
      colourGarment();
      slider.value = String(k);
      label.textContent = `frame ${k} / ${n - 1}, ${times[k].toFixed(3)} s`;
      animation.frame = k;
      render();
    };
    let timer = null;
    const stop = () => {
      if (timer) cancelAnimationFrame(timer);
      timer = null;
      play.textContent = "play";
    };
    const start = () => {
      const t0 = performance.now();
      const from = animation.frame >= n - 1 ? 0 : animation.frame;
      const base = times[from];
      const tick = () => {
        const t = base + (performance.now() - t0) / 1000;
        let k = from;
        while (k + 1 < n && times[k + 1] <= t) ++k;
        if (k !== animation.frame) setFrame(k);
        if (k >= n - 1) { stop(); return; }
        timer = requestAnimationFrame(tick);
      };
      play.textContent = "pause";
      setFrame(from);
      timer = requestAnimationFrame(tick);
    };
    play.addEventListener("click", () => (timer ? stop() : start()));
    slider.addEventListener("input", () => { stop(); setFrame(Number(slider.value)); });
    wrap.append(play, slider, label);
    layersEl.append(wrap);
    animation = { frame: n - 1, frames: n, setFrame };
    label.textContent = `frame ${n - 1} / ${n - 1}, ${times[n - 1].toFixed(3)} s`;
  }

  if (stitchLayers.length) {
    const label = document.createElement("label");
    const cb = document.createElement("input");
    cb.type = "checkbox";
    cb.dataset.layer = "edges";
    cb.checked = !!(stitchLayers[0].edges && stitchLayers[0].edges.visible);
    cb.addEventListener("change", () => { for (const l of stitchLayers) showEdges(l, cb.checked); render(); });
    label.append(cb, "stitch outlines");
    layersEl.append(label);
  }

  // Colour modes (of the stitch mesh; the relaxed and predicted stitch meshes
  // follow when they have the field, each on its own range). The legend is
  // that of the first layer shown that has the mode (named when it is not
  // the stitch mesh), else the stitch mesh's.
  let currentMode = null;
  function stitchLegend() {
    const l = stitchLayers.find((x) => x.group.visible && x.hasMode) || stitchLayers.find((x) => x.sm === mainSm);
    if (!l || !l.legend) return null;
    return l.sm === mainSm || l.legend.kind !== "ramp" ? l.legend : { ...l.legend, title: `${l.legend.title} (${l.label})` };
  }
  const setMode = (mode) => {
    currentMode = mode;
    for (const l of stitchLayers) {
      const ok = colourModes(l.sm).some((m) => m.id === mode);
      const { rgb, legend: lg } = stitchColours(l.sm, ok ? mode : "type");
      l.legend = lg;
      l.hasMode = ok;
      const col = l.built.geometry.getAttribute("color");
      const arr = col.array;
      const owner = l.built.owner;
      for (let k = 0; k < owner.length; ++k) {
        const c = rgb[owner[k]];
        arr[3 * k] = c[0] / 255;
        arr[3 * k + 1] = c[1] / 255;
        arr[3 * k + 2] = c[2] / 255;
      }
      col.needsUpdate = true;
    }
    for (const b of modesEl.querySelectorAll("button")) b.classList.toggle("active", b.dataset.colour === mode);
    renderLegend(legendEl, stitchLegend());
    render();
  };
  if (mainSm) {
    const span = document.createElement("span");
    span.textContent = "colour by";
    modesEl.append(span);
    for (const m of colourModes(mainSm)) {
      const b = document.createElement("button");
      b.type = "button";
      b.textContent = m.label;
      b.dataset.colour = m.id;
      b.addEventListener("click", () => setMode(m.id));
      modesEl.append(b);
    }
  }

  // Colour modes of the cloth garment: its per-frame fields, or plain.
  const setField = (name) => {
    field = name && animFields && animFields[name] ? name : null;
    for (const b of modesEl.querySelectorAll("button[data-field]")) b.classList.toggle("active", b.dataset.field === (field || ""));
    renderLegend(legendEl, field ? fieldLegend(animFields[field]) : null);
    colourGarment();
  };
  if (fieldMesh) {
    const span = document.createElement("span");
    span.textContent = "colour by";
    modesEl.append(span);
    // Stress first: the page opens with it.
    const names = Object.keys(animFields).sort((a, b) => (a === "stress_kpa" ? -1 : b === "stress_kpa" ? 1 : a < b ? -1 : 1));
    for (const name of [...names, ""]) {
      const b = document.createElement("button");
      b.type = "button";
      b.textContent = name ? `${animFields[name].label} (${animFields[name].unit})` : "plain";
      b.dataset.field = name;
      b.addEventListener("click", () => setField(name));
      modesEl.append(b);
    }
    setField(names[0]);
  }

  // Camera: look at everything from above, slightly tilted.
  const bbox = new THREE.Box3();
  for (const l of layers) bbox.expandByObject(l.object);
  const centre = bbox.isEmpty() ? new THREE.Vector3() : bbox.getCenter(new THREE.Vector3());
  const radius = bbox.isEmpty() ? 10 : Math.max(bbox.getSize(new THREE.Vector3()).length() / 2, 1e-3);
  const fit = () => {
    const dir = new THREE.Vector3(0.25, -0.55, 1).normalize();
    const dist = (radius / Math.sin(THREE.MathUtils.degToRad(camera.fov / 2))) * 0.8;
    camera.position.copy(centre).addScaledVector(dir, dist);
    camera.near = dist / 1000;
    camera.far = dist * 10 + radius * 4;
    camera.up.set(0, 1, 0);
    camera.updateProjectionMatrix();
    controls.target.copy(centre);
    controls.update();
  };
  let size = [0, 0];
  const resize = () => {
    const w = Math.max(box.clientWidth, 1), h = Math.max(box.clientHeight, 1);
    if (w === size[0] && h === size[1]) return;
    size = [w, h];
    renderer.setSize(w, h, false);
    camera.aspect = w / h;
    camera.updateProjectionMatrix();
    render();
  };
  fit();
  controls.addEventListener("change", render);
  new ResizeObserver(resize).observe(box);
  resize();
  if (mainSm) setMode("type");
  render();
  /// Renders once and waits for the GPU (reads a pixel back): the time of one frame in ms.
  const measureRender = () => {
    const t = performance.now();
    renderNow();
    const gl = renderer.getContext();
    gl.readPixels(0, 0, 1, 1, gl.RGBA, gl.UNSIGNED_BYTE, new Uint8Array(4));
    return performance.now() - t;
  };
  return { render, setMode, measureRender, setLayer: (id, on) => {
    for (const l of layers) if (l.id === id) l.object.visible = on;
  }, fit: () => { fit(); render(); }, mode: () => currentMode, yarnInfo, layers: layers.map((l) => l.id),
  animation, fields: fieldMesh ? {
    names: Object.keys(animFields), current: () => field, set: setField,
    // What the page shows for corner c (3 t + i of triangle t) at the frame shown: value and rgb 0..1.
    value: (c) => (field ? fieldValue(animFields[field], fieldFrame, data.relaxed.triangles, c) : null),
    colour: (c) => Array.from(fieldMesh.geometry.getAttribute("color").array.slice(3 * c, 3 * c + 3)),
  } : null };
}
