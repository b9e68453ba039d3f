#pragma once
/// \file program_report.h
/// A fabric view of any knitout program (`knitforge simulate FILE.k
/// --report OUTDIR`, docs/machines.md): what the virtual machine found, per
/// course, placed on the fabric the program knits, drawn in a report page.
///
/// Files written to the output directory (atomically; the directory is
/// created):
///  - knitout.k: the program (so the page's knitout panel and download work);
///  - report.json: {"program", "machine": verdict, counts per category,
///    statistics, yarn per carrier (estimates), "fabric": {"kind": "sheet" |
///    "tube" | "none", "reason", "stitches", "courses" and "wales" (the map's
///    rows and columns), "rounds" and "closed_end" (a tube's map), "rounds"
///    and "ring" (plain rounds), "stitch_size_mm"}, "courses": one entry per carriage pass that
///    made stitches ({"pass", "lines": [first, last], "carriers",
///    "direction", "knits", "tucks", "splits", "misses", "needles": [lo, hi],
///    "section", "time_s"}), "diagnostics": every finding with its line,
///    severity, category, check, message and, where it concerns a loop of
///    the fabric, the stitch and its position (mm) on the relaxed shape};
///  - for a sheet or a tube read back as its map (knit_graph_to_map.h):
///    knitting_map.csv, stitch_mesh.ply (the map's stitch mesh relaxed to
///    its rest shape, relax_stitch_mesh.h; a tube's from a cylinder) and
///    yarn.obj (stitch_mesh_to_yarn.h);
///  - for plain rounds without a map: stitch_mesh.ply, the rounds as a ring
///    of quads closed around, relaxed from a cylinder (no yarn model);
///  - report.html (report_html.h), unless options.html is false.
/// Stitch size: one needle pitch wide (25.4 / gauge mm) and 0.75 pitch high
/// unless given (a nominal jersey proportion; the shape is a prediction of
/// the fabric's topology, not of its yarn and tension).

#include <string>

#include <nlohmann/json.hpp>

#include "knitforge/core/knit_params.h"
#include "knitforge/machine/knit_graph_to_map.h"
#include "knitforge/machine/knitout_simulate.h"

namespace knitforge {

struct ProgramReportOptions {
  KnitParams params{0.0, 0.0};  ///< stitch size (mm); 0 = from the gauge (see the file comment)
  int relax_iterations = 60;    ///< Shape-Up iterations for the rest shape
  bool html = true;             ///< write report.html
  /// Largest fabric drawn (stitches); beyond it only report.json and
  /// knitout.k are written (a note says so).
  int max_stitches = 200000;
};

struct ProgramReport {
  KnitGraphFabric fabric;
  nlohmann::json json;  ///< the report.json written
};

/// Writes the fabric view of `sim` (the simulation of `program_text`, read
/// from `program_name`) into `outdir` (see the file comment).
/// \throw IOError when a file cannot be written; InvalidInput for bad options.
ProgramReport write_program_report(const std::string& program_name, const std::string& program_text,
                                   const KnitoutSimulation& sim, const std::string& outdir,
                                   const ProgramReportOptions& options = {});

}  // namespace knitforge
