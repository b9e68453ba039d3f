// knitforge body: bodies from measurements (seed ch. 5).
//   knitforge body make --height 176 --chest 96 ... [--pose a-pose|FILE.json] -o body.obj
//   knitforge body make --model SMPL.npz [--shape b0,b1,...] [--pose ...] -o body.obj
//   knitforge body fit SCAN [--keypoints K.json] [--model SMPL.npz] -o fitted/
//   knitforge body region fitted/|BODY.obj --part torso-front [--model SMPL.npz] -o panel.obj
//   knitforge body transfer GARMENT.obj --from A --to B -o out.obj
//   knitforge body render-depth / calibrate / fuse: body_depth.cpp
#include <algorithm>
#include <array>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <map>
#include <memory>
#include <optional>
#include <random>
#include <chrono>

#include <fmt/core.h>

#include "body_ddr_options.h"
#include "cli_common.h"
#include "knitforge/body/body_json.h"
#include "knitforge/body/body_pose.h"
#include "knitforge/body/cut_body_region.h"
#include "knitforge/body/fit_body.h"
#include "knitforge/body/generated_body.h"
#include "knitforge/body/keypoint_views.h"
#include "knitforge/body/make_body.h"
#include "knitforge/body/pose_from_keypoints.h"
#include "knitforge/body/smpl_model_npz.h"
#include "knitforge/body/transfer_garment.h"
#include "knitforge/evaluate/surface_distance.h"
#include "knitforge/io/mesh_io.h"
#include "knitforge/util/atomic_file.h"
#include "knitforge/util/number_list.h"

