#include "knitforge/body/ddr/reconstruct_body.h"

#include <cmath>
#include <numbers>

#include <fmt/core.h>

#include "knitforge/body/ddr_geometry.h"
#include "knitforge/body/ddr_sample.h"
#include "knitforge/body/poisson_reconstruct.h"
#include "knitforge/util/errors.h"

namespace knitforge {

ReconstructedBody reconstruct_body(DdrModel& model, const ReconstructInput& input, const ReconstructOptions& options) {
  const int s = model.info.size;
  const size_t plane = static_cast<size_t>(s) * static_cast<size_t>(s);
  if (input.rgb.size() != 3 * plane)
    throw InvalidInput(fmt::format("the picture has {} values; the model takes {} x {} RGB", input.rgb.size(), s, s));
  std::vector<float> net_input = input.rgb;
  const std::vector<float> maps = keypoint_heatmaps(input.keypoints_px, input.present, s, ddr_heatmap_sigma({s, 0, 0}));
  net_input.insert(net_input.end(), maps.begin(), maps.end());
  const std::vector<float> ddr = predict_ddr(model, net_input, options.seed);
  ViewPredictor view;
  if (options.refine)
    view = [&](const std::vector<float>& view_input, double) { return predict_view(model, view_input, options.seed); };
  return body_from_ddr(ddr, input, s, view);
}

ReconstructedBody body_from_ddr(const std::vector<float>& ddr, const ReconstructInput& input, int s,
                                const ViewPredictor& view) {
  const size_t plane = static_cast<size_t>(s) * static_cast<size_t>(s);
  if (!input.present[8] || !input.present[11])
    throw InvalidInput("the right and left hip keypoints are needed to place the body (its pelvis is their midpoint)");
  const double sigma = ddr_heatmap_sigma({s, 0, 0});
  const DepthCamera camera = ddr_camera(s);
  ReconstructedBody out;
  out.ddr = ddr;

  const Vec2 pelvis_px = 0.5 * (input.keypoints_px[8] + input.keypoints_px[11]);
  const Vec3 pelvis = back_project(camera, pelvis_px.x(), pelvis_px.y(), kDdrCameraDistanceMm);
  OrientedPoints cloud = ddr_oriented_points(out.ddr, camera, pelvis.z());
  out.ddr_points = static_cast<int>(cloud.points.size());
  if (out.ddr_points < 50)
    throw InvalidInput(fmt::format("only {} points were predicted: the picture does not show a whole body as the "
                                   "model expects (upright, centred, about 7/8 of the image height)",
                                   out.ddr_points));

  if (view) {
    // The keypoints in 3D: at the middle of the body's depth at their pixel.
    const auto [lo, hi] = ddr_depth_images(out.ddr, s, pelvis.z());
    std::array<Vec3, kNumBodyKeypoints> keypoints_mm;
    for (size_t k = 0; k < keypoints_mm.size(); ++k) {
      const Vec2 q = input.keypoints_px[k];
      const int u = static_cast<int>(std::lround(q.x())), v = static_cast<int>(std::lround(q.y()));
      double z = pelvis.z();
      if (u >= 0 && v >= 0 && u < s && v < s && lo.at(u, v) > 0) z = 0.5 * (lo.at(u, v) + hi.at(u, v));
      keypoints_mm[k] = back_project(camera, q.x(), q.y(), z);
    }
    DepthNormalOptions normals;
    normals.radius_px = 1;
    normals.max_gap_mm = 2.5 * pelvis.z() / camera.K(0, 0);
    normals.min_neighbours = 3;
    for (double degrees : {45.0, -45.0, 135.0, -135.0}) {
      const double angle = degrees * std::numbers::pi / 180.0;
      const std::vector<float> refined =
          view(ddr_view_input(cloud.points, keypoints_mm, input.present, pelvis, camera, angle, sigma), angle);
      DepthImage depth{s, s, std::vector<double>(plane, 0.0)};
      for (size_t i = 0; i < plane; ++i)
        if (std::abs(refined[i]) > kDdrForegroundThreshold) depth.depth_mm[i] = pelvis.z() + kDdrDepthUnitMm * refined[i];
      const OrientedPoints seen = depth_to_oriented_points(depth, camera, {}, normals);
      // Back from the turned view: the inverse turn.
      const RigidTransform back = turn_about_vertical(pelvis, -angle);
      for (size_t i = 0; i < seen.points.size(); ++i) {
        cloud.points.push_back(back.apply(seen.points[i]));
        cloud.normals.push_back(back.rotation * seen.normals[i]);
      }
    }
    out.view_points = static_cast<int>(cloud.points.size()) - out.ddr_points;
  }

  out.camera_to_body = camera_to_body_frame(pelvis);
  // One point per voxel of about a pixel's size at the pelvis (evens out the overlapping views).
  FusePointOptions fuse;
  fuse.voxel_mm = pelvis.z() / camera.K(0, 0);
  out.points = fuse_point_clouds(cloud, {}, {}, fuse);
  for (size_t i = 0; i < out.points.points.size(); ++i) {
    out.points.points[i] = out.camera_to_body.apply(out.points.points[i]);
    out.points.normals[i] = out.camera_to_body.rotation * out.points.normals[i];
  }
  out.mesh = poisson_reconstruct(out.points).mesh;
  return out;
}

}  // namespace knitforge
