// Load-time check of report.html for a large design (docs/report.md; not a
// CTest test, it is a measurement):
//
//   node tests/web/load_time.mjs <knitforge CLI> <work dir> <web dir> [rows] [cols]
//
// Makes a random rows x cols map (default 300 x 340 = 102,000 stitches), its
// stitch mesh (relax) and yarn, writes report.html, opens it from file:// in
// headless chromium and prints the time from navigation start to the first
// drawn frame of the 3D view (performance.now() in the page), three runs.
import { createRequire } from "node:module";
import { execFileSync } from "node:child_process";
import { mkdirSync, statSync, writeFileSync } from "node:fs";
import path from "node:path";
import { pathToFileURL } from "node:url";

const [cli, work, webDir, rows = "300", cols = "340"] = process.argv.slice(2);
if (!cli || !work || !webDir) {
  console.error("usage: node load_time.mjs <knitforge CLI> <work dir> <web dir> [rows] [cols]");
  process.exit(2);
}
const { chromium } = createRequire(path.join(path.resolve(webDir), "package.json"))("playwright-core");
mkdirSync(work, { recursive: true });
const f = (n) => path.join(work, n);
const run = (...a) => execFileSync(cli, a, { encoding: "utf8", stdio: ["ignore", "pipe", "inherit"] });
const t0 = Date.now();
run("sample-map", "random", "--rows", rows, "--cols", cols, "--seed", "1", "-o", f("knitting_map.csv"));
run("relax", f("knitting_map.csv"), "-o", f("stitch_mesh.ply"));
run("yarn", f("stitch_mesh.ply"), "-o", f("yarn.obj"));
writeFileSync(f("report.json"), JSON.stringify({ route: "load-time check", rows: Number(rows), cols: Number(cols) }));
const t1 = Date.now();
run("report", work);
const t2 = Date.now();
const size = statSync(f("report.html")).size;
console.log(`design ${((t1 - t0) / 1000).toFixed(1)} s, knitforge report ${((t2 - t1) / 1000).toFixed(1)} s, report.html ${(size / 1e6).toFixed(1)} MB`);

const browser = await chromium.launch({
  executablePath: process.env.KNITFORGE_CHROMIUM || "/usr/bin/chromium",
  headless: true,
  args: ["--use-angle=swiftshader", "--enable-unsafe-swiftshader", "--ignore-gpu-blocklist"],
});
try {
  for (let i = 0; i < 3; ++i) {
    const page = await browser.newPage({ viewport: { width: 1400, height: 1000 } });
    const errors = [];
    page.on("pageerror", (e) => errors.push(e.message));
    await page.goto(pathToFileURL(f("report.html")).href, { timeout: 120000 });
    await page.waitForFunction(() => window.knitforgeReport && (window.knitforgeReport.ready || window.knitforgeReport.error), null, { timeout: 120000 });
    const r = await page.evaluate(() => ({
      ms: window.knitforgeReport.firstFrameMs, t: window.knitforgeReport.timings,
      error: window.knitforgeReport.error,
      stitches: document.querySelector("#knitforge-data") ? null : null,
      yarn: window.knitforgeReport.view3d && window.knitforgeReport.view3d.yarnInfo,
    }));
    if (r.error || errors.length) console.log("page error:", r.error, errors.join(" | "));
    console.log(`run ${i + 1}: first frame after ${r.ms.toFixed(0)} ms (script start ${r.t.start.toFixed(0)}, JSON parsed ${r.t.parsed.toFixed(0)}, scene built ${r.t.built.toFixed(0)}) (yarn ${r.yarn ? (r.yarn.tubes ? "tubes" : "lines") + ", " + r.yarn.points + " points" : "none"})`);
    if (i === 0) await page.screenshot({ path: f("load_time.png") });
    await page.close();
  }
} finally {
  await browser.close();
}
