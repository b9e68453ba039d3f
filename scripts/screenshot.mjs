// Takes a picture of a report page (report.html) as a user first sees it:
// opened from file:// in headless Debian chromium, after the 3D view has
// drawn its first frame. scripts/docs uses it for the
// `<!-- generated screenshot: ... -->` markers of docs/*.md.
//
//   node scripts/screenshot.mjs REPORT.html OUT.png [WIDTHxHEIGHT]
//
// Needs web/node_modules (playwright-core; `make build` installs it) and
// /usr/bin/chromium (scripts/setup), or KNITFORGE_CHROMIUM.
import { createRequire } from "node:module";
import path from "node:path";
import { fileURLToPath, pathToFileURL } from "node:url";

const [html, png, size = "1400x1000"] = process.argv.slice(2);
if (!html || !png || !/^\d+x\d+$/.test(size)) {
  console.error("usage: node scripts/screenshot.mjs REPORT.html OUT.png [WIDTHxHEIGHT]");
  process.exit(2);
}
const [width, height] = size.split("x").map(Number);
const webDir = path.join(path.dirname(fileURLToPath(import.meta.url)), "..", "web");
const { chromium } = createRequire(path.join(webDir, "package.json"))("playwright-core");
const browser = await chromium.launch({
  executablePath: process.env.KNITFORGE_CHROMIUM || "/usr/bin/chromium",
  headless: true,
  args: ["--use-angle=swiftshader", "--enable-unsafe-swiftshader", "--ignore-gpu-blocklist"],
});
let status = 0;
try {
  const page = await browser.newPage({ viewport: { width, height } });
  const errors = [];
  page.on("pageerror", (e) => errors.push(e.message));
  await page.goto(pathToFileURL(path.resolve(html)).href, { timeout: 120000 });
  await page.waitForFunction(
    () => window.knitforgeReport && (window.knitforgeReport.ready || window.knitforgeReport.error), null,
    { timeout: 120000 });
  const error = await page.evaluate(() => window.knitforgeReport.error);
  if (error || errors.length) {
    console.error(`scripts/screenshot.mjs: ${html}: the page failed: ${error || errors.join(" | ")}`);
    status = 1;
  } else {
    await page.screenshot({ path: png });
  }
} finally {
  await browser.close();
}
process.exit(status);
