// knitforge body: bodies from measurements (seed ch. 5).
//   knitforge body make --height 176 --chest 96 ... [--pose a-pose|FILE.json] -o body.obj
#include <array>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <optional>
#include <chrono>

#include <fmt/core.h>

#include "cli_common.h"
#include "knitforge/body/body_json.h"
#include "knitforge/body/body_pose.h"
#include "knitforge/body/fit_body.h"
#include "knitforge/body/generated_body.h"
#include "knitforge/body/make_body.h"
#include "knitforge/evaluate/surface_distance.h"
#include "knitforge/io/mesh_io.h"
#include "knitforge/util/atomic_file.h"

namespace knitforge::cli {

namespace {

struct MakeOptions {
  std::array<std::optional<double>, kNumMeasurements> values;
  std::string units = "cm";
  std::string pose = "t-pose";
  std::string output;
  std::string params;
  double edge = 15.0;
  bool json = false;
};

BodyParams load_pose(const BodyModel& model, const std::string& pose) {
  for (const auto& n : pose_preset_names())
    if (pose == n) return pose_preset(model, pose);
  if (extension(pose) == ".json" || std::filesystem::exists(pose)) {
    const std::string text = read_text_file(pose, "pose file");
    nlohmann::json j;
    try {
      j = nlohmann::json::parse(text);
    } catch (const nlohmann::json::parse_error& e) {
      throw InvalidInput(fmt::format("{}: not valid JSON ({})", pose, e.what()));
    }
    return body_params_from_json(model, j, pose);
  }
  return pose_preset(model, pose);  // throws, listing the names
}

int run_make(const MakeOptions& o) {
  if (o.output.empty()) throw InvalidInput("body make: give the output mesh with -o FILE (.obj, .ply, .off, .stl)");
  const double scale = unit_scale(o.units);
  MeasurementTargets targets;
  for (int k = 0; k < kNumMeasurements; ++k) {
    const auto sk = static_cast<size_t>(k);
    if (o.values[sk]) targets.mm[sk] = *o.values[sk] * scale;
  }
  std::unique_ptr<BodyModel> own;
  const BodyModel* model = &generated_body();
  if (o.edge != GeneratedBodyOptions{}.edge_length) {
    GeneratedBodyOptions go;
    go.edge_length = o.edge;
    own = std::make_unique<BodyModel>(make_generated_body(go));
    model = own.get();
  }
  const BodyParams pose = load_pose(*model, o.pose);
  const MadeBody body = make_body(*model, targets, pose);
  for (const std::string& file : {o.output, o.params}) {
    const std::filesystem::path parent = std::filesystem::path(file).parent_path();
    if (!file.empty() && !parent.empty()) std::filesystem::create_directories(parent);
  }
  write_mesh(o.output, body.mesh);
  nlohmann::json report = body_params_to_json(*model, body.params, &body.fit.achieved);
  report["targets_mm"] = measurements_to_json(body.fit.targets);
  report["max_measurement_error_mm"] = body.fit.max_error_mm;
  report["newton_iterations"] = body.fit.iterations;
  report["vertex_parts"] = vertex_part_names(*model);
  report["joints_mm"] = nlohmann::json::object();
  for (int j = 0; j < model->num_joints(); ++j) {
    const Vec3& p = body.posed.joints[static_cast<size_t>(j)];
    report["joints_mm"][model->joint_names[static_cast<size_t>(j)]] = {p.x(), p.y(), p.z()};
  }
  if (!o.params.empty()) write_report_json(o.params, report, false);
  if (o.json) std::fputs((body_params_to_json(*model, body.params, &body.fit.achieved).dump(2) + "\n").c_str(), stdout);
  const auto& m = body.fit.achieved;
  note(fmt::format("body: {} vertices, height {:.1f} cm, chest {:.1f}, waist {:.1f}, hip {:.1f} cm "
                   "(largest error {:.2f} mm), pose {} -> {}",
                   body.mesh.num_vertices(), m[0] / 10.0, m[static_cast<size_t>(Measurement::ChestGirth)] / 10.0,
                   m[static_cast<size_t>(Measurement::WaistGirth)] / 10.0,
                   m[static_cast<size_t>(Measurement::HipGirth)] / 10.0, body.fit.max_error_mm, o.pose, o.output));
  return 0;
}

struct FitOptions {
  std::string input;
  std::string outdir;
  std::string units = "mm";
  std::string pose = "a-pose";
  std::string objective = "best";
  int iterations = BodyFitOptions{}.max_iterations;
  double max_distance = BodyFitOptions{}.max_distance_mm;
  bool json = false;
};

int run_fit(const FitOptions& o) {
  if (o.outdir.empty()) throw InvalidInput("body fit: give the output directory with -o DIR");
  const TriMesh scan = load_surface(o.input, o.units);
  const BodyModel& model = generated_body();
  BodyFitOptions fo;
  const bool cloud = o.objective == "cloud";
  if (!cloud && scan.faces.empty())
    throw InvalidInput(fmt::format("{}: has no faces; for a point cloud use --objective cloud", o.input));
  fo.direction = cloud ? BodyFitDirection::ScanToTemplate
                       : (o.objective == "both" ? BodyFitDirection::Both : BodyFitDirection::TemplateToScan);
  fo.max_iterations = o.iterations;
  fo.max_distance_mm = o.max_distance;
  const BodyParams init = place_on_scan(model, load_pose(model, o.pose), scan);
  const auto start = std::chrono::steady_clock::now();
  const BodyFitResult fit =
      o.objective == "best" ? fit_body_multistart(model, scan, init, fo) : fit_body(model, scan, init, fo);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const BodyMeasurements measured = measure_body(model, shape_body(model, fit.params.shape));
  const TriMesh body = posed_mesh(model, fit.posed);
  std::filesystem::create_directories(o.outdir);
  const std::filesystem::path dir(o.outdir);
  write_mesh((dir / "fitted.obj").string(), body);
  nlohmann::json report = body_params_to_json(model, fit.params, &measured);
  report["fit"] = {{"scan", o.input},
                   {"objective", cloud ? "eq. 5.4 cloud-to-template"
                                       : o.objective == "both" ? "eq. 5.1 + eq. 5.4 (both directions)"
                                       : o.objective == "best" ? "best of three (eq. 5.1; both from it; both), by both directions"
                                                               : "eq. 5.1 template-to-scan"},
                   {"rms_mm", fit.rms_mm},
                   {"initial_rms_mm", fit.initial_rms_mm},
                   {"iterations", fit.iterations},
                   {"converged", fit.converged},
                   {"seconds", seconds},
                   {"scan_points", scan.num_vertices()}};
  write_report_json((dir / "params.json").string(), report, o.json);
  // Per-vertex fit error of the fitted body to the scan surface; for a
  // point cloud (no faces), of every cloud point to the fitted body.
  if (!scan.faces.empty()) {
    const std::vector<double> err = vertex_distances_mm(body, scan);
    write_file_atomically((dir / "vertex_error.csv").string(), [&](std::ostream& os) {
      os << "vertex,error_mm,part\n";
      for (size_t i = 0; i < err.size(); ++i)
        os << i << ',' << fmt::format("{:.3f}", err[i]) << ',' << body_part_name(model.vertex_parts[i]) << '\n';
    });
  } else {
    const std::vector<double> err = distances_to_surface(body, scan.vertices);
    write_file_atomically((dir / "vertex_error.csv").string(), [&](std::ostream& os) {
      os << "scan_point,error_mm\n";
      for (size_t i = 0; i < err.size(); ++i) os << i << ',' << fmt::format("{:.3f}", err[i]) << '\n';
    });
  }
  const std::vector<BodyPart> parts = scan_vertex_parts(model, fit.posed, scan);
  write_file_atomically((dir / "scan_parts.csv").string(), [&](std::ostream& os) {
    os << "scan_vertex,part\n";
    for (size_t i = 0; i < parts.size(); ++i) os << i << ',' << body_part_name(parts[i]) << '\n';
  });
  note(fmt::format("body fit: rms {:.2f} mm (from {:.1f}) in {} iterations; height {:.1f} cm, chest {:.1f}, waist "
                   "{:.1f}, hip {:.1f} cm; {:.1f} s -> {}/fitted.obj, params.json, vertex_error.csv, scan_parts.csv",
                   fit.rms_mm, fit.initial_rms_mm, fit.iterations, measured[0] / 10.0,
                   measured[static_cast<size_t>(Measurement::ChestGirth)] / 10.0,
                   measured[static_cast<size_t>(Measurement::WaistGirth)] / 10.0,
                   measured[static_cast<size_t>(Measurement::HipGirth)] / 10.0, seconds, o.outdir));
  return 0;
}

}  // namespace

void add_body_command(CLI::App& app, Action& action) {
  auto* body = app.add_subcommand(
      "body", "Bodies for individuals (seed ch. 5): make a body from measurements, fit it to a scan");
  body->require_subcommand(1);
  auto* make = body->add_subcommand(
      "make",
      "Write the built-in body (our own model, generated by code) with the given measurements (ISO 8559-1) "
      "and pose as a mesh");
  auto o = std::make_shared<MakeOptions>();
  for (int k = 0; k < kNumMeasurements; ++k) {
    const MeasurementInfo& info = measurement_info(static_cast<Measurement>(k));
    make->add_option(fmt::format("--{}", info.option), o->values[static_cast<size_t>(k)],
                     fmt::format("{} (in --units; unset: {})", info.iso_term,
                                 info.is_girth ? "the model's" : "scaled with the height"))
        ->check(CLI::PositiveNumber);
  }
  make->add_option("--units", o->units, "Unit of the measurements: cm (default) or mm")
      ->check(CLI::IsMember({"cm", "mm"}));
  std::string poses;
  for (const auto& n : pose_preset_names()) poses += (poses.empty() ? "" : ", ") + n;
  make->add_option("--pose", o->pose, "Pose: " + poses + ", or a parameter JSON file (docs/body.md)");
  make->add_option("-o,--output", o->output, "Output mesh (.obj, .ply, .off, .stl), millimetres");
  make->add_option("--params", o->params,
                   "Also write the parameters, the measurements, the joints and each vertex's part (JSON)");
  make->add_option("--edge", o->edge, "Edge length of the model's mesh (mm, 8-60; 15 is built once and cached)")
      ->check(CLI::Range(8.0, 60.0));
  make->add_flag("--json", o->json, "Print the parameters and measurements as JSON");
  make->callback([o, &action] { action = [o] { return run_make(*o); }; });

  auto* fit = body->add_subcommand(
      "fit", "Fit the built-in body to a scan (eq. 5.1) or a partial point cloud (eq. 5.4): shape, pose, translation");
  auto f = std::make_shared<FitOptions>();
  fit->add_option("scan", f->input, "Scan mesh (.obj/.ply/.off/.stl), standing upright, z up, facing -y")->required();
  fit->add_option("-o,--output", f->outdir,
                  "Output directory: fitted.obj, params.json (parameters, measurements, fit), vertex_error.csv, "
                  "scan_parts.csv (each scan vertex's garment region)")
      ->required();
  fit->add_option("--units", f->units, "Units of the scan: mm (default), cm, m")->check(CLI::IsMember({"mm", "cm", "m"}));
  fit->add_option("--objective", f->objective,
                  "best (default): three fits (eq. 5.1; both directions from it; both from the initial pose), the "
                  "one nearest by both distances; scan: eq. 5.1 only (head, hands and feet ignored, as the seed); "
                  "both: eq. 5.1 + 5.4; cloud: eq. 5.4 only, for a partial view such as a depth camera's (the "
                  "input's faces, if any, are ignored)")
      ->check(CLI::IsMember({"best", "scan", "both", "cloud"}));
  fit->add_option("--pose", f->pose, "Initial pose: " + poses + " (default a-pose), or a parameter JSON file");
  fit->add_option("--iterations", f->iterations, "Most Gauss-Newton iterations (default 40)")->check(CLI::Range(1, 1000));
  fit->add_option("--max-distance", f->max_distance, "Pairs farther apart are ignored (mm, default 80)")
      ->check(CLI::PositiveNumber);
  fit->add_flag("--json", f->json, "Print params.json");
  fit->callback([f, &action] { action = [f] { return run_fit(*f); }; });
}

}  // namespace knitforge::cli
