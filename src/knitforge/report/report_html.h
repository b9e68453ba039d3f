#pragma once
/// \file report_html.h
/// The report page of a design run (`report.html`, issue 6 items 4-5): one
/// self-contained HTML file that shows what a design command left in its
/// output directory — an interactive 3D view (target surface, stitch mesh
/// coloured by stitch type / course / wale / direction / yarn / any
/// per-stitch scalar, relaxed shape, yarn tubes, wale curves), the knitting
/// map on a zoomable canvas, the metrics of report.json and the statistics
/// of the knitting program. docs/report.md describes the page.
///
/// The page needs no network and no other file: the design data is embedded
/// as JSON (`<script type="application/json" id="knitforge-data">`) and the
/// viewer (web/, three.js) is inlined; the viewer is compiled into the
/// library at build time, so the source tree is not needed at run time.
///
/// Files read from the output directory (each optional; docs/formats.md):
///
///  - report.json (nlohmann::json): the metrics tree;
///  - target.ply (read_mesh()): a translucent surface;
///  - stitch_mesh.ply (read_stitch_mesh_ply()): the coloured stitches; extra
///    scalar face properties (e.g. `shape_error`, `distortion`) become
///    colour modes;
///  - relaxed.ply (a stitch mesh or a triangle mesh): the second layer;
///  - predicted.ply (a stitch mesh or a triangle mesh): the third layer, the
///    converged predicted shape;
///  - knitting_map.csv (read_knitting_map_csv()): the 2D map;
///  - wales.obj (read_polylines_obj()): curves;
///  - yarn.obj (read_polylines_obj()): tubes (lines above 40,000 points);
///  - knitout.k (read_knitout() + simulate_knitout()): statistics;
///  - animation.glb + cloth.json (read_gltf_animation(), nlohmann::json):
///    frames of the garment and the body, the garment's stress / sliding per
///    frame.
///
/// The data (`report_data()`) is compact: coordinates are integers in units
/// of `quantum_mm` (key `scale`), meshes and polylines are flat arrays,
/// the map is one string of cell codes (K L R I D C .) row-major from row 0.

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

namespace knitforge {

struct ReportHtmlOptions {
  /// Page title; "" = the name of the output directory.
  std::string title;
  /// Where to write the page; "" = <outdir>/report.html.
  std::string output;
  /// Coordinates are rounded to multiples of this length (mm), > 0.
  double quantum_mm = 0.01;
  /// Run the knitout simulator (machine profile from the `;;Machine:`
  /// header) for pass counts, knitting time and yarn length; false gives only
  /// the parse statistics (line and operation counts).
  bool simulate_knitout = true;
  /// Yarn and wale curves with more points than this in total are thinned
  /// for the page (every k-th point of each polyline, plus its last point;
  /// a note says so): a 100k-stitch design has over a million yarn points,
  /// which would make the page slow to open. <= 0 keeps every point.
  int64_t max_polyline_points = 250000;
  /// The frames of animation.glb and the per-frame fields of cloth.json
  /// (see report_data()) hold at most this many coordinates and field values
  /// in all (per frame: 3 x the vertices of every moving layer + the
  /// garment's triangles (stress) + its vertices (sliding)); more frames are
  /// thinned, the same frames for every layer and field (every k-th and the
  /// last, a note says so). <= 0 keeps every frame.
  int64_t max_animation_values = 3000000;
};

/// The file names report_data() looks for, in the order listed above.
const std::vector<std::string>& report_input_files();

/// Reads every file of report_input_files() that exists in `outdir` and
/// returns the page's data object:
///   {"format": "knitforge-report", "version": 1, "title", "scale",
///    "files": [{"name", "bytes"}], "notes": [...],
///    "metrics": <report.json>,
///    "target":  {"positions": [int x3], "triangles": [int x3]},
///    "stitch_mesh": {"positions", "corners": [4 per stitch, -1 pads triangles],
///                    "type", "direction", "course", "wale", "yarn" (only when
///                    a stitch has yarn != 0), "scalars": {name: [per stitch]}},
///    "relaxed": {"kind": "stitch_mesh", ...} or {"kind": "mesh", ...},
///    "predicted": as "relaxed" (predicted.ply: a design's converged predicted shape),
///    "map": {"rows", "cols", "cells": "KK.L...", "direction": [...], "yarn"},
///    "wales" / "yarn": {"names": [...], "polylines": [[int x3], ...]},
///    "knitout": {"lines", "operations", ..., "simulation": {...}},
///    "animation": {"layers": {"relaxed" | "target":
///                  {"times": [s], "frames": [[int x3], ...],
///                   "fields" (relaxed only): {"stress_kpa" | "sliding_mm":
///                     {"label", "unit", "per": "triangle" | "vertex",
///                      "measure", "step", "range": [lo, hi],
///                      "frames": [[int, one per element], ...]}}}}}}
/// "animation" comes from animation.glb (what `cloth` writes: its mesh
/// "garment" moves the relaxed layer, "body" the target layer, each when
/// the vertex counts agree; read by io/read_gltf_animation.h), sampled at
/// its key times; absent without the file, and not listed as missing.
/// "fields" come from cloth.json beside it (`fields[f].stress_kpa` per
/// triangle, `fields[f].sliding_mm` per vertex, one entry per frame of the
/// animation; "measure" from its "result"), when the relaxed layer is a
/// plain mesh of those sizes: each value is an integer in units of "step"
/// (a power of ten: at most 1,000 levels below the largest value of all
/// frames), null where cloth.json has none; "range" holds min(0, smallest)
/// and the largest value over all frames, to 5 significant digits (the
/// colour scale of every frame).
/// The frames of every layer and field are the same ones (thinned together,
/// see ReportHtmlOptions::max_animation_values).
/// A key is absent when its file is. Scalars are rounded to 5 significant
/// digits of the field's largest magnitude; NaN becomes null.
/// \throw IOError when `outdir` is not a directory, holds none of the files
///        ("nothing to report"), or a file present cannot be read (the
///        reader's message, naming the file and line).
/// \throw InvalidInput when options.quantum_mm is not positive or a
///        coordinate is too large for it.
nlohmann::json report_data(const std::string& outdir, const ReportHtmlOptions& options = {});

/// The complete HTML page for `data` (as report_data() returns it): the data
/// embedded as JSON (every '<' escaped so no text can close the element) and
/// the viewer script inlined.
std::string report_html_page(const nlohmann::json& data);

/// The viewer script (web/dist/report.js, minified three.js + page code) as
/// compiled into the library.
std::string_view report_viewer_script();

/// Writes the report page of `outdir` (report_data() + report_html_page())
/// atomically to options.output (default <outdir>/report.html).
/// \throw as report_data(); IOError when the page cannot be written.
void write_report_html(const std::string& outdir, const ReportHtmlOptions& options = {});

}  // namespace knitforge