namespace knitforge::cli {

namespace {

struct MakeOptions {
  std::array<std::optional<double>, kNumMeasurements> values;
  std::string units = "cm";
  std::string pose = "t-pose";
  std::string output;
  std::string params;
  std::string model;  // an SMPL-format .npz instead of the built-in model
  std::string shape;  // its shape parameters, "b0,b1,..."
  double edge = 15.0;
  double noise = 0.0;
  unsigned seed = 1;
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

// The mesh of body make, with --noise as a stand-in for a scan; creates the
// directories of the output files.
void write_made_body(const MakeOptions& o, const TriMesh& mesh) {
  for (const std::string& file : {o.output, o.params}) {
    const std::filesystem::path parent = std::filesystem::path(file).parent_path();
    if (!file.empty() && !parent.empty()) std::filesystem::create_directories(parent);
  }
  if (o.noise > 0.0) {
    // Uniform noise per coordinate (deterministic).
    TriMesh noisy = mesh;
    std::mt19937 rng(o.seed);
    std::uniform_real_distribution<double> u(-o.noise, o.noise);
    for (Vec3& v : noisy.vertices) v += Vec3(u(rng), u(rng), u(rng));
    write_mesh(o.output, noisy);
  } else {
    write_mesh(o.output, mesh);
  }
}

nlohmann::json joints_json(const BodyModel& model, const PosedBody& posed) {
  nlohmann::json j = nlohmann::json::object();
  for (int q = 0; q < model.num_joints(); ++q) {
    const Vec3& p = posed.joints[static_cast<size_t>(q)];
    j[model.joint_names[static_cast<size_t>(q)]] = {p.x(), p.y(), p.z()};
  }
  return j;
}

// body make --model: a body of a licensed SMPL-format model from its shape
// parameters (not from measurements: its shape parameters are betas; the
// body's measurements are reported when the model has landmarks).
int run_make_from_file(const MakeOptions& o) {
  for (int k = 0; k < kNumMeasurements; ++k) {
    if (o.values[static_cast<size_t>(k)])
      throw InvalidInput(fmt::format("body make: --{} cannot be used with --model: a model file's shape parameters "
                                     "are not measurements; give them with --shape b0,b1,...",
                                     measurement_info(static_cast<Measurement>(k)).option));
  }
  if (o.edge != GeneratedBodyOptions{}.edge_length)
    throw InvalidInput("body make: --edge is the built-in model's mesh size; a model file (--model) has its own mesh");
  const BodyModel model = load_smpl_model(o.model);
  BodyParams params = load_pose(model, o.pose);
  const std::vector<double> betas = o.shape.empty() ? std::vector<double>{} : parse_number_list(o.shape, "body make --shape");
  if (static_cast<int>(betas.size()) > model.num_shapes())
    throw InvalidInput(fmt::format("body make --shape: {} values, the model {} has {} shape parameters", betas.size(),
                                   o.model, model.num_shapes()));
  for (size_t k = 0; k < betas.size(); ++k) params.shape(static_cast<Eigen::Index>(k)) = betas[k];
  const PosedBody posed = pose_body(model, params);
  write_made_body(o, posed_mesh(model, posed));
  const std::optional<BodyMeasurements> measured =
      model.landmarks.empty() ? std::nullopt
                              : std::optional<BodyMeasurements>(measure_body(model, shape_body(model, params.shape)));
  nlohmann::json report = body_params_to_json(model, params, measured ? &*measured : nullptr);
  report["joints_mm"] = joints_json(model, posed);
  if (!model.vertex_parts.empty()) report["vertex_parts"] = vertex_part_names(model);
  if (!o.params.empty()) write_report_json(o.params, report, false);
  if (o.json) std::fputs((body_params_to_json(model, params).dump(2) + "\n").c_str(), stdout);
  note(fmt::format("body: {} of {} vertices, {} joints, {} of {} shape parameters given, pose {}{} -> {}", o.model,
                   model.num_vertices(), model.num_joints(), betas.size(), model.num_shapes(), o.pose,
                   o.noise > 0.0 ? fmt::format(", noise ±{:g} mm", o.noise) : "", o.output));
  return 0;
}

int run_make(const MakeOptions& o) {
  if (o.output.empty()) throw InvalidInput("body make: give the output mesh with -o FILE (.obj, .ply, .off, .stl)");
  if (!o.model.empty()) return run_make_from_file(o);
  if (!o.shape.empty())
    throw InvalidInput("body make: --shape gives the shape parameters of a model file (--model FILE.npz); the "
                       "built-in model takes measurements (--height, --chest, ...)");
  const double scale = unit_scale(o.units);
  MeasurementTargets targets;
  for (int k = 0; k < kNumMeasurements; ++k) {
    const auto sk = static_cast<size_t>(k);
    if (o.values[sk]) targets.mm[sk] = *o.values[sk] * scale;
  }
  // Another --edge builds only its own model (not the default one first).
  std::unique_ptr<BodyModel> own;
  if (o.edge != GeneratedBodyOptions{}.edge_length) {
    GeneratedBodyOptions go;
    go.edge_length = o.edge;
    own = std::make_unique<BodyModel>(make_generated_body(go));
  }
  const BodyModel* model = own ? own.get() : &generated_body();
  const BodyParams pose = load_pose(*model, o.pose);
  const MadeBody body = make_body(*model, targets, pose);
  write_made_body(o, body.mesh);
  nlohmann::json report = body_params_to_json(*model, body.params, &body.fit.achieved);
  report["targets_mm"] = measurements_to_json(body.fit.targets);
  report["max_measurement_error_mm"] = body.fit.max_error_mm;
  report["newton_iterations"] = body.fit.iterations;
  report["vertex_parts"] = vertex_part_names(*model);
  report["joints_mm"] = joints_json(*model, body.posed);
  if (!o.params.empty()) write_report_json(o.params, report, false);
  if (o.json) std::fputs((body_params_to_json(*model, body.params, &body.fit.achieved).dump(2) + "\n").c_str(), stdout);
  const auto& m = body.fit.achieved;
  note(fmt::format("body: {} vertices, height {:.1f} cm, chest {:.1f}, waist {:.1f}, hip {:.1f} cm "
                   "(largest error {:.2f} mm), pose {}{} -> {}",
                   body.mesh.num_vertices(), m[0] / 10.0, m[static_cast<size_t>(Measurement::ChestGirth)] / 10.0,
                   m[static_cast<size_t>(Measurement::WaistGirth)] / 10.0,
                   m[static_cast<size_t>(Measurement::HipGirth)] / 10.0, body.fit.max_error_mm, o.pose,
                   o.noise > 0.0 ? fmt::format(", noise ±{:g} mm", o.noise) : "", o.output));
  return 0;
}

struct FitOptions {
  std::string input;
  std::string outdir;
  std::string units = "mm";
  std::string pose = "a-pose";
  std::string objective = "best";
  std::string keypoints;
  std::string model;
  int iterations = BodyFitOptions{}.max_iterations;
  std::string optimizer = "gauss-newton";
  int evaluations = BodyFitOptions{}.max_evaluations;
  std::uint64_t seed = BodyFitOptions{}.seed;
  double max_distance = BodyFitOptions{}.max_distance_mm;
  bool json = false;
};

int run_fit(const FitOptions& o) {
  if (o.outdir.empty()) throw InvalidInput("body fit: give the output directory with -o DIR");
  const TriMesh scan = load_surface(o.input, o.units);
  // A model file: its first 10 shape directions (SMPL's usual betas; the
  // cost of a fit grows with their number).
  std::unique_ptr<BodyModel> own;
  if (!o.model.empty()) own = std::make_unique<BodyModel>(load_smpl_model(o.model, {.max_shapes = 10}));
  const BodyModel& model = own ? *own : generated_body();
  const bool labelled = !model.vertex_parts.empty();
  BodyFitOptions fo;
  // SMPL's betas are unitless (about one standard deviation per unit): a
  // prior of 1 mm² per beta² keeps the shapes the scan does not constrain
  // near the mean; ours are mm of a measurement.
  if (own) fo.shape_prior = 1.0;
  const bool cloud = o.objective == "cloud";
  if (!cloud && scan.faces.empty())
    throw InvalidInput(fmt::format("{}: has no faces; for a point cloud use --objective cloud", o.input));
  fo.direction = cloud ? BodyFitDirection::ScanToTemplate
                       : (o.objective == "both" ? BodyFitDirection::Both : BodyFitDirection::TemplateToScan);
  fo.max_iterations = o.iterations;
  const bool evolution = o.optimizer == "evolution";
  fo.optimizer = evolution ? BodyFitOptimizer::EvolutionStrategy : BodyFitOptimizer::GaussNewton;
  fo.max_evaluations = o.evaluations;
  fo.seed = o.seed;
  fo.max_distance_mm = o.max_distance;
  const auto start = std::chrono::steady_clock::now();
  BodyParams init;
  nlohmann::json keypoint_report;
  if (o.keypoints.empty()) {
    init = place_on_scan(model, load_pose(model, o.pose), scan);
  } else {
    // Seed §5.A: keypoints triangulated from the calibrated views, then the
    // initial pose and placement from them.
    const std::string text = read_text_file(o.keypoints, "keypoints file");
    nlohmann::json j;
    try {
      j = nlohmann::json::parse(text);
    } catch (const nlohmann::json::parse_error& e) {
      throw InvalidInput(fmt::format("{}: not valid JSON ({})", o.keypoints, e.what()));
    }
    const TriangulatedKeypoints tk = triangulate_keypoints(keypoint_views_from_json(j, o.keypoints));
    std::map<std::string, Vec3> points;
    keypoint_report = nlohmann::json::object();
    for (const auto& [name, k] : tk.points) {
      points[name] = k.point_mm;
      keypoint_report["points_mm"][name] = {k.point_mm.x(), k.point_mm.y(), k.point_mm.z()};
      keypoint_report["rms_ray_distance_mm"][name] = k.rms_ray_distance_mm;
    }
    keypoint_report["skipped"] = tk.skipped;
    const KeypointPose kp = pose_from_keypoints(model, points, load_pose(model, o.pose));
    keypoint_report["joints_used"] = kp.joints_used;
    keypoint_report["initial_joint_rms_mm"] = kp.rms_mm;
    keypoint_report["scale"] = kp.scale;
    init = kp.params;
    note(fmt::format("body fit: {} keypoints from {} views ({} seen in fewer than two skipped); initial pose: joints "
                     "{:.1f} mm rms from them, scale {:.3f}",
                     kp.joints_used, j["cameras"].size(), tk.skipped.size(), kp.rms_mm, kp.scale));
  }
  const BodyFitResult fit =
      o.objective == "best" ? fit_body_multistart(model, scan, init, fo) : fit_body(model, scan, init, fo);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  // A model file whose landmarks could not be derived has no measurements.
  const std::optional<BodyMeasurements> measured =
      model.landmarks.empty() ? std::nullopt
                              : std::optional<BodyMeasurements>(measure_body(model, shape_body(model, fit.params.shape)));
  const TriMesh body = posed_mesh(model, fit.posed);
  std::filesystem::create_directories(o.outdir);
  const std::filesystem::path dir(o.outdir);
  write_mesh((dir / "fitted.obj").string(), body);
  nlohmann::json report = body_params_to_json(model, fit.params, measured ? &*measured : nullptr);
  report["fit"] = {{"scan", o.input},
                   {"objective", cloud ? "eq. 5.4 cloud-to-template"
                                       : o.objective == "both" ? "eq. 5.1 + eq. 5.4 (both directions)"
                                       : o.objective == "best" ? "best of five (eq. 5.1; both from it; both; the first two from the scan's girths), by both directions"
                                                               : "eq. 5.1 template-to-scan"},
                   {"rms_mm", fit.rms_mm},
                   {"initial_rms_mm", fit.initial_rms_mm},
                   {"optimizer", evolution ? "(1+1) evolution strategy" : "Gauss-Newton (Levenberg-Marquardt)"},
                   {"iterations", fit.iterations},
                   {"evaluations", fit.evaluations},
                   {"converged", fit.converged},
                   {"seconds", seconds},
                   {"scan_points", scan.num_vertices()},
                   {"units", o.units},
                   {"keypoints", o.keypoints.empty() ? nlohmann::json(nullptr) : keypoint_report}};
  write_report_json((dir / "params.json").string(), report, o.json);
  // Per-vertex fit error of the fitted body to the scan surface; for a
  // point cloud (no faces), of every cloud point to the fitted body.
  if (!scan.faces.empty()) {
    const std::vector<double> err = vertex_distances_mm(body, scan);
    write_file_atomically((dir / "vertex_error.csv").string(), [&](std::ostream& os) {
      os << (labelled ? "vertex,error_mm,part\n" : "vertex,error_mm\n");
      for (size_t i = 0; i < err.size(); ++i) {
        os << i << ',' << fmt::format("{:.3f}", err[i]);
        if (labelled) os << ',' << body_part_name(model.vertex_parts[i]);
        os << '\n';
      }
    });
  } else {
    const std::vector<double> err = distances_to_surface(body, scan.vertices);
    write_file_atomically((dir / "vertex_error.csv").string(), [&](std::ostream& os) {
      os << "scan_point,error_mm\n";
      for (size_t i = 0; i < err.size(); ++i) os << i << ',' << fmt::format("{:.3f}", err[i]) << '\n';
    });
  }
  // Garment regions on the scan need the model's part labels.
  if (labelled) {
    const std::vector<BodyPart> parts = scan_vertex_parts(model, fit.posed, scan);
    write_file_atomically((dir / "scan_parts.csv").string(), [&](std::ostream& os) {
      os << "scan_vertex,part\n";
      for (size_t i = 0; i < parts.size(); ++i) os << i << ',' << body_part_name(parts[i]) << '\n';
    });
  }
  const std::string sizes =
      measured ? fmt::format("height {:.1f} cm, chest {:.1f}, waist {:.1f}, hip {:.1f} cm", (*measured)[0] / 10.0,
                             (*measured)[static_cast<size_t>(Measurement::ChestGirth)] / 10.0,
                             (*measured)[static_cast<size_t>(Measurement::WaistGirth)] / 10.0,
                             (*measured)[static_cast<size_t>(Measurement::HipGirth)] / 10.0)
               : fmt::format("model {} (no measurements, no garment regions: {})", model.name, model.labels_note);
  std::string work = evolution ? fmt::format("{} evaluations of the evolution strategy", fit.evaluations)
                               : fmt::format("{} iterations", fit.iterations);
  // The rms of a fit stopped by its budget is not a minimum: say so (params.json: fit.converged).
  if (!fit.converged)
    work += evolution ? " (not converged: --evaluations raises the budget)" : " (not converged: --iterations raises the limit)";
  note(fmt::format("body fit: rms {:.2f} mm (from {:.1f}) in {}; {}; {:.1f} s -> {}/fitted.obj, "
                   "params.json, vertex_error.csv{}",
                   fit.rms_mm, fit.initial_rms_mm, work, sizes, seconds, o.outdir,
                   labelled ? ", scan_parts.csv" : ""));
  return 0;
}

struct RegionOptions {
  std::string input;
  std::string part;
  std::string output;
  std::string scan;
  double edge = 0.0;
  double model_edge = 15.0;
  std::string model;  // an SMPL-format .npz instead of the built-in model
  int remesh = BodyRegionOptions{}.remesh_iterations;
};

const BodyModel& model_with_edge(double edge, std::unique_ptr<BodyModel>& own) {
  if (edge == GeneratedBodyOptions{}.edge_length) return generated_body();
  GeneratedBodyOptions go;
  go.edge_length = edge;
  own = std::make_unique<BodyModel>(make_generated_body(go));
  return *own;
}

int run_region(const RegionOptions& o) {
  if (o.output.empty()) throw InvalidInput("body region: give the output mesh with -o FILE (.obj, .ply, .off, .stl)");
  const BodyPart part = body_part_from_name(o.part);
  std::unique_ptr<BodyModel> own;
  if (!o.model.empty()) {
    if (o.model_edge != RegionOptions{}.model_edge)
      throw InvalidInput("body region: --model-edge is the built-in model's mesh size; a model file (--model) has its "
                         "own mesh");
    own = std::make_unique<BodyModel>(load_smpl_model(o.model));
    if (own->vertex_parts.empty())
      throw InvalidInput(fmt::format("body region: the model {} has no garment regions: {}", o.model, own->labels_note));
  }
  const BodyModel& model = own ? *own : model_with_edge(o.model_edge, own);
  TriMesh surface;
  std::vector<double> field;
  std::string source;
  std::error_code ec;
  if (std::filesystem::is_directory(o.input, ec)) {
    // A fit's directory: the scan, with the field carried from the fitted body.
    const std::filesystem::path dir(o.input);
    const std::string params_path = (dir / "params.json").string();
    nlohmann::json params;
    try {
      params = nlohmann::json::parse(read_text_file(params_path, "fit parameters"));
    } catch (const nlohmann::json::parse_error& e) {
      throw InvalidInput(fmt::format("{}: not valid JSON ({})", params_path, e.what()));
    }
    if (params.contains("model") && params["model"].is_string() && params["model"].get<std::string>() != model.name)
      throw InvalidInput(fmt::format("{}: the fit used the model '{}', not '{}'; give the model file the fit used "
                                     "with --model FILE.npz (or none for the built-in model)",
                                     params_path, params["model"].get<std::string>(), model.name));
    std::string scan_path = o.scan;
    if (scan_path.empty()) {
      if (!params.contains("fit") || !params["fit"].contains("scan") || !params["fit"]["scan"].is_string())
        throw InvalidInput(fmt::format("{}: names no scan (fit.scan); give it with --scan FILE", params_path));
      scan_path = params["fit"]["scan"].get<std::string>();
    }
    const std::string units =
        params.contains("fit") && params["fit"].contains("units") && params["fit"]["units"].is_string()
            ? params["fit"]["units"].get<std::string>()
            : "mm";
    surface = load_surface(scan_path, units);
    if (surface.faces.empty())
      throw InvalidInput(fmt::format("{}: has no faces; a region is cut out of a scan mesh", scan_path));
    const TriMesh fitted = load_surface((dir / "fitted.obj").string(), "mm");
    // The fit's own labels must belong to this scan.
    const std::string parts_path = (dir / "scan_parts.csv").string();
    const std::string parts = read_text_file(parts_path, "scan parts");
    const auto rows = static_cast<int>(std::count(parts.begin(), parts.end(), '\n')) - 1;
    if (rows != surface.num_vertices())
      throw InvalidInput(fmt::format("{}: {} rows for a scan of {} vertices ({}): the directory is not this scan's fit",
                                     parts_path, rows, surface.num_vertices(), scan_path));
    field = scan_part_field(model, fitted, surface, part);
    source = scan_path + " fitted in " + o.input;
  } else {
    surface = load_surface(o.input, "mm");
    if (surface.num_vertices() != model.num_vertices() || surface.faces != model.faces)
      throw InvalidInput(fmt::format("{}: {} vertices, {} faces: not a body of {} ({} vertices; as written by body "
                                     "make/fit{}); for a scan give the directory of its fit",
                                     o.input, surface.num_vertices(), surface.num_faces(),
                                     !o.model.empty() ? "the model " + o.model
                                                      : fmt::format("the built-in model at edge {} mm", o.model_edge),
                                     model.num_vertices(), o.model.empty() ? "; for a model file's body give --model" : ""));
    field = body_part_field(model, part);
    source = o.input;
  }
  BodyRegionOptions ro;
  ro.edge_length_mm = o.edge;
  ro.remesh_iterations = o.remesh;
  const BodyRegion region = cut_body_region(surface, field, ro);
  const std::filesystem::path parent = std::filesystem::path(o.output).parent_path();
  if (!parent.empty()) std::filesystem::create_directories(parent);
  write_mesh(o.output, region.mesh);
  note(fmt::format("body region: {} of {}: {} vertices, {} faces, {:.0f} cm², rim {:.0f} mm ({} islands removed, {} "
                   "holes filled, edges {:.1f} mm) -> {}",
                   o.part, source, region.mesh.num_vertices(), region.mesh.num_faces(), region.area_mm2 / 100.0,
                   region.boundary_length_mm, region.islands_removed, region.holes_filled, region.edge_length_mm,
                   o.output));
  return 0;
}

struct TransferOptions {
  std::string garment;
  std::string from;
  std::string to;
  std::string output;
  std::string units = "mm";
};

// A body mesh: a file, or a fit's directory (its fitted.obj).
TriMesh load_body_mesh(const std::string& path) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) return load_surface((std::filesystem::path(path) / "fitted.obj").string(), "mm");
  return load_surface(path, "mm");
}

int run_transfer(const TransferOptions& o) {
  if (o.output.empty()) throw InvalidInput("body transfer: give the output mesh with -o FILE");
  const TriMesh garment = load_surface(o.garment, o.units);
  const TriMesh a = load_body_mesh(o.from), b = load_body_mesh(o.to);
  if (a.num_vertices() != b.num_vertices() || a.faces != b.faces)
    throw InvalidInput(fmt::format("body transfer: {} ({} vertices) and {} ({} vertices) are not bodies of the same "
                                   "model (same vertices and faces); use outputs of body make / body fit with the "
                                   "same --edge",
                                   o.from, a.num_vertices(), o.to, b.num_vertices()));
  const TriMesh moved = transfer_garment(garment, a, b);
  double largest = 0.0;
  for (size_t i = 0; i < moved.vertices.size(); ++i)
    largest = std::max(largest, (moved.vertices[i] - garment.vertices[i]).norm());
  const std::filesystem::path parent = std::filesystem::path(o.output).parent_path();
  if (!parent.empty()) std::filesystem::create_directories(parent);
  write_mesh(o.output, moved);
  note(fmt::format("body transfer: {} vertices of {} rigged to {} (eq. 5.13, 1-ring faces), moved to {}: largest "
                   "displacement {:.1f} mm -> {}",
                   moved.num_vertices(), o.garment, o.from, o.to, largest, o.output));
  return 0;
}

}  // namespace

