// Builds dist/report.js: the whole report viewer (three.js, the page code and
// its CSS) as ONE self-contained, minified script that knitforge inlines into
// report.html (src/knitforge/report/report_html.cpp). Run with `npm run build`.
import { build } from "esbuild";
import { readFileSync } from "node:fs";

// Output: the path given as the first argument (CMake builds into the build
// tree), else dist/report.js.
const outfile = process.argv[2] || "dist/report.js";
await build({
  entryPoints: ["src/main.js"],
  bundle: true,
  minify: true,
  format: "iife",
  target: "es2020",
  loader: { ".css": "text" },
  legalComments: "none",
  outfile,
  logLevel: "warning",
});

// The script is inlined in a <script> element: it must not close or confuse it.
const text = readFileSync(outfile, "utf8");
if (!/^[\x09\x0a\x0d\x20-\x7e]*$/.test(text)) {
  console.error(`web/build.mjs: ${outfile} is not plain ASCII`);
  process.exit(1);
}
for (const bad of ["</script", "<!--", "<script"]) {
  if (text.toLowerCase().includes(bad)) {
    console.error(`web/build.mjs: ${outfile} contains '${bad}', which cannot be inlined in report.html`);
    process.exit(1);
  }
}
console.log(`web/build.mjs: wrote ${outfile} (${text.length} bytes)`);
