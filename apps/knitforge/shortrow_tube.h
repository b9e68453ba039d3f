#pragma once
// knitforge shortrow --tube: a surface with two boundary loops knitted in the
// round (design/tube/design_tube.h, docs/tubes.md "Design").
#include <optional>
#include <string>
#include <vector>

#include "cli_common.h"
#include "knitforge/design/tube/tube_field_candidates.h"

namespace knitforge::cli {

/// The options of `shortrow` that --tube reads.
struct TubeCommandOptions {
  std::string input, outdir, stitch, units;
  double edge = 0.0, max_stitches = 0.0;
  bool json = false, ascii = false, no_report = false;
  bool short_rows = true;  ///< !--no-tube-short-rows
  int crown_stitches = 12;  ///< --crown-stitches (a closed tube: one boundary loop)
  TubeFieldKind field = TubeFieldKind::Auto;  ///< --tube-field
  DesignMachineOptions mach;
  DesignPredictOptions predict;  ///< the converged predicted shape (report_design_shape())
  bool no_evaluate = false;      ///< --no-evaluate: no prediction unless --predict
};

/// The --tube flags of the design commands (`shortrow`, `shortcolumn`).
struct TubeFlags {
  bool tube = false;
  bool no_tube_short_rows = false;
  int crown_stitches = 12;
  std::string tube_field = "auto";
};
/// Adds --tube, --crown-stitches, --tube-field and --no-tube-short-rows to cmd.
void add_tube_flags(CLI::App& cmd, TubeFlags& flags);

/// With --tube: the options the tube route takes from the command (the
/// common ones), after refusing every option in `sheet_only` that was given
/// (the sheet route's field, seams, ...: UsageError naming it), and an
/// unknown --tube-field. Without --tube: refuses --no-tube-short-rows and
/// --tube-field and returns nothing.
/// \throw UsageError as above.
std::optional<TubeCommandOptions> tube_command(const TubeFlags& flags, const std::vector<const CLI::Option*>& sheet_only);

/// Copies the options every design command shares (input, output, stitch,
/// units, edge, limits, report and machine options) from a command's own
/// option struct into the tube route's.
template <class CommandOptions>
void copy_common_options(const CommandOptions& o, TubeCommandOptions& t) {
  t.input = o.input;
  t.outdir = o.outdir;
  t.stitch = o.stitch;
  t.units = o.units;
  t.edge = o.edge;
  t.max_stitches = o.max_stitches;
  t.json = o.json;
  t.ascii = o.ascii;
  t.no_report = o.no_report;
  t.mach = o.mach;
  t.predict = o.predict;
  t.no_evaluate = o.no_evaluate;
}

/// Runs the tube route and writes its outputs; returns the exit code (0
/// knittable, 1 not, as `shortrow`).
int run_tube_design(const TubeCommandOptions& o);

}  // namespace knitforge::cli
