// Browser test of report.html (CTest `web_report`; docs/report.md).
//
//   node tests/web/report_test.mjs <knitforge CLI> <artifacts dir> <web dir>
//
// Makes a small design with the CLI (cup map -> relaxed stitch mesh -> yarn,
// knitout, a report.json), writes report.html with `knitforge report`, opens
// it from file:// in headless Debian chromium through playwright-core
// (web/node_modules) and checks what a person would see: the 3D view draws,
// the colour buttons and layer toggles change its pixels, the map canvas
// shows and hovering a cell gives its course / wale / type, the metrics and
// knitout panels are filled, and the page logs no error. Screenshots go to
// <artifacts dir>/web_report/. Then a design with predicted.ply: its layer.
// Then a small `cloth` run: the frame slider and
// the play button move the sleeve and the arm (animation.glb); the sleeve is
// coloured by the stress of the frame shown (cloth.json), or by sliding.
import { createRequire } from "node:module";
import { execFileSync } from "node:child_process";
import { existsSync, mkdirSync, readFileSync, rmSync, writeFileSync } from "node:fs";
import path from "node:path";
import { pathToFileURL } from "node:url";

const [cli, artifactsRoot, webDir] = process.argv.slice(2);
if (!cli || !artifactsRoot || !webDir) {
  console.error("usage: node report_test.mjs <knitforge CLI> <artifacts dir> <web dir>");
  process.exit(2);
}
const CHROMIUM = process.env.KNITFORGE_CHROMIUM || "/usr/bin/chromium";
if (!existsSync(CHROMIUM)) {
  console.error(`web_report: FAILED: ${CHROMIUM} is not installed; run scripts/setup (it installs Debian's chromium)`);
  process.exit(1);
}
let chromium;
try {
  chromium = createRequire(path.join(path.resolve(webDir), "package.json"))("playwright-core").chromium;
} catch (e) {
  console.error(`web_report: FAILED: playwright-core is not installed in ${webDir}/node_modules; run 'npm ci' in web/ (the build does): ${e.message}`);
  process.exit(1);
}

const art = path.join(path.resolve(artifactsRoot), "web_report");
const design = path.join(art, "design");
rmSync(art, { recursive: true, force: true });
mkdirSync(design, { recursive: true });

let passed = 0, failed = 0;
function check(ok, what, detail = "") {
  if (ok) {
    ++passed;
    console.log(`ok   ${what}`);
  } else {
    ++failed;
    console.log(`FAIL ${what}${detail ? ": " + detail : ""}`);
  }
}

function run(...args) {
  try {
    return execFileSync(cli, args, { encoding: "utf8", stdio: ["ignore", "pipe", "pipe"] });
  } catch (e) {
    console.error(`web_report: FAILED: knitforge ${args.join(" ")} exited with ${e.status}:\n${e.stderr}`);
    process.exit(1);
  }
}

// --- a small design -----------------------------------------------------------
const f = (n) => path.join(design, n);
run("sample-map", "cup", "-o", f("knitting_map.csv"));
run("relax", f("knitting_map.csv"), "-o", f("stitch_mesh.ply"));
run("yarn", f("stitch_mesh.ply"), "-o", f("yarn.obj"));
run("knitout", f("knitting_map.csv"), "-o", f("knitout.k"));
writeFileSync(f("report.json"), JSON.stringify({
  route: "sample cup (web test)",
  counts: { stitches: 0, short_row_pairs: 3 },
  knittability: { knittable: true, errors: 0, warnings: 0 },
  shape_error: { rms_mm: 0.42, max_mm: 1.3 },
  stage_times_s: { map: 0.001, relax: 0.2, yarn: 0.05 },
}, null, 2));
run("report", design);
const reportPath = path.join(design, "report.html");
check(existsSync(reportPath), "knitforge report wrote report.html");

