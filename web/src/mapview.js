// The 2D knitting map on a canvas, drawn like knitforge's knitting_map.png
// (docs/formats.md): row 0 at the bottom, rows knitted left to right light
// blue, right to left darker blue, shaping stitches with a triangle pointing
// to their apex. Wheel zooms around the cursor, dragging pans, hovering shows
// the cell's course, wale and type.
import {
  CELL_CODES, CELL_NAMES, STITCH_TYPE_COLOURS, MAP_LTR, MAP_RTL, MAP_COLLAPSED, MAP_EMPTY, MAP_GRID,
  categorical, css, mix,
} from "./colours.js";

/// Decodes the map of the data blob into typed arrays.
export function decodeMap(m) {
  const n = m.rows * m.cols;
  if (m.cells.length !== n) throw new Error(`knitting map: ${m.cells.length} cells for ${m.rows} x ${m.cols}`);
  const cells = new Uint8Array(n);
  for (let i = 0; i < n; ++i) {
    const k = CELL_CODES.indexOf(m.cells[i]);
    if (k < 0) throw new Error(`knitting map: unknown cell code '${m.cells[i]}'`);
    cells[i] = k;
  }
  return { rows: m.rows, cols: m.cols, cells, direction: m.direction, yarn: m.yarn || null };
}

function cellColour(map, r, c) {
  const t = map.cells[r * map.cols + c];
  if (t === 6) return MAP_EMPTY;
  if (t === 5) return MAP_COLLAPSED;
  let base = map.direction[r] > 0 ? MAP_LTR : MAP_RTL;
  const y = map.yarn ? map.yarn[r * map.cols + c] : 0;
  if (y !== 0) base = mix(base, categorical(y), 0.45);
  return base;
}

/// Cell description for the tooltip.
export function describeCell(map, r, c) {
  const t = map.cells[r * map.cols + c];
  let s = `course ${r}, wale ${c}: ${CELL_NAMES[t]}`;
  if (t < 5) {
    s += map.direction[r] > 0 ? " (knitted left to right)" : " (knitted right to left)";
    const y = map.yarn ? map.yarn[r * map.cols + c] : 0;
    if (y !== 0) s += `, yarn ${y}`;
  }
  return s;
}

