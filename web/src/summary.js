// "For the knitter": the first panel of the page, from the machine section
// of report.json (report/machine_report.h) and the files of the run.
import { formatValue } from "./tables.js";

function row(table, key, value, id) {
  const tr = document.createElement("tr");
  if (id) tr.id = id;
  const k = document.createElement("td");
  k.className = "key";
  k.textContent = key;
  const v = document.createElement("td");
  if (value instanceof Node) v.append(value);
  else v.textContent = value;
  tr.append(k, v);
  table.append(tr);
  return v;
}

function minutes(s) {
  if (s < 90) return `${s.toFixed(0)} s`;
  const m = s / 60;
  return m < 90 ? `${m.toFixed(1)} min` : `${(m / 60).toFixed(1)} h`;
}

function mm(v) {
  return `${(v / 10).toFixed(1)} cm`;
}

/// The summary table for `machine` (report.json "machine"), or null when
/// the run has none. `files` are the files of the run, for download links.
export function knitterSummary(machine, metrics, files) {
  if (!machine || typeof machine !== "object") return null;
  const table = document.createElement("table");
  table.className = "kv summary";
  table.id = "knitter-summary";
  row(table, "machine", `${machine.machine ?? machine.profile}${machine.gauge ? `, gauge ${formatValue(machine.gauge)}` : ""}`);
  const verdict = document.createElement("span");
  verdict.id = "machine-verdict";
  const good = machine.verdict === "VALID" && machine.matches_map !== false;
  verdict.className = good ? "verdict good" : "verdict bad";
  verdict.textContent = machine.verdict === "VALID"
    ? `VALID on the virtual machine${machine.matches_map ? ", knits exactly the designed map" : ", but DIFFERS from the map"}` +
      (machine.warnings ? ` (${machine.warnings} warning${machine.warnings === 1 ? "" : "s"})` : "")
    : `${machine.verdict}${machine.reason ? ": " + machine.reason : ""}`;
  row(table, "machine verdict", verdict);
  if (machine.finished_size_mm) {
    const [x, y, z] = machine.finished_size_mm;
    row(table, "finished size", `${mm(x)} \u00d7 ${mm(y)} \u00d7 ${mm(z)} (designed shape)`);
  }
  const params = metrics && metrics.parameters;
  if (params && params.stitch_width_mm) {
    row(table, "stitch size", `${formatValue(params.stitch_width_mm)} \u00d7 ${formatValue(params.stitch_height_mm)} mm`);
  }
  if (machine.stitches !== undefined) row(table, "stitches", formatValue(machine.stitches), "summary-stitches");
  if (machine.courses !== undefined) row(table, "courses \u00d7 wales", `${machine.courses} \u00d7 ${machine.wales}`);
  if (machine.knit_time_s !== undefined) row(table, "knitting time", `${minutes(machine.knit_time_s)} (estimate)`);
  if (Array.isArray(machine.yarn_m)) {
    const list = machine.yarn_m.map((y) => `carrier ${y.carrier} (${y.role}): ${y.metres.toFixed(1)} m`).join(" \u00b7 ");
    row(table, "yarn", `${list} (estimate)`, "summary-yarn");
  }
  if (machine.shaping) {
    const s = machine.shaping;
    row(table, "shaping transfers",
      `${s.transfer_stitches} transfer stitches (short columns: ${s.short_column_increases} increases, ` +
      `${s.short_column_decreases} decreases); ${s.transfers} transfers in the fabric ` +
      `(${s.wales_started} wales started, ${s.wales_ended} ended` +
      (s.edge_bound_off ? `, ${s.edge_bound_off} of them bound off at the edge` : "") +
      `), ${s.other_transfers} for cast-on and bind-off`, "summary-transfers");
  }
  if (machine.short_row_turns) {
    const t = machine.short_row_turns;
    row(table, "short-row turns", `${t.inside} (${t.closed} closed by a tuck, ${t.open} open)`);
  }
  if (machine.waste_courses !== undefined) {
    row(table, "waste section", machine.waste_courses ? `${machine.waste_courses} courses + draw thread` : "none");
  }
  if (machine.needles) row(table, "needles", `${machine.needles[0]} \u2013 ${machine.needles[1]}`);
  const links = document.createElement("span");
  links.id = "downloads";
  for (const f of files || []) {
    const a = document.createElement("a");
    a.href = encodeURI(f.name);
    a.setAttribute("download", f.name);
    a.textContent = f.name;
    if (links.childNodes.length) links.append(" \u00b7 ");
    links.append(a);
  }
  if (links.childNodes.length) row(table, "download", links);
  if (Array.isArray(machine.notes) && machine.notes.length) row(table, "notes", machine.notes.join("; "));
  return table;
}
