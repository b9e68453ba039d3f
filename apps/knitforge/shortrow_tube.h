#pragma once
// knitforge shortrow --tube: a surface with two boundary loops knitted in the
// round (design/tube/design_tube.h, docs/tubes.md "Design").
#include <string>

#include "cli_common.h"

namespace knitforge::cli {

/// The options of `shortrow` that --tube reads.
struct TubeCommandOptions {
  std::string input, outdir, stitch, units;
  double edge = 0.0, max_stitches = 0.0;
  bool json = false, ascii = false, no_report = false;
  bool short_rows = true;  ///< !--no-tube-short-rows
  int crown_stitches = 12;  ///< --crown-stitches (a closed tube: one boundary loop)
  DesignMachineOptions mach;
  DesignPredictOptions predict;  ///< the converged predicted shape (report_design_shape())
  bool no_evaluate = false;      ///< --no-evaluate: no prediction unless --predict
};

/// Runs the tube route and writes its outputs; returns the exit code (0
/// knittable, 1 not, as `shortrow`).
int run_tube_design(const TubeCommandOptions& o);

}  // namespace knitforge::cli
