// The metrics of report.json as a readable tree of tables, and the knitout
// statistics.

export function formatValue(v) {
  if (v === null) return "null";
  if (typeof v === "number") {
    if (Number.isInteger(v)) return v.toLocaleString("en-US");
    const a = Math.abs(v);
    if (a !== 0 && (a < 1e-3 || a >= 1e7)) return v.toExponential(4);
    return Number(v.toPrecision(6)).toString();
  }
  if (typeof v === "boolean") return v ? "yes" : "no";
  return String(v);
}

function isScalar(v) {
  return v === null || typeof v !== "object";
}

function summariseNumbers(a) {
  let lo = Infinity, hi = -Infinity, sum = 0;
  for (const x of a) { lo = Math.min(lo, x); hi = Math.max(hi, x); sum += x; }
  return `${a.length} values: min ${formatValue(lo)}, mean ${formatValue(sum / a.length)}, max ${formatValue(hi)}`;
}

function label(key) {
  return String(key).replace(/_/g, " ");
}

/// A DOM node showing any JSON value: scalars as text, short scalar arrays
/// inline, long numeric arrays summarised, objects and arrays of objects as
/// nested tables inside <details> (open up to depth 2).
export function jsonNode(value, depth = 0) {
  if (isScalar(value)) {
    const span = document.createElement("span");
    span.textContent = formatValue(value);
    return span;
  }
  if (Array.isArray(value)) {
    if (value.length === 0) {
      const span = document.createElement("span");
      span.className = "empty";
      span.textContent = "(empty list)";
      return span;
    }
    if (value.every((x) => typeof x === "number") && value.length > 12) {
      const span = document.createElement("span");
      span.textContent = summariseNumbers(value);
      return span;
    }
    if (value.every(isScalar) && value.length <= 12) {
      const span = document.createElement("span");
      span.textContent = value.map(formatValue).join(", ");
      return span;
    }
  }
  const entries = Array.isArray(value) ? value.map((v, i) => [String(i), v]) : Object.entries(value);
  const table = document.createElement("table");
  table.className = "kv";
  for (const [k, v] of entries) {
    const tr = document.createElement("tr");
    const tk = document.createElement("td");
    tk.className = "key";
    const tv = document.createElement("td");
    if (isScalar(v)) {
      tk.textContent = label(k);
      if (typeof v === "number") tv.className = "num";
      tv.append(jsonNode(v, depth + 1));
      tr.append(tk, tv);
    } else if (Array.isArray(v) && v.every(isScalar) && (v.length <= 12 || v.every((x) => typeof x === "number"))) {
      tk.textContent = label(k);
      tv.append(jsonNode(v, depth + 1));
      tr.append(tk, tv);
    } else {
      const td = document.createElement("td");
      td.colSpan = 2;
      const det = document.createElement("details");
      det.open = depth < 2;
      const sum = document.createElement("summary");
      sum.textContent = label(k);
      det.append(sum, jsonNode(v, depth + 1));
      td.append(det);
      tr.append(td);
    }
    table.append(tr);
  }
  if (entries.length === 0) {
    const span = document.createElement("span");
    span.className = "empty";
    span.textContent = "(empty)";
    return span;
  }
  return table;
}
