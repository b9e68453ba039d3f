// Colour tables of the report viewer. The stitch-type and map colours are
// those of knitforge's own files (src/knitforge/io/colours.h,
// docs/formats.md) so the page matches stitch_mesh.ply and knitting_map.png.

export const STITCH_TYPE_NAMES = ["knit", "short-row-left", "short-row-right", "increase", "decrease"];
export const STITCH_TYPE_COLOURS = [
  [166, 206, 227],
  [255, 127, 0],
  [227, 26, 28],
  [51, 160, 44],
  [106, 61, 154],
];

// Map cells: rows knitted left to right / right to left, collapsed, empty.
export const MAP_LTR = [166, 206, 227];
export const MAP_RTL = [31, 120, 180];
export const MAP_COLLAPSED = [170, 170, 170];
export const MAP_EMPTY = [255, 255, 255];
export const MAP_GRID = [150, 150, 150];

// Map cell codes (knitting_map.csv) -> cell type index (core/stitch.h CellType).
export const CELL_CODES = "KLRIDC.";
export const CELL_NAMES = [...STITCH_TYPE_NAMES, "collapsed", "empty"];

// Categorical palette for yarns (yarn 0 first) and other small integer sets.
export const CATEGORICAL = [
  [214, 96, 77], [67, 147, 195], [90, 174, 97], [153, 112, 171], [224, 180, 60],
  [53, 151, 143], [191, 129, 45], [140, 81, 10], [197, 27, 125], [102, 102, 102],
];

// Viridis, sampled at 9 stops (linear interpolation in between).
const VIRIDIS = [
  [68, 1, 84], [71, 45, 123], [59, 82, 139], [44, 114, 142], [33, 145, 140],
  [40, 174, 128], [94, 201, 98], [173, 220, 48], [253, 231, 37],
];

/// t in [0, 1] -> [r, g, b] in 0..255.
export function viridis(t) {
  if (!(t >= 0)) t = 0;
  if (t > 1) t = 1;
  const x = t * (VIRIDIS.length - 1);
  const i = Math.min(Math.floor(x), VIRIDIS.length - 2);
  const f = x - i;
  const a = VIRIDIS[i], b = VIRIDIS[i + 1];
  return [a[0] + (b[0] - a[0]) * f, a[1] + (b[1] - a[1]) * f, a[2] + (b[2] - a[2]) * f];
}

export function viridisCss() {
  return `linear-gradient(to right, ${VIRIDIS.map((c) => `rgb(${c[0]},${c[1]},${c[2]})`).join(", ")})`;
}

export function categorical(i) {
  const n = CATEGORICAL.length;
  return CATEGORICAL[((i % n) + n) % n];
}

export function css(rgb) {
  return `rgb(${Math.round(rgb[0])},${Math.round(rgb[1])},${Math.round(rgb[2])})`;
}

/// Mixes a towards b by f.
export function mix(a, b, f) {
  return [a[0] + (b[0] - a[0]) * f, a[1] + (b[1] - a[1]) * f, a[2] + (b[2] - a[2]) * f];
}