// --- the page -----------------------------------------------------------------
const browser = await chromium.launch({
  executablePath: CHROMIUM,
  headless: true,
  args: ["--use-angle=swiftshader", "--enable-unsafe-swiftshader", "--ignore-gpu-blocklist"],
});
const errors = [];
try {
  const page = await browser.newPage({ viewport: { width: 1400, height: 1000 }, deviceScaleFactor: 1 });
  page.on("console", (m) => { if (m.type() === "error") errors.push("console: " + m.text()); });
  page.on("pageerror", (e) => errors.push("page error: " + e.message));
  page.on("request", (r) => { if (!r.url().startsWith("file:") && !r.url().startsWith("data:")) errors.push("network request: " + r.url()); });

  await page.goto(pathToFileURL(reportPath).href);
  await page.waitForFunction(() => window.knitforgeReport && (window.knitforgeReport.ready || window.knitforgeReport.error), null, { timeout: 60000 });
  const state = await page.evaluate(() => ({ error: window.knitforgeReport.error, firstFrameMs: window.knitforgeReport.firstFrameMs }));
  check(!state.error, "the page loaded its data", state.error);
  console.log(`     first frame after ${state.firstFrameMs.toFixed(0)} ms`);
  await page.screenshot({ path: path.join(art, "page.png"), fullPage: true });

  // Waits until the page has drawn its pending changes (rendering is on demand).
  const settle = () => page.evaluate(() => new Promise((r) => requestAnimationFrame(() => requestAnimationFrame(r))));

  // Pixels of a screenshot, counted in the page (decoding the PNG there).
  const analyse = (a, b) => page.evaluate(async ([a64, b64]) => {
    const load = async (s) => {
      const img = new Image();
      img.src = "data:image/png;base64," + s;
      await img.decode();
      const c = document.createElement("canvas");
      c.width = img.width; c.height = img.height;
      const ctx = c.getContext("2d");
      ctx.drawImage(img, 0, 0);
      return ctx.getImageData(0, 0, c.width, c.height).data;
    };
    const pa = await load(a64);
    let nonWhite = 0, differ = 0;
    const pb = b64 ? await load(b64) : null;
    for (let i = 0; i < pa.length; i += 4) {
      if (pa[i] < 245 || pa[i + 1] < 245 || pa[i + 2] < 245) ++nonWhite;
      if (pb && (Math.abs(pa[i] - pb[i]) + Math.abs(pa[i + 1] - pb[i + 1]) + Math.abs(pa[i + 2] - pb[i + 2]) > 24)) ++differ;
    }
    return { pixels: pa.length / 4, nonWhite, differ };
  }, [a.toString("base64"), b ? b.toString("base64") : null]);

  // 3D view draws something.
  const view = page.locator("#view3d-box");
  const shotType = await view.screenshot({ path: path.join(art, "view3d-type.png") });
  const a1 = await analyse(shotType);
  check(a1.nonWhite > 0.03 * a1.pixels, "the 3D view shows the design", `${a1.nonWhite} of ${a1.pixels} pixels not background`);

  // Colour buttons change the stitch colours.
  const modes = await page.$$eval("#colour-modes button", (bs) => bs.map((b) => b.dataset.colour));
  check(["type", "course", "wale", "direction"].every((m) => modes.includes(m)), "colour modes offered", modes.join(", "));
  await page.click('#colour-modes button[data-colour="course"]');
  await settle();
  const shotCourse = await view.screenshot({ path: path.join(art, "view3d-course.png") });
  const d1 = await analyse(shotType, shotCourse);
  check(d1.differ > 0.005 * d1.pixels, "colouring by course changes the picture", `${d1.differ} pixels differ`);
  check(await page.$eval('#colour-modes button[data-colour="course"]', (b) => b.classList.contains("active")), "the course button is marked active");
  const legend = await page.textContent("#legend-3d");
  check(/course/.test(legend), "the legend names the course ramp", legend);
  await page.click('#colour-modes button[data-colour="wale"]');
  await settle();
  const shotWale = await view.screenshot({ path: path.join(art, "view3d-wale.png") });
  const d2 = await analyse(shotCourse, shotWale);
  check(d2.differ > 0.005 * d2.pixels, "colouring by wale changes the picture", `${d2.differ} pixels differ`);

  // Layer toggles: hiding the yarn and the stitch mesh changes the picture.
  await page.click('#colour-modes button[data-colour="type"]');
  await page.uncheck('input[data-layer="yarn"]');
  await page.uncheck('input[data-layer="stitch_mesh"]');
  await settle();
  const shotHidden = await view.screenshot({ path: path.join(art, "view3d-hidden.png") });
  const d3 = await analyse(shotType, shotHidden);
  check(d3.differ > 0.01 * d3.pixels, "hiding yarn and stitch mesh changes the picture", `${d3.differ} pixels differ`);
  await page.check('input[data-layer="yarn"]');
  await page.check('input[data-layer="stitch_mesh"]');

  // The map canvas.
  const mapBox = page.locator("#map-box");
  check(await mapBox.isVisible(), "the knitting map is shown");
  const shotMap = await mapBox.screenshot({ path: path.join(art, "map.png") });
  const a2 = await analyse(shotMap);
  check(a2.nonWhite > 0.05 * a2.pixels, "the map canvas is drawn", `${a2.nonWhite} of ${a2.pixels}`);

  // Hover: a short-row cell (the cup has them) and a knit cell.
  const targets = await page.evaluate(() => {
    const m = window.knitforgeReport.mapView;
    const find = (want) => {
      for (let r = 0; r < m.map.rows; ++r) for (let c = 0; c < m.map.cols; ++c) if (m.map.cells[r * m.map.cols + c] === want) return { r, c, ...m.cellCentre(r, c) };
      return null;
    };
    return { knit: find(0), shortRow: find(1) || find(2) };
  });
  const canvasBox = await page.locator("#mapview").boundingBox();
  for (const [kind, t, re] of [["knit", targets.knit, /knit/], ["short-row", targets.shortRow, /short-row-(left|right)/]]) {
    if (!t) { check(false, `the map has a ${kind} cell`); continue; }
    await page.mouse.move(canvasBox.x + t.x, canvasBox.y + t.y);
    const tip = page.locator("#map-tooltip");
    const visible = await tip.isVisible();
    const text = visible ? await tip.textContent() : "";
    check(visible && text.startsWith(`course ${t.r}, wale ${t.c}: `) && re.test(text),
      `hovering a ${kind} cell shows its course, wale and type`, JSON.stringify(text));
    if (kind === "short-row") await mapBox.screenshot({ path: path.join(art, "map-hover.png") });
  }
  // Zoom changes the map.
  await page.mouse.wheel(0, -600);
  await settle();
  const shotZoom = await mapBox.screenshot({ path: path.join(art, "map-zoom.png") });
  const d4 = await analyse(shotMap, shotZoom);
  check(d4.differ > 0.05 * d4.pixels, "the wheel zooms the map", `${d4.differ} pixels differ`);

  // Metrics and knitout panels.
  const metrics = await page.textContent("#panel-metrics");
  check(metrics.includes("short row pairs") && metrics.includes("rms mm") && metrics.includes("0.42"), "the metrics of report.json are listed");
  const knitout = await page.textContent("#panel-knitout");
  check(/operations/.test(knitout) && /knit/.test(knitout), "the knitout statistics are listed");

  // The knitter's summary of a real design run (shortrow writes knitout.k and
  // the machine section of report.json).
  const design2 = path.join(art, "design-shortrow");
  run("shortrow", "disk", "--stitch", "5x4", "--no-evaluate", "-o", design2);
  const metrics2 = JSON.parse(readFileSync(path.join(design2, "report.json"), "utf8"));
  await page.goto(pathToFileURL(path.join(design2, "report.html")).href);
  await page.waitForFunction(() => window.knitforgeReport && (window.knitforgeReport.ready || window.knitforgeReport.error), null, { timeout: 60000 });
  check(await page.locator("#panel-summary").isVisible(), "the knitter's summary is shown");
  const firstPanel = await page.evaluate(() => document.querySelector("main section.panel").id);
  check(firstPanel === "panel-summary", "the knitter's summary comes first", firstPanel);
  const verdict = await page.textContent("#machine-verdict");
  check(/^VALID/.test(verdict) && /knits exactly the designed map/.test(verdict), "the machine verdict is VALID and matches the map", verdict);
  const stitches = await page.textContent("#summary-stitches td:last-child");
  check(stitches.replace(/,/g, "") === String(metrics2.machine.stitches) && metrics2.machine.stitches === metrics2.counts.stitches,
    "the summary's stitch count is the design's", `${stitches} vs ${metrics2.counts.stitches}`);
  const summaryText = await page.textContent("#knitter-summary");
  for (const want of ["finished size", "courses \u00d7 wales", "knitting time", "yarn", "shaping transfers", "gauge 15"]) {
    check(summaryText.includes(JSON.parse(`"${want}"`)), `the summary lists ${JSON.parse(`"${want}"`)}`);
  }
  const yarn = await page.textContent("#summary-yarn td:last-child");
  check(/carrier 1 \(main\): [0-9.]+ m/.test(yarn) && /waste/.test(yarn), "yarn per carrier with its role", yarn);
  const hrefs = await page.$$eval("#downloads a", (as) => as.map((a) => a.getAttribute("href")));
  check(hrefs.includes("knitout.k") && hrefs.includes("knitting_map.csv"), "download links for the program and the map", hrefs.join(", "));
  check(hrefs.every((h) => existsSync(path.join(design2, decodeURI(h)))), "every download link points at a file of the run");
  await page.screenshot({ path: path.join(art, "summary.png") });
  check(!(await page.$('input[data-layer="predicted"]')), "no predicted layer without predicted.ply");

  // A design with its converged predicted shape (predicted.ply): a layer of
  // its own, hidden at start; shown alone, the legend is its shape error.
  const design3 = path.join(art, "design-predicted");
  run("shortrow", "disk", "--stitch", "5x4", "--no-knitout", "-o", design3);
  check(existsSync(path.join(design3, "predicted.ply")), "the design wrote predicted.ply");
  await page.goto(pathToFileURL(path.join(design3, "report.html")).href);
  await page.waitForFunction(() => window.knitforgeReport && (window.knitforgeReport.ready || window.knitforgeReport.error), null, { timeout: 60000 });
  const pred = page.locator('input[data-layer="predicted"]');
  check((await pred.count()) === 1 && !(await pred.isChecked()), "a predicted layer, hidden at start beside the stitch mesh");
  await page.click('[data-colour="scalar:shape_error"]');
  await page.uncheck('input[data-layer="stitch_mesh"]');
  await page.uncheck('input[data-layer="relaxed"]');
  await settle();
  const shotNone = await view.screenshot();
  await pred.check();
  await settle();
  const shotPred = await view.screenshot({ path: path.join(art, "predicted.png") });
  const d7 = await analyse(shotNone, shotPred);
  check(d7.differ > 0.01 * d7.pixels, "ticking it draws the predicted shape", `${d7.differ} pixels differ`);
  const predLegend = await page.textContent("#legend-3d");
  check(/shape error \(predicted\)/.test(predLegend), "the legend gives the predicted shape's own shape error", predLegend);

  // A cloth run (a small built-in sleeve): the page plays animation.glb; the
  // frame slider moves the garment and the arm. The page is tested, not the
  // solver: a few iterations a step (--quasi-newton 10, 2 Newton) make it
  // 5.5 s instead of 36 s under ASan.
  const cloth = path.join(art, "cloth");
  writeFileSync(path.join(art, "sleeve.json"), JSON.stringify({
    builtin: "sleeve", frames: 3, frame_rate_hz: 20, substeps: 1, newton: { max_iterations: 2 },
    arm: { upper_length_mm: 110, forearm_length_mm: 100, upper_radius_mm: 30, forearm_radius_mm: 26,
           body_edge_mm: 10, sleeve_edge_mm: 9, transition_mm: 40, max_angle_deg: 60 },
  }));
  run("cloth", path.join(art, "sleeve.json"), "--quasi-newton", "10", "-o", cloth);
  await page.goto(pathToFileURL(path.join(cloth, "report.html")).href);
  await page.waitForFunction(() => window.knitforgeReport && (window.knitforgeReport.ready || window.knitforgeReport.error), null, { timeout: 60000 });
  const anim = await page.evaluate(() => window.knitforgeReport.view3d && window.knitforgeReport.view3d.animation &&
    { frame: window.knitforgeReport.view3d.animation.frame, frames: window.knitforgeReport.view3d.animation.frames });
  check(anim && anim.frames === 4 && anim.frame === 3, "the cloth page has the 4 frames, at the last", JSON.stringify(anim));
  check(await page.locator('[data-animation="play"]').isVisible(), "a play button is shown");
  const layerText = await page.textContent("#layers");
  check(/body/.test(layerText) && /garment/.test(layerText), "the layers are named body and garment", layerText);
  await settle();
  const shotLast = await view.screenshot({ path: path.join(art, "cloth-last.png") });
  await page.$eval('[data-animation="frame"]', (s) => { s.value = "0"; s.dispatchEvent(new Event("input")); });
  await settle();
  const shotFirst = await view.screenshot({ path: path.join(art, "cloth-first.png") });
  const d5 = await analyse(shotLast, shotFirst);
  check(d5.differ > 0.005 * d5.pixels, "the frame slider moves the arm and the sleeve", `${d5.differ} pixels differ`);
  check(/frame 0 \/ 3/.test(await page.textContent('[data-animation="time"]')), "the frame and time are shown");
  await page.click('[data-animation="play"]');
  await page.waitForFunction(() => window.knitforgeReport.view3d.animation.frame === 3, null, { timeout: 10000 });
  check(true, "play runs to the last frame");

  // The garment is coloured by the stress of the frame shown (cloth.json's
  // fields), with a legend; a button switches to sliding.
  const clothJson = JSON.parse(readFileSync(path.join(cloth, "cloth.json"), "utf8"));
  const shown = () => page.evaluate(() => {
    const v = window.knitforgeReport.view3d;
    const data = JSON.parse(document.getElementById("knitforge-data").textContent);
    const tri = data.relaxed.triangles;
    const out = { field: v.fields.current(), frame: v.animation.frame, values: [], colours: [], triangles: tri };
    for (let c = 0; c < tri.length; ++c) { out.values.push(v.fields.value(c)); out.colours.push(v.fields.colour(c)); }
    const f = out.field && data.animation.layers.relaxed.fields[out.field];
    out.step = f ? f.step : null;
    return out;
  });
  // Page values against the run's, and the colours: viridis over [0, largest of all frames].
  const agrees = (s, key) => {
    const ref = clothJson.fields[s.frame][key];
    let worst = 0, hi = 0;
    for (const fr of clothJson.fields) for (const x of fr[key]) hi = Math.max(hi, x);
    let top = -1, low = -1;
    for (let c = 0; c < s.values.length; ++c) {
      const want = key === "stress_kpa" ? ref[Math.floor(c / 3)] : ref[s.triangles[c]];
      worst = Math.max(worst, Math.abs(s.values[c] - want));
      if (top < 0 || s.values[c] > s.values[top]) top = c;
      if (low < 0 || s.values[c] < s.values[low]) low = c;
    }
    // viridis(t) at the two ends: t = value / hi (0: dark purple, 1: yellow).
    const frac = (c) => (hi > 0 ? s.values[c] / hi : 0);
    const yellowish = (rgb) => rgb[0] > 0.5 && rgb[1] > 0.5 && rgb[2] < 0.5;
    const purplish = (rgb) => rgb[0] < 0.35 && rgb[1] < 0.2 && rgb[2] > 0.25;
    return { worst, ok: worst <= 0.5 * s.step + 1e-9,
      ends: (frac(top) < 0.9 || yellowish(s.colours[top])) && (frac(low) > 0.05 || purplish(s.colours[low])),
      detail: `worst ${worst} (step ${s.step}); top ${s.values[top]} of ${hi} -> ${s.colours[top]}; low ${s.values[low]} -> ${s.colours[low]}` };
  };
  let st = await shown();
  check(st.field === "stress_kpa" && st.frame === 3, "the garment opens coloured by the stress of the last frame", `${st.field} at ${st.frame}`);
  let a = agrees(st, "stress_kpa");
  check(a.ok && a.ends, "its colours are cloth.json's stress of that frame on viridis over all frames", a.detail);
  const stressLegend = await page.textContent("#legend-3d");
  check(/stress \(kPa\)/.test(stressLegend) && /Cauchy/.test(stressLegend), "the legend names the stress, its unit and its measure", stressLegend);
  await page.$eval('[data-animation="frame"]', (s) => { s.value = "1"; s.dispatchEvent(new Event("input")); });
  st = await shown();
  a = agrees(st, "stress_kpa");
  check(st.frame === 1 && a.ok && a.ends, "moving the slider shows the stress of the new frame", a.detail);
  await settle();
  const shotStress = await view.screenshot({ path: path.join(art, "cloth-stress.png") });
  await page.click('[data-field="sliding_mm"]');
  st = await shown();
  a = agrees(st, "sliding_mm");
  check(st.field === "sliding_mm" && a.ok && a.ends, "the sliding button colours by cloth.json's sliding per vertex", a.detail);
  check(/sliding \(mm\)/.test(await page.textContent("#legend-3d")), "the legend says sliding (mm)");
  await settle();
  const shotSliding = await view.screenshot({ path: path.join(art, "cloth-sliding.png") });
  const d6 = await analyse(shotStress, shotSliding);
  check(d6.differ > 0.002 * d6.pixels, "stress and sliding colour the garment differently", `${d6.differ} pixels differ`);
  await page.click('[data-field=""]');
  check((await shown()).field === null && (await page.textContent("#legend-3d")) === "", "plain: no field, no legend");

  check(errors.length === 0, "no console errors, page errors or network requests", errors.join(" | "));
} finally {
  await browser.close();
}

console.log(`web_report: ${passed} passed, ${failed} failed`);
process.exit(failed === 0 ? 0 : 1);