void add_body_command(CLI::App& app, Action& action) {
  auto* body = app.add_subcommand(
      "body", "Bodies for individuals (seed ch. 5): make a body from measurements, fit it to a scan, cut garment regions, move garments between bodies");
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
  make->add_option("--pose", o->pose, "Pose: " + poses + ", or a parameter JSON file (docs/bodies.md)");
  make->add_option("-o,--output", o->output, "Output mesh (.obj, .ply, .off, .stl), millimetres");
  make->add_option("--params", o->params,
                   "Also write the parameters, the measurements, the joints and each vertex's part (JSON)");
  make->add_option("--model", o->model,
                   "A licensed SMPL-format model file (.npz: docs/bodies.md) instead of the built-in model; its "
                   "shape is given by --shape, not by measurements (which --params reports)");
  make->add_option("--shape", o->shape,
                   "With --model: the shape parameters (betas) b0,b1,... (unitless; those not given are 0)");
  make->add_option("--edge", o->edge, "Edge length of the model's mesh (mm, 8-60; 15 is built once and cached)")
      ->check(CLI::Range(8.0, 60.0));
  make->add_option("--noise", o->noise,
                   "Move every vertex by uniform noise in ±MM per coordinate, as a stand-in for a scan (the "
                   "--params are the noiseless body's)")
      ->check(CLI::Range(0.0, 50.0));
  make->add_option("--seed", o->seed, "Seed of --noise (default 1)");
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
                  "best (default): five fits (eq. 5.1; both directions from it; both from the initial pose; the "
                  "first two again from the scan's own girths), the one nearest by both distances; scan: eq. 5.1 only (head, hands and feet ignored, as the seed); "
                  "both: eq. 5.1 + 5.4; cloud: eq. 5.4 only, for a partial view such as a depth camera's (the "
                  "input's faces, if any, are ignored)")
      ->check(CLI::IsMember({"best", "scan", "both", "cloud"}));
  fit->add_option("--pose", f->pose, "Initial pose: " + poses + " (default a-pose), or a parameter JSON file");
  fit->add_option("--keypoints", f->keypoints,
                  "Initial pose and placement from 3D keypoints triangulated from calibrated views (seed 5.A; the "
                  "JSON format: docs/formats.md) instead of --pose on the scan's bounding box");
  fit->add_option("--model", f->model,
                  "Fit a licensed SMPL-format model file (.npz: docs/bodies.md; its first 10 shape parameters) "
                  "instead of the built-in model; its part labels and landmarks are derived from its joints, "
                  "weights and shape (a model they cannot be derived for: no measurements, no scan_parts.csv)");
  fit->add_option("--iterations", f->iterations, "Most Gauss-Newton iterations (default 40)")->check(CLI::Range(1, 1000));
  fit->add_option("--optimizer", f->optimizer,
                  "gauss-newton (default) or evolution: the seed's gradient-free (1+1) evolution strategy on the "
                  "same objective (thousands of evaluations; slower, kept for comparison)")
      ->check(CLI::IsMember({"gauss-newton", "evolution"}));
  fit->add_option("--evaluations", f->evaluations,
                  "Most cost evaluations of the evolution strategy per fit (default 4000; --objective best runs "
                  "five fits)")
      ->check(CLI::Range(1, 100000));
  fit->add_option("--seed", f->seed, "Seed of the evolution strategy's random steps (default 1)");
  fit->add_option("--max-distance", f->max_distance, "Pairs farther apart are ignored (mm, default 80)")
      ->check(CLI::PositiveNumber);
  fit->add_flag("--json", f->json, "Print params.json");
  fit->callback([f, &action] { action = [f] { return run_fit(*f); }; });
  auto* region = body->add_subcommand(
      "region", "Cut a garment region out of a fitted scan or a body of the model: a disk-like panel with a smooth "
                "rim for shortrow / flatten");
  auto r = std::make_shared<RegionOptions>();
  std::string part_names;
  for (int q = 0; q < kNumBodyParts; ++q) part_names += (q ? ", " : "") + body_part_name(static_cast<BodyPart>(q));
  region->add_option("input", r->input,
                     "The output directory of body fit (the region is cut out of its scan) or a body mesh written by "
                     "body make / body fit (fitted.obj)")
      ->required();
  region->add_option("--part", r->part, "The region: " + part_names)->required();
  region->add_option("-o,--output", r->output, "Output mesh (.obj, .ply, .off, .stl), millimetres")->required();
  region->add_option("--scan", r->scan, "The scan of a fit directory, when not the one its params.json names");
  region->add_option("--edge", r->edge, "Edge length of the panel (mm; default: that of the cut surface)")
      ->check(CLI::NonNegativeNumber);
  region->add_option("--remesh", r->remesh, "Isotropic remeshing iterations of the panel (default 3; 0: none)")
      ->check(CLI::Range(0, 50));
  region->add_option("--model", r->model,
                     "The licensed SMPL-format model file (.npz) the body or the fit was made with, instead of the "
                     "built-in model");
  region->add_option("--model-edge", r->model_edge, "Edge length of the body model (mm) the body was made with (body make --edge; default 15)")
      ->check(CLI::Range(8.0, 60.0));
  region->callback([r, &action] { action = [r] { return run_region(*r); }; });

  auto* transfer = body->add_subcommand(
      "transfer", "Move a garment designed on body A to body B of the same model (style transfer, seed eq. 5.13)");
  auto t = std::make_shared<TransferOptions>();
  transfer->add_option("garment", t->garment, "The garment mesh (.obj/.ply/.off/.stl), on body A")->required();
  transfer->add_option("--from", t->from, "Body A: a mesh of body make / body fit, or a fit's directory")->required();
  transfer->add_option("--to", t->to, "Body B: the same model, another shape or pose")->required();
  transfer->add_option("-o,--output", t->output, "Output mesh: the garment on body B")->required();
  transfer->add_option("--units", t->units, "Units of the garment: mm (default), cm, m (the output is in mm)")
      ->check(CLI::IsMember({"mm", "cm", "m"}));
  transfer->callback([t, &action] { action = [t] { return run_transfer(*t); }; });
  add_body_depth_commands(*body, action);
  add_body_photo_command(*body, action);
  // The LibTorch commands run in their own program (knitforge-ddr).
  const auto forward = [](const auto&) -> int { run_sibling_program("knitforge-ddr"); };
  add_body_ddr_commands(*body, action, {forward, forward, forward});
}

}  // namespace knitforge::cli
