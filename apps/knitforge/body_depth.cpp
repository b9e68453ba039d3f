// knitforge body render-depth / calibrate / fuse: two depth cameras (seed §5.3).
//   knitforge body render-depth [MESH] -o DIR [--poses K] [--noise MM]      synthetic captures
//   knitforge body calibrate --camera1 C1.json --camera2 C2.json --thickness MM IMAGES... -o calibration.json
//   knitforge body fuse K1.png K2.png --camera1 C1.json --camera2 C2.json --calibration CAL.json -o body.ply
//   knitforge body calibrate-study [--noise LIST] [--poses LIST] [--runs N]     the calibration error, as a table
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <numbers>

#include <fmt/core.h>

#include "cli_common.h"
#include "knitforge/body/calibrate_depth_cameras.h"
#include "knitforge/body/depth_image.h"
#include "knitforge/body/fuse_point_clouds.h"
#include "knitforge/body/json_values.h"
#include "knitforge/body/poisson_reconstruct.h"
#include "knitforge/body/render_depth_image.h"
#include "knitforge/body/study_depth_calibration.h"
#include "knitforge/body/synthetic_depth_scenes.h"
#include "knitforge/evaluate/scalar_stats.h"
#include "knitforge/evaluate/surface_distance.h"
#include "knitforge/io/mesh_io.h"

