// knitforge predict: the predicted shape of a knitted piece by the fabric
// simulator (docs/sim.md): the static equilibrium of its stitches at their
// ideal size, free or resting under gravity on a support, with the shape
// error to the design's target when there is one.
#include <filesystem>

#include <fmt/core.h>
#include <nlohmann/json.hpp>

#include "cli_common.h"
#include "knitforge/convert/map_to_stitch_mesh.h"
#include "knitforge/convert/relax_stitch_mesh.h"
#include "knitforge/evaluate/scalar_stats.h"
#include "knitforge/evaluate/shape_error.h"
#include "knitforge/geometry/shapes.h"
#include "knitforge/io/mesh_io.h"
#include "knitforge/io/stitch_mesh_ply.h"
#include "knitforge/sim/material_json.h"
#include "knitforge/sim/predict_shape.h"
#include "knitforge/util/timer.h"

namespace knitforge::cli {

namespace {

/// The largest piece predict takes (stitches): about 1 GB of memory and a
/// few minutes at the measured rate (docs/sim.md).
constexpr int kMaxStitches = 200000;

}  // namespace

void add_predict_command(CLI::App& app, Action& action) {
  auto* cmd = app.add_subcommand(
      "predict",
      "Predicted shape of a knitted piece by the fabric simulator (docs/sim.md): the equilibrium of its stitches at "
      "their ideal size, free or under gravity on a support, reported with its convergence and the shape error to "
      "the design's target");
  struct Opts {
    std::string input, outdir, stitch, on, target, material, units = "mm", projection = "none";
    double edge = kDefaultShapeEdgeLength, friction = 0.5, tolerance = 1e-5;
    int max_iterations = 500;
    bool gravity = false, json = false, ascii = false;
  };
  auto o = std::make_shared<Opts>();
  cmd->add_option("input", o->input,
                  "A design directory (its stitch_mesh.ply, target.ply and report.json), a stitch mesh (.ply) or "
                  "a knitting map (.csv; its Shape-Up relaxed shape is the start)")
      ->required();
  cmd->add_option("-o,--output", o->outdir, "Output directory")->required();
  cmd->add_option("--stitch", o->stitch,
                  "Stitch size WxH in mm (default: the design's report.json, else 3.5x2.8)");
  cmd->add_option("--on", o->on,
                  "Support to rest on: a mesh (.obj/.ply/.off/.stl; outer side = its face normals) or a built-in "
                  "shape (e.g. hemisphere)");
  cmd->add_option("--units", o->units, "Units of the --on mesh: mm, cm, m");
  cmd->add_option("--edge", o->edge, "Edge length (mm) of a built-in support's triangulation")
      ->check(CLI::PositiveNumber);
  cmd->add_flag("--gravity", o->gravity, "Gravity along -z (needs --on)");
  cmd->add_option("--projection", o->projection,
                  "Element Hessian projection of Newton: abs (absolute eigenvalues), clamp (negative ones to 0), "
                  "none (exact, shifted when indefinite)")
      ->check(CLI::IsMember({"abs", "clamp", "none"}))
      ->capture_default_str();
  cmd->add_option("--friction", o->friction, "Coulomb friction coefficient against the support")
      ->check(CLI::NonNegativeNumber)
      ->capture_default_str();
  cmd->add_option("--target", o->target, "Target surface for the shape error (default: DESIGN_DIR/target.ply)");
  cmd->add_option("--material", o->material,
                  "Material JSON (docs/sim.md; OUTDIR/material.json is the one used, to copy and edit)");
  cmd->add_option("--tolerance", o->tolerance, "Converged when no free vertex force exceeds this (mN)")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  cmd->add_option("--max-iterations", o->max_iterations, "Newton iterations at most (per friction round; the L-BFGS phase before them takes at most 20 times as many)")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  cmd->add_flag("--json", o->json, "Also print the report (predict.json) on stdout");
  cmd->add_flag("--ascii", o->ascii, "Write ASCII PLY");
  cmd->callback([=, &action] {
    action = [=]() -> int {
      const Timer all;
      namespace fs = std::filesystem;
      std::string mesh_path = o->input, target_path = o->target, stitch = o->stitch;
      if (fs::is_directory(o->input)) {
        mesh_path = (fs::path(o->input) / "stitch_mesh.ply").string();
        if (!fs::exists(mesh_path)) {
          throw InvalidInput(o->input + ": not a design directory (no stitch_mesh.ply); give a design command's "
                                        "output directory, a stitch mesh or a map");
        }
        if (target_path.empty() && fs::exists(fs::path(o->input) / "target.ply"))
          target_path = (fs::path(o->input) / "target.ply").string();
        const fs::path report = fs::path(o->input) / "report.json";
        if (stitch.empty() && fs::exists(report)) {
          const nlohmann::json r = nlohmann::json::parse(read_text_file(report.string(), "design report"), nullptr, false);
          if (r.is_object() && r.contains("parameters") && r["parameters"].contains("stitch_width_mm")) {
            stitch = fmt::format("{}x{}", r["parameters"]["stitch_width_mm"].get<double>(),
                                 r["parameters"]["stitch_height_mm"].get<double>());
          }
        }
      }
      const KnitParams params = parse_stitch_size(stitch.empty() ? "3.5x2.8" : stitch);
      const StitchInput in = load_stitch_input(mesh_path);
      StitchMesh designed;
      if (in.is_map) {
        RelaxOptions ro;
        designed = relax_stitch_mesh(map_to_stitch_mesh_topology(in.map, params), params, ro).mesh;
      } else {
        designed = in.mesh;
      }
      if (designed.num_stitches() > kMaxStitches) {
        throw InvalidInput(fmt::format("{}: {} stitches; predict takes at most {} (split the piece)", mesh_path,
                                       designed.num_stitches(), kMaxStitches));
      }
      PredictOptions po;
      if (!o->material.empty()) po.model.materials = {read_material_json(o->material)};
      po.gravity = o->gravity;
      po.equilibrium.projection = o->projection == "abs"     ? PsdProjection::Abs
                                  : o->projection == "clamp" ? PsdProjection::Clamp
                                                             : PsdProjection::None;
      po.equilibrium.contact.friction = o->friction;
      po.equilibrium.newton.force_tolerance_mn = o->tolerance;
      set_predict_iterations(po, o->max_iterations);
      std::string support_desc;
      KinematicBody support;
      if (!o->on.empty()) support = KinematicBody(load_surface_or_shape(o->on, o->units, o->edge, support_desc));
      note(fmt::format("predicting the shape of {} stitches ({}) ...", designed.num_stitches(),
                       o->on.empty() ? "free" : "on " + support_desc + (o->gravity ? ", gravity" : "")));
      const PredictResult r = predict_shape(designed, params, o->on.empty() ? nullptr : &support, po);

      fs::create_directories(o->outdir);
      auto out = [&](const char* name) { return (fs::path(o->outdir) / name).string(); };
      nlohmann::json j;
      j["input"] = {{"stitch_mesh", mesh_path}, {"stitches", designed.num_stitches()},
                    {"vertices", designed.num_vertices()}, {"triangles", r.num_elements},
                    {"stitch_width_mm", params.stitch_width}, {"stitch_height_mm", params.stitch_height}};
      j["setup"] = {{"support", o->on.empty() ? nlohmann::json(nullptr) : nlohmann::json(support_desc)},
                    {"gravity", o->gravity},
                    {"friction", o->friction},
                    {"lift_mm", r.lift_mm},
                    {"settle_steps", r.settle_steps},
                    {"settled", r.settled},
                    {"settle_seconds", r.settle_seconds},
                    {"contact_distance_mm", po.equilibrium.contact.distance_mm},
                    {"material", po.model.materials[0].name}};
      j["solve"] = {{"converged", r.solve.converged},
                    {"stop_reason", r.solve.stop_reason},
                    {"newton_iterations", r.solve.iterations},
                    {"factorizations", r.solve.factorizations},
                    {"local_minimum", r.solve.local_minimum},
                    {"quasi_newton_iterations", r.solve.quasi_newton_iterations},
                    {"quasi_newton_evaluations", r.solve.quasi_newton_evaluations},
                    {"max_free_force_mn", r.solve.max_force_mn},
                    {"force_tolerance_mn", o->tolerance},
                    {"projection", o->projection},
                    {"elastic_energy_uj", r.solve.energy},
                    {"contacts", r.solve.contacts},
                    {"min_distance_to_support_mm",
                     std::isfinite(r.solve.min_distance_mm) ? nlohmann::json(r.solve.min_distance_mm) : nullptr},
                    {"seconds", newton_timings_json(r.solve.seconds)},
                    {"history", newton_history_json(r.solve.history)}};
      j["stress_kpa"] = scalar_stats_json(scalar_stats(r.stitch_stress_kpa));
      j["stress_measure"] = "largest principal Cauchy membrane stress per stitch / thickness (kPa, 0 if compressed)";
      j["course_strain"] = scalar_stats_json(scalar_stats(r.stitch_course_strain));
      j["wale_strain"] = scalar_stats_json(scalar_stats(r.stitch_wale_strain));
      StitchMeshPlyOptions ply;
      ply.ascii = o->ascii;
      ply.scalars = {{"stress_kpa", r.stitch_stress_kpa},
                     {"course_strain", r.stitch_course_strain},
                     {"wale_strain", r.stitch_wale_strain}};
      if (!target_path.empty()) {
        const Timer shape_timer;
        const TriMesh target = read_mesh(target_path);
        const SurfaceBvh bvh(target);
        const ShapeError se = shape_error_to_target(r.predicted.vertices, designed, target, bvh, o->on.empty());
        j["shape_error"] = {{"target", target_path},
                            {"aligned", o->on.empty() ? "rigid fit to the design, then ICP onto the target"
                                                      : "as it rests on the support (no alignment)"},
                            {"rms_mm", se.rms_error},
                            {"max_mm", se.max_error},
                            {"relative_rms", se.relative_rms_error},
                            {"relative_max", se.relative_max_error},
                            {"designed_rms_mm", se.designed_rms_error},
                            {"icp_rounds", se.icp_iterations},
                            {"icp_converged", o->on.empty() ? nlohmann::json(se.icp_converged) : nlohmann::json()},
                            {"seconds", shape_timer.seconds()},
                            {"converged", r.solve.converged}};
        ply.scalars.push_back({"shape_error", se.stitch_error});
        if (o->on.empty()) {
          StitchMesh aligned = r.predicted;
          aligned.vertices = se.aligned;
          write_stitch_mesh_ply(out("predicted.ply"), aligned, ply);
        }
      }
      if (target_path.empty() || !o->on.empty()) write_stitch_mesh_ply(out("predicted.ply"), r.predicted, ply);
      if (!o->on.empty()) {
        MeshWriteOptions w;
        w.ascii = o->ascii;
        write_mesh(out("support.ply"), support.mesh(), w);
      }
      write_report_json(out("material.json"), material_to_json(po.model.materials[0]), false);
      j["seconds"] = all.seconds();
      write_report_json(out("predict.json"), j, o->json);
      note(fmt::format("{} after {} L-BFGS and {} Newton iterations (largest free force {:.3g} mN, tolerance "
                       "{:.3g}){}; {:.2f} s -> {}",
                       r.solve.converged ? "converged" : "NOT converged (" + r.solve.stop_reason + ")",
                       r.solve.quasi_newton_iterations, r.solve.iterations, r.solve.max_force_mn, o->tolerance,
                       j.contains("shape_error")
                           ? fmt::format("; shape error RMS {:.3f} mm, max {:.3f} mm",
                                         j["shape_error"]["rms_mm"].get<double>(),
                                         j["shape_error"]["max_mm"].get<double>())
                           : std::string(),
                       all.seconds(), o->outdir));
      return r.solve.converged ? 0 : 1;
    };
  });
}

}  // namespace knitforge::cli