export function createMapView(box, tooltip, mapData) {
  const map = decodeMap(mapData);
  const canvas = document.createElement("canvas");
  canvas.id = "mapview";
  const overlay = document.createElement("canvas");
  overlay.style.position = "absolute";
  overlay.style.left = "0";
  overlay.style.top = "0";
  overlay.style.pointerEvents = "none";
  box.append(canvas, overlay);
  const ctx = canvas.getContext("2d");
  const octx = overlay.getContext("2d");
  let dpr = window.devicePixelRatio || 1;
  let W = 1, H = 1;
  // View: cell size s (CSS px) and the screen position (ox, oy) of the
  // top-left corner of the grid (column 0, top row).
  let s = 10, ox = 0, oy = 0;

  const fit = () => {
    s = Math.max(0.05, Math.min((W - 20) / map.cols, (H - 20) / map.rows));
    ox = (W - s * map.cols) / 2;
    oy = (H - s * map.rows) / 2;
  };

  // One pixel per cell (row rows-1 at the top), scaled up when drawn: fast
  // for large maps, and crisp with smoothing off.
  const bitmap = document.createElement("canvas");
  bitmap.width = map.cols;
  bitmap.height = map.rows;
  {
    const bctx = bitmap.getContext("2d");
    const img = bctx.createImageData(map.cols, map.rows);
    for (let r = 0; r < map.rows; ++r) {
      const i = map.rows - 1 - r;
      for (let c = 0; c < map.cols; ++c) {
        const col = cellColour(map, r, c);
        const k = 4 * (i * map.cols + c);
        img.data[k] = col[0];
        img.data[k + 1] = col[1];
        img.data[k + 2] = col[2];
        img.data[k + 3] = 255;
      }
    }
    bctx.putImageData(img, 0, 0);
  }

  const draw = () => {
    ctx.setTransform(dpr, 0, 0, dpr, 0, 0);
    ctx.fillStyle = "#f0f1f3";
    ctx.fillRect(0, 0, W, H);
    ctx.imageSmoothingEnabled = false;
    ctx.drawImage(bitmap, ox, oy, map.cols * s, map.rows * s);
    const c0 = Math.max(0, Math.floor(-ox / s)), c1 = Math.min(map.cols - 1, Math.floor((W - ox) / s));
    // screen row i (from the top) is map row rows-1-i
    const i0 = Math.max(0, Math.floor(-oy / s)), i1 = Math.min(map.rows - 1, Math.floor((H - oy) / s));
    if (c0 > c1 || i0 > i1) return;
    if (s >= 6) {
      ctx.strokeStyle = css(MAP_GRID);
      ctx.lineWidth = 1;
      ctx.beginPath();
      for (let c = c0; c <= c1 + 1; ++c) {
        const x = Math.round(ox + c * s) + 0.5;
        ctx.moveTo(x, oy + i0 * s);
        ctx.lineTo(x, oy + (i1 + 1) * s);
      }
      for (let i = i0; i <= i1 + 1; ++i) {
        const y = Math.round(oy + i * s) + 0.5;
        ctx.moveTo(ox + c0 * s, y);
        ctx.lineTo(ox + (c1 + 1) * s, y);
      }
      ctx.stroke();
    }
    if (s >= 4) {
      for (let i = i0; i <= i1; ++i) {
        const r = map.rows - 1 - i;
        const y = oy + i * s;
        for (let c = c0; c <= c1; ++c) {
          const t = map.cells[r * map.cols + c];
          if (t < 1 || t > 4) continue;
          const x = ox + c * s;
          const m = s * 0.18;
          const L = x + m, R = x + s - m, T = y + m, B = y + s - m, cx = x + s / 2, cy = y + s / 2;
          ctx.fillStyle = css(STITCH_TYPE_COLOURS[t]);
          ctx.beginPath();
          if (t === 1) { ctx.moveTo(L, cy); ctx.lineTo(R, T); ctx.lineTo(R, B); }  // apex left
          else if (t === 2) { ctx.moveTo(R, cy); ctx.lineTo(L, B); ctx.lineTo(L, T); }  // apex right
          else if (t === 3) { ctx.moveTo(cx, B); ctx.lineTo(R, T); ctx.lineTo(L, T); }  // apex at the bottom
          else { ctx.moveTo(cx, T); ctx.lineTo(L, B); ctx.lineTo(R, B); }  // apex at the top
          ctx.closePath();
          ctx.fill();
        }
      }
    }
  };

  let hover = null;
  const drawOverlay = () => {
    octx.setTransform(dpr, 0, 0, dpr, 0, 0);
    octx.clearRect(0, 0, W, H);
    if (!hover) return;
    const i = map.rows - 1 - hover.r;
    octx.strokeStyle = "#000";
    octx.lineWidth = 2;
    octx.strokeRect(ox + hover.c * s, oy + i * s, s, s);
  };

  const resize = () => {
    dpr = window.devicePixelRatio || 1;
    const first = W === 1 && H === 1;
    W = Math.max(box.clientWidth, 1);
    H = Math.max(box.clientHeight, 1);
    for (const cv of [canvas, overlay]) {
      cv.width = Math.round(W * dpr);
      cv.height = Math.round(H * dpr);
      cv.style.width = W + "px";
      cv.style.height = H + "px";
    }
    if (first) fit();
    draw();
    drawOverlay();
  };

  const cellAt = (x, y) => {
    const c = Math.floor((x - ox) / s);
    const i = Math.floor((y - oy) / s);
    const r = map.rows - 1 - i;
    if (c < 0 || c >= map.cols || r < 0 || r >= map.rows) return null;
    return { r, c };
  };

  let drag = null;
  canvas.addEventListener("pointerdown", (e) => {
    drag = { x: e.clientX, y: e.clientY, ox, oy };
    canvas.setPointerCapture(e.pointerId);
    box.classList.add("dragging");
  });
  canvas.addEventListener("pointerup", (e) => {
    drag = null;
    canvas.releasePointerCapture(e.pointerId);
    box.classList.remove("dragging");
  });
  canvas.addEventListener("pointermove", (e) => {
    const rect = canvas.getBoundingClientRect();
    const x = e.clientX - rect.left, y = e.clientY - rect.top;
    if (drag) {
      ox = drag.ox + (e.clientX - drag.x);
      oy = drag.oy + (e.clientY - drag.y);
      draw();
    }
    const cell = cellAt(x, y);
    hover = cell;
    drawOverlay();
    if (cell) {
      tooltip.textContent = describeCell(map, cell.r, cell.c);
      tooltip.style.display = "block";
      const tx = Math.min(x + 14, W - tooltip.offsetWidth - 4);
      tooltip.style.left = Math.max(0, tx) + "px";
      tooltip.style.top = Math.max(0, y + 16 > H - 24 ? y - 28 : y + 16) + "px";
    } else {
      tooltip.style.display = "none";
    }
  });
  canvas.addEventListener("pointerleave", () => {
    hover = null;
    tooltip.style.display = "none";
    drawOverlay();
  });
  canvas.addEventListener("wheel", (e) => {
    e.preventDefault();
    const rect = canvas.getBoundingClientRect();
    const x = e.clientX - rect.left, y = e.clientY - rect.top;
    const f = Math.exp(-e.deltaY * 0.0015);
    const ns = Math.min(200, Math.max(0.05, s * f));
    ox = x - ((x - ox) * ns) / s;
    oy = y - ((y - oy) * ns) / s;
    s = ns;
    draw();
    drawOverlay();
  }, { passive: false });

  new ResizeObserver(resize).observe(box);
  resize();
  return {
    map,
    fit: () => { fit(); draw(); drawOverlay(); },
    /// Screen position (CSS px, relative to the canvas) of the centre of cell (r, c).
    cellCentre: (r, c) => ({ x: ox + (c + 0.5) * s, y: oy + (map.rows - 1 - r + 0.5) * s }),
  };
}
