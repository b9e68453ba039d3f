#include "knitforge/body/ddr/evaluate_ddr.h"

#include <chrono>
#include <cmath>

#include <fmt/core.h>

#include "knitforge/body/ddr_geometry.h"
#include "knitforge/body/ddr_sample.h"
#include "knitforge/body/ddr/reconstruct_body.h"
#include "knitforge/body/ddr/train_ddr.h"
#include "knitforge/evaluate/surface_distance.h"
#include "knitforge/util/errors.h"

namespace knitforge {

namespace {

double mean(const std::vector<double>& v) {
  double s = 0;
  for (double x : v) s += x;
  return v.empty() ? 0.0 : s / static_cast<double>(v.size());
}

double rms(const std::vector<double>& v) {
  double s = 0;
  for (double x : v) s += x * x;
  return v.empty() ? 0.0 : std::sqrt(s / static_cast<double>(v.size()));
}

}  // namespace

DdrEvaluation evaluate_ddr(DdrModel& model, const BodyModel& body, int samples, int meshes,
                           const std::function<void(const std::string&)>& log) {
  if (samples < 1 || meshes < 0)
    throw InvalidInput(fmt::format("ddr-evaluate: {} samples and {} meshes (at least 1 and 0)", samples, meshes));
  const auto t0 = std::chrono::steady_clock::now();
  const BodyKeypointRig rig = body_keypoint_rig(body);
  const DdrSceneOptions scene{model.info.size, model.info.max_azimuth_deg, 0.0};
  DdrEvaluation e;
  std::vector<double> placed, aligned, completeness;
  for (int i = 0; i < samples; ++i) {
    const DdrSample s = synthetic_ddr_sample(body, rig, ddr_test_seed(i), scene);
    std::vector<float> input = s.rgb;
    input.insert(input.end(), s.heatmaps.begin(), s.heatmaps.end());
    const DdrErrors err = ddr_errors(predict_ddr(model, input, ddr_test_seed(i)), s.ddr, s.foreground, s.size);
    e.ei += err.ei;
    e.ep_cm += err.ep_cm;
    e.eg += err.eg;
    e.flat_ep_cm += ddr_errors(std::vector<float>(s.ddr.size(), 0.0f), s.ddr, s.foreground, s.size).ep_cm;
    ++e.samples;
    if (i >= meshes) continue;
    ReconstructInput r{s.rgb, s.keypoints_px, {}};
    r.present.fill(true);
    const ReconstructedBody rec = reconstruct_body(model, r, {true, ddr_test_seed(i)});
    // The true body in the output frame.
    TriMesh truth = s.body;
    for (Vec3& x : truth.vertices) x = rec.camera_to_body.apply(s.world_to_camera.apply(x));
    std::vector<double> d = distances_to_surface(truth, rec.mesh.vertices);
    placed.insert(placed.end(), d.begin(), d.end());
    // The best translation: a few closest-point iterations.
    TriMesh moved = rec.mesh;
    const SurfaceBvh bvh(truth);
    for (int it = 0; it < 10; ++it) {
      Vec3 shift = Vec3::Zero();
      for (const Vec3& x : moved.vertices) shift += bvh.closest_point(x).point - x;
      shift /= static_cast<double>(moved.vertices.size());
      for (Vec3& x : moved.vertices) x += shift;
    }
    d = distances_to_surface(truth, moved.vertices);
    aligned.insert(aligned.end(), d.begin(), d.end());
    d = distances_to_surface(moved, truth.vertices);
    completeness.insert(completeness.end(), d.begin(), d.end());
    ++e.meshes;
    if (log) log(fmt::format("test body {}: {} points, {} mesh vertices, {:.2f} cm mean distance after translation",
                             i + 1, rec.points.points.size(), rec.mesh.vertices.size(), mean(d) / 10.0));
  }
  e.ei /= e.samples;
  e.ep_cm /= e.samples;
  e.eg /= e.samples;
  e.flat_ep_cm /= e.samples;
  e.placed_mesh_to_body_cm = mean(placed) / 10.0;
  e.mesh_to_body_cm = mean(aligned) / 10.0;
  e.mesh_to_body_rms_cm = rms(aligned) / 10.0;
  e.body_to_mesh_cm = mean(completeness) / 10.0;
  e.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return e;
}

nlohmann::json ddr_evaluation_json(const DdrEvaluation& e) {
  return {{"test_samples", e.samples},
          {"EI", e.ei},
          {"EP_cm", e.ep_cm},
          {"EG", e.eg},
          {"EP_flat_cm", e.flat_ep_cm},
          {"meshes", e.meshes},
          {"mesh_to_body_placed_mean_cm", e.placed_mesh_to_body_cm},
          {"mesh_to_body_mean_cm", e.mesh_to_body_cm},
          {"mesh_to_body_rms_cm", e.mesh_to_body_rms_cm},
          {"body_to_mesh_mean_cm", e.body_to_mesh_cm},
          {"seconds", e.seconds}};
}

}  // namespace knitforge
