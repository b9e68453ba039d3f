// The design routes' converged predicted shape (cli_common.h,
// design_prediction()): the same free equilibrium and shape-error measure as
// `knitforge predict DESIGN_DIR`; report_design_shape(), the evaluation and
// prediction sections every design route writes.
#include <filesystem>

#include <fmt/core.h>

#include "cli_common.h"
#include "knitforge/evaluate/shape_error.h"
#include "knitforge/io/stitch_mesh_ply.h"
#include "knitforge/sim/predict_shape.h"
#include "knitforge/util/timer.h"

namespace knitforge::cli {

void add_design_predict_options(CLI::App& cmd, DesignPredictOptions& options) {
  auto* on = cmd.add_flag("--predict", options.force,
                          fmt::format("Predict the shape with the fabric simulator (free, converged; as `knitforge "
                                      "predict`) even above {} stitches, where it is off by default",
                                      kDesignPredictMaxStitches));
  cmd.add_flag("--no-predict", options.skip, "Skip the fabric simulator's predicted shape")->excludes(on);
  cmd.add_option("--predict-max-iterations", options.max_iterations,
                 "Newton iterations at most of the predicted shape (default 500; the L-BFGS phase before them "
                 "takes at most 20 times as many)")
      ->check(positive_number());
}

nlohmann::json design_prediction(const DesignPredictOptions& options, const std::string& outdir,
                                 const StitchMesh& designed, const KnitParams& params, const TriMesh& target,
                                 bool ascii, std::string& summary) {
  summary.clear();
  // A predicted.ply of an earlier run into this directory would be shown by
  // the report page as this design's: only a converged prediction of this run writes one.
  std::error_code ec;
  std::filesystem::remove(std::filesystem::path(outdir) / "predicted.ply", ec);
  if (options.skip) return nullptr;
  const int n = designed.num_stitches();
  if (n == 0) return nullptr;
  if (!options.force && n > kDesignPredictMaxStitches) {
    summary = fmt::format(
        "predicted shape skipped: {} stitches is above the default limit of {} (it would take about {:.0f} s); "
        "--predict runs it, or `knitforge predict {}`",
        n, kDesignPredictMaxStitches, 0.0015 * n, outdir);
    return nullptr;
  }
  const Timer t;
  note(fmt::format("predicting the shape of {} stitches (fabric simulator, free) ...", n));
  PredictOptions po;
  set_predict_iterations(po, options.max_iterations);
  const PredictResult r = predict_shape(designed, params, nullptr, po);
  nlohmann::json j = {{"predictor", "fabric simulator: free static equilibrium (as knitforge predict)"},
                      {"converged", r.solve.converged},
                      {"stop_reason", r.solve.stop_reason},
                      {"newton_iterations", r.solve.iterations},
                      {"quasi_newton_iterations", r.solve.quasi_newton_iterations},
                      {"factorizations", r.solve.factorizations},
                      {"max_free_force_mn", r.solve.max_force_mn},
                      {"force_tolerance_mn", po.equilibrium.newton.force_tolerance_mn},
                      {"elastic_energy_uj", r.solve.energy},
                      {"solve_seconds", newton_timings_json(r.solve.seconds)}};
  if (r.solve.converged) {
    const SurfaceBvh bvh(target);
    const ShapeError se = shape_error_to_target(r.predicted.vertices, designed, target, bvh, true);
    j["aligned"] = "rigid fit to the design, then ICP onto the target";
    j["shape_error_mm"] = {{"rms", se.rms_error}, {"max", se.max_error}};
    j["shape_error_relative"] = {{"rms", se.relative_rms_error}, {"max", se.relative_max_error}};
    StitchMesh aligned = r.predicted;
    aligned.vertices = se.aligned;
    StitchMeshPlyOptions ply;
    ply.ascii = ascii;
    ply.scalars = {{"shape_error", se.stitch_error}};
    write_stitch_mesh_ply((std::filesystem::path(outdir) / "predicted.ply").string(), aligned, ply);
    summary = fmt::format(
        "predicted shape error RMS {:.3f} mm, max {:.3f} mm (converged after {} L-BFGS and {} Newton iterations)",
        se.rms_error, se.max_error, r.solve.quasi_newton_iterations, r.solve.iterations);
  } else {
    j["shape_error_mm"] = nullptr;
    summary = fmt::format(
        "predicted shape NOT converged ({}, {} L-BFGS and {} Newton iterations, largest free force {:.3g} mN): "
        "no predicted shape error",
        r.solve.stop_reason, r.solve.quasi_newton_iterations, r.solve.iterations, r.solve.max_force_mn);
  }
  j["seconds"] = t.seconds();
  return j;
}

std::vector<std::string> report_design_shape(nlohmann::json& report, const DesignPredictOptions& options,
                                             bool no_evaluate, const std::string& outdir,
                                             const StitchMesh& designed, const KnitParams& params,
                                             const TriMesh& target, const StitchMeshEvaluation* evaluation,
                                             bool ascii) {
  std::vector<std::string> lines;
  if (evaluation) {
    report["evaluation"] = evaluation_json(*evaluation);
    report["evaluation"]["predictor"] = "Shape-Up preview (not a converged shape)";
    lines.push_back(fmt::format(
        "preview (Shape-Up) shape error RMS {:.3f} mm, max {:.3f} mm ({:.2f} % / {:.2f} % of the part size)",
        evaluation->rms_error, evaluation->max_error, 100 * evaluation->relative_rms_error,
        100 * evaluation->relative_max_error));
  }
  DesignPredictOptions po = options;
  po.skip = po.skip || (no_evaluate && !po.force);
  std::string summary;
  report["prediction"] = design_prediction(po, outdir, designed, params, target, ascii, summary);
  if (!summary.empty()) lines.push_back(summary);
  return lines;
}

}  // namespace knitforge::cli
