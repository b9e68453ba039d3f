#include "knitforge/body/study_depth_calibration.h"

#include <algorithm>
#include <cmath>

#include <fmt/core.h>

#include "knitforge/body/render_depth_image.h"
#include "knitforge/util/errors.h"

namespace knitforge {

namespace {

// What a 16-bit PNG of the camera's depth units keeps of a depth.
void round_to_depth_units(DepthImage& image, const DepthCamera& camera) {
  for (double& z : image.depth_mm)
    if (z > 0.0) z = std::max(1.0, std::round(z / camera.depth_unit_mm)) * camera.depth_unit_mm;
}

}  // namespace

std::vector<BoardCapture> synthetic_board_captures(const DepthRig& rig, std::span<const RigidTransform> poses,
                                                   const BoardSize& board, const DepthNoise& noise) {
  std::vector<BoardCapture> captures;
  for (size_t i = 0; i < poses.size(); ++i) {
    const TriMesh mesh = board_mesh(board, poses[i]);
    BoardCapture c{render_depth_image(mesh, rig.camera1, rig.world_to_camera1),
                   render_depth_image(mesh, rig.camera2, rig.world_to_camera2), fmt::format("board pose {}", i + 1)};
    const auto seed = noise.seed + 2 * static_cast<unsigned>(i);
    add_depth_noise(c.image1, {noise.sigma_mm, noise.outlier_fraction, seed});
    add_depth_noise(c.image2, {noise.sigma_mm, noise.outlier_fraction, seed + 1});
    round_to_depth_units(c.image1, rig.camera1);
    round_to_depth_units(c.image2, rig.camera2);
    captures.push_back(std::move(c));
  }
  return captures;
}

std::vector<DepthCalibrationStudyRow> study_depth_calibration(const DepthCalibrationStudyOptions& o) {
  if (o.noise_mm.empty() || o.poses.empty())
    throw InvalidInput("calibration study: give at least one noise and one number of poses");
  for (double s : o.noise_mm)
    if (!(s >= 0.0) || !std::isfinite(s))
      throw InvalidInput(fmt::format("calibration study: noise {} mm must be a finite number >= 0", s));
  for (int k : o.poses)
    if (k < 3 || k > 100)
      throw InvalidInput(fmt::format("calibration study: {} poses; eq. 5.2/5.3 need 3 to 100", k));
  if (o.runs < 1 || o.runs > 1000)
    throw InvalidInput(fmt::format("calibration study: {} runs; give 1 to 1000", o.runs));
  const DepthRig rig = seed_depth_rig(o.distance_mm);
  const RigidTransform truth = camera2_to_camera1(rig);
  DepthCalibrationOptions co;
  co.thickness_mm = o.board.thickness_mm;
  std::vector<DepthCalibrationStudyRow> rows;
  for (double sigma : o.noise_mm) {
    for (int k : o.poses) {
      DepthCalibrationStudyRow row;
      row.noise_mm = sigma;
      row.poses = k;
      for (int r = 0; r < o.runs; ++r) {
        const unsigned seed = o.seed + 1000u * static_cast<unsigned>(k) + static_cast<unsigned>(r);
        const std::vector<RigidTransform> poses = random_board_poses(rig, k, seed);
        const std::vector<BoardCapture> captures =
            synthetic_board_captures(rig, poses, o.board, {sigma, o.outlier_fraction, seed});
        DepthImageCalibration found;
        try {
          found = calibrate_from_depth_images(captures, rig.camera1, rig.camera2, {}, o.ransac, co);
        } catch (const InvalidInput&) {
          ++row.failed;  // counted: at high noise RANSAC may find no plane
          continue;
        }
        const RigidTransform& T = found.calibration.camera2_to_camera1;
        const double rot = rotation_angle_between_deg(T.rotation, truth.rotation);
        const double tr = (T.translation - truth.translation).norm();
        ++row.runs;
        row.rotation_mean_deg += rot;
        row.translation_mean_mm += tr;
        row.rotation_max_deg = std::max(row.rotation_max_deg, rot);
        row.translation_max_mm = std::max(row.translation_max_mm, tr);
      }
      if (row.runs > 0) {
        row.rotation_mean_deg /= row.runs;
        row.translation_mean_mm /= row.runs;
      }
      rows.push_back(row);
    }
  }
  return rows;
}

}  // namespace knitforge