namespace knitforge::cli {

namespace {

DepthCamera read_camera(const std::string& path) { return depth_camera_from_json(read_json_file(path, "camera intrinsics"), path); }

std::string parse_size3(const std::string& text, BoardSize& size) {
  double a = 0, b = 0, c = 0;
  char x1 = 0, x2 = 0;
  char tail = 0;
  if (std::sscanf(text.c_str(), "%lf%c%lf%c%lf%c", &a, &x1, &b, &x2, &c, &tail) != 5 || x1 != 'x' || x2 != 'x')
    return fmt::format("--board {}: give WIDTHxHEIGHTxTHICKNESS in mm, e.g. 600x450x10", text);
  size = {a, b, c};
  if (!(a > 0 && b > 0 && c > 0) || !std::isfinite(a + b + c))
    return fmt::format("--board {}: every size must be a positive number (mm)", text);
  return "";
}

// ---------------------------------------------------------------- render-depth

struct RenderDepthOptions {
  std::string mesh;
  std::string outdir;
  std::string board = "600x450x10";
  std::string units = "mm";
  int poses = 6;
  double noise = 1.0;
  double outliers = 0.0;
  double distance = 2000.0;
  unsigned seed = 1;
};

int run_render_depth(const RenderDepthOptions& o) {
  BoardSize board;
  if (const std::string e = parse_size3(o.board, board); !e.empty()) throw UsageError(e);
  check_output_dir("--output", o.outdir, {o.mesh});
  const DepthRig rig = seed_depth_rig(o.distance);
  std::vector<std::pair<std::string, TriMesh>> scenes;
  nlohmann::json truth = depth_rig_to_json(rig);
  if (o.mesh.empty()) {
    const std::vector<RigidTransform> poses = random_board_poses(rig, o.poses, o.seed);
    truth["board_mm"] = {board.width_mm, board.height_mm, board.thickness_mm};
    truth["board_poses"] = nlohmann::json::array();
    for (size_t i = 0; i < poses.size(); ++i) {
      scenes.emplace_back(fmt::format("board_{:02d}", i + 1), board_mesh(board, poses[i]));
      truth["board_poses"].push_back(rigid_transform_to_json(poses[i]));
    }
  } else {
    scenes.emplace_back("scene", load_surface(o.mesh, o.units));
    truth["scene"] = o.mesh;
  }
  // Render everything before writing anything.
  std::vector<std::pair<std::string, DepthImage>> images;
  unsigned seed = o.seed;
  for (const auto& [name, mesh] : scenes) {
    for (int cam = 1; cam <= 2; ++cam) {
      DepthImage image = render_depth_image(mesh, cam == 1 ? rig.camera1 : rig.camera2,
                                            cam == 1 ? rig.world_to_camera1 : rig.world_to_camera2);
      add_depth_noise(image, {o.noise, o.outliers, seed++});
      images.emplace_back(fmt::format("{}_k{}.png", name, cam), std::move(image));
    }
  }
  std::filesystem::create_directories(o.outdir);
  const std::filesystem::path dir(o.outdir);
  for (size_t i = 0; i < images.size(); ++i)
    write_depth_image((dir / images[i].first).string(), images[i].second, i % 2 == 0 ? rig.camera1 : rig.camera2);
  write_report_json((dir / "camera1.json").string(), depth_camera_to_json(rig.camera1), false);
  write_report_json((dir / "camera2.json").string(), depth_camera_to_json(rig.camera2), false);
  truth["noise_mm"] = o.noise;
  truth["outlier_fraction"] = o.outliers;
  truth["seed"] = o.seed;
  write_report_json((dir / "rig.json").string(), truth, false);
  note(fmt::format("body render-depth: {} seen by two cameras {:.0f} mm apart ({}x{} px, f {:.0f} px), noise {:g} mm{} "
                   "-> {}/ ({}, camera1.json, camera2.json, rig.json)",
                   o.mesh.empty() ? fmt::format("{} board poses ({})", o.poses, o.board) : o.mesh, o.distance,
                   rig.camera1.width, rig.camera1.height, rig.camera1.K(0, 0), o.noise,
                   o.outliers > 0 ? fmt::format(", {:g} % outliers", 100.0 * o.outliers) : "", o.outdir,
                   images.size() == 2 ? images[0].first + ", " + images[1].first
                                      : images[0].first + " ... " + images.back().first));
  return 0;
}

// ---------------------------------------------------------------- calibrate

struct CalibrateOptions {
  std::vector<std::string> images;
  std::string camera1, camera2;
  std::string output;
  std::string truth;
  double thickness = -1.0;
  double min_depth = 0.0;
  double max_depth = 0.0;
  double inlier_distance = RansacPlaneOptions{}.inlier_distance_mm;
  unsigned seed = 1;
  bool json = false;
};

// The image pairs: files in pairs, or a directory's NAME_k1.png + NAME_k2.png.
std::vector<std::pair<std::string, std::string>> image_pairs(const std::vector<std::string>& args) {
  std::vector<std::string> files;
  for (const std::string& a : args) {
    std::error_code ec;
    if (!std::filesystem::is_directory(a, ec)) {
      files.push_back(a);
      continue;
    }
    std::vector<std::string> k1;
    for (const auto& e : std::filesystem::directory_iterator(a)) {
      const std::string name = e.path().filename().string();
      if (name.size() > 7 && name.ends_with("_k1.png")) k1.push_back(e.path().string());
    }
    std::sort(k1.begin(), k1.end());
    if (k1.empty()) throw InvalidInput(fmt::format("{}: a directory without NAME_k1.png images", a));
    for (const std::string& f : k1) {
      const std::string f2 = f.substr(0, f.size() - 7) + "_k2.png";
      if (!std::filesystem::exists(f2)) throw InvalidInput(fmt::format("{}: has no {} to pair with", f, f2));
      files.push_back(f);
      files.push_back(f2);
    }
  }
  if (files.size() % 2 != 0)
    throw UsageError(fmt::format("body calibrate: {} images; give them in pairs, camera 1's then camera 2's image of "
                                 "each board pose",
                                 files.size()));
  std::vector<std::pair<std::string, std::string>> pairs;
  for (size_t i = 0; i + 1 < files.size(); i += 2) pairs.emplace_back(files[i], files[i + 1]);
  return pairs;
}

DepthRange depth_range(double min_depth, double max_depth) {
  DepthRange r;
  r.min_mm = min_depth;
  if (max_depth > 0.0) r.max_mm = max_depth;
  if (!(r.max_mm > r.min_mm))
    throw UsageError(fmt::format("--min-depth {} must be below --max-depth {}", min_depth, max_depth));
  return r;
}

int run_calibrate(const CalibrateOptions& o) {
  if (o.thickness < 0.0)
    throw UsageError("body calibrate: give the board's thickness with --thickness MM (the seed's c; 0 for a sheet)");
  check_output_file("--output", o.output, {".json"});
  const auto pairs = image_pairs(o.images);
  if (pairs.size() < 3) {
    std::string given;
    for (const std::string& a : o.images) given += (given.empty() ? "" : ", ") + a;
    throw InvalidInput(fmt::format("{}: {} board pose{} (image pairs); eq. 5.2/5.3 need at least 3 poses, no two "
                                   "parallel: capture the board tilted differently {} more time{}",
                                   given, pairs.size(), pairs.size() == 1 ? "" : "s", 3 - pairs.size(),
                                   3 - pairs.size() == 1 ? "" : "s"));
  }
  const DepthCamera cam1 = read_camera(o.camera1), cam2 = read_camera(o.camera2);
  std::vector<BoardCapture> captures;
  for (const auto& [a, b] : pairs)
    captures.push_back({read_depth_image(a, cam1), read_depth_image(b, cam2),
                        std::filesystem::path(a).filename().string() + " + " +
                            std::filesystem::path(b).filename().string()});
  RansacPlaneOptions ro;
  ro.inlier_distance_mm = o.inlier_distance;
  ro.seed = o.seed;
  DepthCalibrationOptions co;
  co.thickness_mm = o.thickness;
  const DepthImageCalibration result =
      calibrate_from_depth_images(captures, cam1, cam2, depth_range(o.min_depth, o.max_depth), ro, co);
  const DepthCalibration& c = result.calibration;
  const RigidTransform& T = c.camera2_to_camera1;
  nlohmann::json report = {{"camera2_to_camera1", rigid_transform_to_json(T)},
                           {"poses", c.poses},
                           {"thickness_mm", c.thickness_mm},
                           {"spread", c.spread},
                           {"normal_residual_deg", c.normal_residual_deg},
                           {"plane_residual_mm", c.plane_residual_mm},
                           {"camera1", o.camera1},
                           {"camera2", o.camera2}};
  double lo_frac = 1.0, hi_frac = 0.0, worst_rms = 0.0;
  report["planes"] = nlohmann::json::array();
  for (size_t i = 0; i < pairs.size(); ++i) {
    nlohmann::json pose = {{"images", {pairs[i].first, pairs[i].second}}};
    for (int cam = 0; cam < 2; ++cam) {
      const RansacPlane& p = cam == 0 ? result.detected1[i] : result.detected2[i];
      pose[cam == 0 ? "camera1" : "camera2"] = {{"normal", json_values::to_json(p.normal)},
                                                {"point_mm", json_values::to_json(p.point)},
                                                {"inlier_fraction", p.inlier_fraction},
                                                {"rms_mm", p.rms_mm},
                                                {"hypotheses", p.iterations}};
      lo_frac = std::min(lo_frac, p.inlier_fraction);
      hi_frac = std::max(hi_frac, p.inlier_fraction);
      worst_rms = std::max(worst_rms, p.rms_mm);
    }
    report["planes"].push_back(pose);
  }
  std::string against;
  if (!o.truth.empty()) {
    const DepthRig rig = depth_rig_from_json(read_json_file(o.truth, "rig"), o.truth);
    const RigidTransform truth = camera2_to_camera1(rig);
    const double rot = rotation_angle_between_deg(T.rotation, truth.rotation);
    const double tr = (T.translation - truth.translation).norm();
    report["truth"] = {{"rig", o.truth}, {"rotation_error_deg", rot}, {"translation_error_mm", tr}};
    against = fmt::format("; against {}: rotation error {:.3f}°, translation error {:.2f} mm", o.truth, rot, tr);
  }
  write_report_json(o.output, report, o.json);
  const auto rms = [](const std::vector<double>& v) {
    double s = 0;
    for (double x : v) s += x * x;
    return std::sqrt(s / static_cast<double>(v.size()));
  };
  note(fmt::format("body calibrate: {} poses; the board holds {:.0f}-{:.0f} % of the points in range (plane rms <= "
                   "{:.2f} mm); residuals: normals {:.3f}° rms (eq. 5.2), mid-planes {:.2f} mm rms (eq. 5.3); camera "
                   "2 is {:.1f} mm from camera 1, turned {:.2f}°{} -> {}",
                   c.poses, 100.0 * lo_frac, 100.0 * hi_frac, worst_rms, rms(c.normal_residual_deg),
                   rms(c.plane_residual_mm), T.translation.norm(),
                   rotation_angle_between_deg(T.rotation, Mat3::Identity()), against, o.output));
  return 0;
}

// ---------------------------------------------------------------- fuse

struct FuseOptions {
  std::string image1, image2;
  std::string camera1, camera2;
  std::string calibration;
  std::string output;
  std::string truth;
  std::string rig;
  double min_depth = 0.0;
  double max_depth = 0.0;
  double voxel = FusePointOptions{}.voxel_mm;
  double max_points = PoissonOptions{}.max_points;
  bool upright = false;
  bool json = false;
};

// Camera 1's frame -> z up, facing -y (exact for a level camera 1).
const Mat3& upright_rotation() {
  static const Mat3 R = (Mat3() << 1, 0, 0, 0, 0, 1, 0, -1, 0).finished();
  return R;
}

int run_fuse(const FuseOptions& o) {
  // The report JSON beside the mesh must not replace an input either (a
  // calibration named like the output).
  const std::vector<std::string> inputs = {o.image1, o.image2, o.camera1, o.camera2, o.calibration, o.truth, o.rig};
  check_output_file("--output", o.output, {".obj", ".ply", ".off", ".stl"}, inputs);
  const std::string report_path = std::filesystem::path(o.output).replace_extension(".json").string();
  check_output_file("--output's report", report_path, {".json"}, inputs);
  if (!o.truth.empty() && o.rig.empty())
    throw UsageError("body fuse: --truth needs --rig RIG.json (where the cameras stood relative to the true mesh)");
  const DepthCamera cam1 = read_camera(o.camera1), cam2 = read_camera(o.camera2);
  const nlohmann::json cal = read_json_file(o.calibration, "calibration");
  const RigidTransform T =
      rigid_transform_from_json(json_values::field(cal, "camera2_to_camera1", o.calibration),
                                o.calibration + ": camera2_to_camera1");
  const DepthImage d1 = read_depth_image(o.image1, cam1), d2 = read_depth_image(o.image2, cam2);
  const DepthRange range = depth_range(o.min_depth, o.max_depth);
  const OrientedPoints c1 = depth_to_oriented_points(d1, cam1, range), c2 = depth_to_oriented_points(d2, cam2, range);
  FusePointOptions fo;
  fo.voxel_mm = o.voxel;
  OrientedPoints fused = fuse_point_clouds(c1, c2, T, fo);
  if (o.upright)
    for (size_t i = 0; i < fused.points.size(); ++i) {
      fused.points[i] = upright_rotation() * fused.points[i];
      fused.normals[i] = upright_rotation() * fused.normals[i];
    }
  PoissonOptions po;
  po.max_points = o.max_points;
  const PoissonResult rec = poisson_reconstruct(fused, po);
  nlohmann::json report = {{"images", {o.image1, o.image2}},
                           {"calibration", o.calibration},
                           {"points", {{"camera1", c1.points.size()}, {"camera2", c2.points.size()}, {"fused", fused.points.size()}}},
                           {"voxel_mm", o.voxel},
                           {"poisson_spacing_mm", rec.spacing_mm},
                           {"mesh", {{"vertices", rec.mesh.num_vertices()}, {"faces", rec.mesh.num_faces()}}},
                           {"frame", o.upright ? "camera 1, upright (x, z, -y)" : "camera 1"}};
  std::string against;
  if (!o.truth.empty()) {
    const DepthRig rig = depth_rig_from_json(read_json_file(o.rig, "rig"), o.rig);
    TriMesh truth = load_surface(o.truth, "mm");
    for (Vec3& v : truth.vertices) {
      v = rig.world_to_camera1.apply(v);
      if (o.upright) v = upright_rotation() * v;
    }
    const ScalarStats to_truth = scalar_stats(distances_to_surface(truth, rec.mesh.vertices));
    const ScalarStats points_to_truth = scalar_stats(distances_to_surface(truth, fused.points));
    const ScalarStats from_truth = scalar_stats(distances_to_surface(rec.mesh, truth.vertices));
    report["truth"] = {{"mesh", o.truth},
                       {"reconstruction_to_truth_mm", scalar_stats_json(to_truth)},
                       {"fused_points_to_truth_mm", scalar_stats_json(points_to_truth)},
                       {"truth_to_reconstruction_mm", scalar_stats_json(from_truth)}};
    against = fmt::format("; against {}: points {:.2f} mm rms, surface {:.2f} mm rms (p90 {:.1f}, max {:.1f}), the "
                          "true surface to it {:.2f} mm rms",
                          o.truth, points_to_truth.rms, to_truth.rms, to_truth.p90, to_truth.max, from_truth.rms);
  }
  write_mesh(o.output, rec.mesh);
  write_report_json(report_path, report, o.json);
  note(fmt::format("body fuse: {} + {} points, {} after {:g} mm voxels; Poisson (spacing {:.1f} mm): {} vertices, {} "
                   "faces{} -> {}, {}",
                   c1.points.size(), c2.points.size(), fused.points.size(), o.voxel, rec.spacing_mm,
                   rec.mesh.num_vertices(), rec.mesh.num_faces(), against, o.output, report_path));
  return 0;
}

// ---------------------------------------------------------------- calibrate-study

struct CalibrateStudyOptions {
  std::vector<double> noise = {0.0, 0.5, 1.0, 2.0, 4.0};
  std::vector<int> poses = {3, 4, 6, 10};
  int runs = 5;
  std::string board = "600x450x10";
  double outliers = 0.0;
  unsigned seed = 1;
};

int run_calibrate_study(const CalibrateStudyOptions& o) {
  DepthCalibrationStudyOptions so;
  if (const std::string e = parse_size3(o.board, so.board); !e.empty()) throw UsageError(e);
  so.noise_mm = o.noise;
  so.poses = o.poses;
  so.runs = o.runs;
  so.outlier_fraction = o.outliers;
  so.seed = o.seed;
  const std::vector<DepthCalibrationStudyRow> rows = study_depth_calibration(so);
  std::printf("| depth noise σ (mm) | poses k | calibrations | rotation error (°) mean / max | translation error "
              "(mm) mean / max |\n|---|---|---|---|---|\n");
  for (const DepthCalibrationStudyRow& r : rows) {
    const std::string failed = r.failed > 0 ? fmt::format(" ({} refused)", r.failed) : "";
    if (r.runs == 0) {
      std::printf("%s\n", fmt::format("| {:g} | {} | 0{} | — | — |", r.noise_mm, r.poses, failed).c_str());
      continue;
    }
    std::printf("%s\n", fmt::format("| {:g} | {} | {}{} | {:.3f} / {:.3f} | {:.2f} / {:.2f} |", r.noise_mm, r.poses,
                                    r.runs, failed, r.rotation_mean_deg, r.rotation_max_deg, r.translation_mean_mm,
                                    r.translation_max_mm)
                            .c_str());
  }
  note(fmt::format("body calibrate-study: {} noise levels x {} pose counts x {} runs on the seed's rig (board {}, "
                   "depths in 1 mm units{})",
                   o.noise.size(), o.poses.size(), o.runs, o.board,
                   o.outliers > 0 ? fmt::format(", {:g} % outliers", 100.0 * o.outliers) : ""));
  return 0;
}

}  // namespace

void add_body_depth_commands(CLI::App& body, Action& action) {
  auto* render = body.add_subcommand(
      "render-depth", "Synthetic depth images (16-bit PNG + intrinsics JSON) from the seed's dual-camera rig: the "
                      "calibration board in random poses, or a mesh (a body of body make), with depth noise");
  auto r = std::make_shared<RenderDepthOptions>();
  render->add_option("mesh", r->mesh, "A mesh to capture (world frame: z up, facing -y, as body make writes); "
                                      "none: the calibration board in --poses poses");
  render->add_option("-o,--output", r->outdir,
                     "Output directory: NAME_k1.png / NAME_k2.png per pose, camera1.json, camera2.json, rig.json "
                     "(the true rig and board poses)")
      ->required();
  render->add_option("--poses", r->poses, "Board poses (default 6)")->check(CLI::Range(1, 100));
  render->add_option("--board", r->board, "Board WIDTHxHEIGHTxTHICKNESS (mm, default 600x450x10)");
  render->add_option("--noise", r->noise, "Gaussian depth noise, sigma (mm, default 1)")->check(number_in(0.0, 100.0));
  render->add_option("--outliers", r->outliers, "Fraction of pixels replaced by random depths (default 0)")
      ->check(number_in(0.0, 0.5));
  render->add_option("--distance", r->distance, "Distance between the cameras (mm, default 2000, the seed's)")
      ->check(number_in(800.0, 10000.0));
  render->add_option("--units", r->units, "Units of the mesh: mm (default), cm, m")->check(CLI::IsMember({"mm", "cm", "m"}));
  render->add_option("--seed", r->seed, "Seed of the poses and the noise (default 1)");
  render->callback([r, &action] { action = [r] { return run_render_depth(*r); }; });

  auto* calibrate = body.add_subcommand(
      "calibrate", "Calibrate two facing depth cameras from k >= 3 depth images pairs of a flat board (seed eq. "
                   "5.2/5.3, RANSAC planes): camera 2's frame to camera 1's");
  auto c = std::make_shared<CalibrateOptions>();
  calibrate->add_option("images", c->images,
                        "Depth images (16-bit PNG) in pairs, camera 1's then camera 2's of each pose; or directories "
                        "of NAME_k1.png + NAME_k2.png")
      ->required();
  calibrate->add_option("--camera1", c->camera1, "Intrinsics of camera 1 (JSON: docs/formats.md)")->required();
  calibrate->add_option("--camera2", c->camera2, "Intrinsics of camera 2")->required();
  calibrate->add_option("--thickness", c->thickness, "The board's thickness c (mm)")->required()->check(number_in(0.0, 1000.0));
  calibrate->add_option("-o,--output", c->output, "Output calibration (JSON: R, t, residuals, planes)")->required();
  calibrate->add_option("--min-depth", c->min_depth, "Ignore depths up to this (mm; default 0)")->check(non_negative_number());
  calibrate->add_option("--max-depth", c->max_depth, "Ignore depths beyond this, e.g. the walls behind (mm; default: none)")
      ->check(non_negative_number());
  calibrate->add_option("--inlier-distance", c->inlier_distance, "RANSAC inlier distance (mm, default 4: 4 sigma of 1 mm noise)")
      ->check(positive_number());
  calibrate->add_option("--seed", c->seed, "Seed of RANSAC (default 1)");
  calibrate->add_option("--truth", c->truth, "The rig.json of body render-depth: also report the errors against it");
  calibrate->add_flag("--json", c->json, "Print the calibration");
  calibrate->callback([c, &action] { action = [c] { return run_calibrate(*c); }; });

  auto* fuse = body.add_subcommand(
      "fuse", "Fuse the two depth images of a person into one point cloud (calibrated) and reconstruct a closed "
              "mesh (Poisson)");
  auto f = std::make_shared<FuseOptions>();
  fuse->add_option("image1", f->image1, "Camera 1's depth image (16-bit PNG)")->required();
  fuse->add_option("image2", f->image2, "Camera 2's depth image")->required();
  fuse->add_option("--camera1", f->camera1, "Intrinsics of camera 1 (JSON)")->required();
  fuse->add_option("--camera2", f->camera2, "Intrinsics of camera 2 (JSON)")->required();
  fuse->add_option("--calibration", f->calibration, "The output of body calibrate (or a rig.json)")->required();
  fuse->add_option("-o,--output", f->output, "Output mesh (.obj/.ply/.off/.stl; mm, camera 1's frame); a report "
                                             "JSON beside it")
      ->required();
  fuse->add_option("--min-depth", f->min_depth, "Ignore depths up to this (mm)")->check(non_negative_number());
  fuse->add_option("--max-depth", f->max_depth, "Ignore depths beyond this (mm; default: none)")->check(non_negative_number());
  fuse->add_option("--voxel", f->voxel, "Averaging grid of the fused points (mm, default 4)")->check(number_in(0.5, 100.0));
  fuse->add_option("--max-points", f->max_points, "Refuse Poisson beyond this many fused points (default 300000)")
      ->check(positive_number());
  fuse->add_flag("--upright", f->upright,
                 "Rotate camera 1's frame (x right, y down, z ahead) to z up, facing -y (x, z, -y): exact for a "
                 "level camera 1; what body fit expects");
  fuse->add_option("--truth", f->truth, "The true mesh (world frame; with --rig): also report the distances to it");
  fuse->add_option("--rig", f->rig, "The rig.json of body render-depth (for --truth)");
  fuse->add_flag("--json", f->json, "Print the report");
  fuse->callback([f, &action] { action = [f] { return run_fuse(*f); }; });

  auto* study = body.add_subcommand(
      "calibrate-study", "How well body calibrate recovers a known rig against the depth noise and the number of "
                         "board poses k: synthetic boards on the seed's rig, calibrated, compared with the truth "
                         "(a Markdown table on stdout)");
  auto s = std::make_shared<CalibrateStudyOptions>();
  study->add_option("--noise", s->noise, "Depth noise sigmas, comma-separated (mm, default 0,0.5,1,2,4)")
      ->delimiter(',')
      ->check(number_in(0.0, 100.0));
  study->add_option("--poses", s->poses, "Numbers of board poses k, comma-separated (default 3,4,6,10)")
      ->delimiter(',')
      ->check(CLI::Range(3, 100));
  study->add_option("--runs", s->runs, "Random pose sets per noise and k (default 5)")->check(CLI::Range(1, 1000));
  study->add_option("--board", s->board, "Board WIDTHxHEIGHTxTHICKNESS (mm, default 600x450x10)");
  study->add_option("--outliers", s->outliers, "Fraction of pixels replaced by random depths (default 0)")
      ->check(number_in(0.0, 0.5));
  study->add_option("--seed", s->seed, "Seed of the poses and the noise (default 1)");
  study->callback([s, &action] { action = [s] { return run_calibrate_study(*s); }; });
}

}  // namespace knitforge::cli
