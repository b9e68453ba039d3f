#include "knitforge/body/calibrate_depth_cameras.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>

#include "knitforge/body/render_depth_image.h"
#include "knitforge/body/study_depth_calibration.h"
#include "knitforge/body/synthetic_depth_scenes.h"
#include "knitforge/util/errors.h"

using namespace knitforge;

namespace {

Mat3 random_rotation(std::mt19937& rng) {
  std::normal_distribution<double> g(0.0, 1.0);
  return Eigen::Quaterniond(g(rng), g(rng), g(rng), g(rng)).normalized().toRotationMatrix();
}

// The board planes of `poses` as the rig's cameras see them, from the poses
// themselves (no images): the sides at ±c/2 along the board's normal.
std::vector<BoardPlanes> exact_planes(const DepthRig& rig, const std::vector<RigidTransform>& poses, double c) {
  std::vector<BoardPlanes> out;
  for (const RigidTransform& pose : poses) {
    const Vec3 n = pose.rotation * Vec3::UnitY();  // the +y side faces camera 2
    const Vec3 side1 = pose.translation - 0.5 * c * n + 37.0 * pose.rotation * Vec3::UnitX();
    const Vec3 side2 = pose.translation + 0.5 * c * n - 21.0 * pose.rotation * Vec3::UnitZ();
    out.push_back({rig.world_to_camera1.rotation * -n, rig.world_to_camera1.apply(side1),
                   rig.world_to_camera2.rotation * n, rig.world_to_camera2.apply(side2)});
  }
  return out;
}

struct CalibrationError {
  double rotation_deg = 0.0;
  double translation_mm = 0.0;
};

CalibrationError error_of(const RigidTransform& found, const DepthRig& rig) {
  const RigidTransform truth = camera2_to_camera1(rig);
  return {rotation_angle_between_deg(found.rotation, truth.rotation), (found.translation - truth.translation).norm()};
}

}  // namespace

TEST(CalibrateDepthCameras, Eq52GivesTheRotationExactlyFromNoiselessNormals) {
  std::mt19937 rng(5);
  for (int k : {3, 4, 7}) {
    const Mat3 R = random_rotation(rng);
    std::vector<Vec3> n1, n2;
    std::normal_distribution<double> g(0.0, 1.0);
    for (int i = 0; i < k; ++i) {
      const Vec3 n = Vec3(g(rng), g(rng), g(rng)).normalized();
      n2.push_back(n);
      n1.push_back(-(R * n));
    }
    const Mat3 found = rotation_from_board_normals(n1, n2);
    EXPECT_LT((found - R).cwiseAbs().maxCoeff(), 1e-12) << "k = " << k;
  }
}

TEST(CalibrateDepthCameras, Eq52ProjectsTheLeastSquaresMatrixToARotation) {
  std::mt19937 rng(8);
  const Mat3 R = random_rotation(rng);
  std::normal_distribution<double> g(0.0, 1.0);
  std::vector<Vec3> n1, n2;
  for (int i = 0; i < 6; ++i) {
    const Vec3 n = Vec3(g(rng), g(rng), g(rng)).normalized();
    n2.push_back(n);
    n1.push_back((-(R * n) + 0.02 * Vec3(g(rng), g(rng), g(rng))).normalized());
  }
  const Mat3 found = rotation_from_board_normals(n1, n2);
  EXPECT_LT((found * found.transpose() - Mat3::Identity()).cwiseAbs().maxCoeff(), 1e-12);
  EXPECT_NEAR(found.determinant(), 1.0, 1e-12);
  EXPECT_LT(rotation_angle_between_deg(found, R), 2.0);
  EXPECT_GT(rotation_angle_between_deg(found, R), 0.0);
}

TEST(CalibrateDepthCameras, Eq53GivesTheTranslationExactlyFromNoiselessPlanes) {
  const DepthRig rig = seed_depth_rig();
  for (double c : {0.0, 10.0, 25.0}) {
    const std::vector<BoardPlanes> planes = exact_planes(rig, random_board_poses(rig, 3, 4), c);
    const RigidTransform truth = camera2_to_camera1(rig);
    const Vec3 t = translation_from_board_planes(truth.rotation, planes, c);
    EXPECT_LT((t - truth.translation).norm(), 1e-9) << "thickness " << c;
    DepthCalibrationOptions o;
    o.thickness_mm = c;
    const DepthCalibration cal = calibrate_depth_cameras(planes, o);
    const CalibrationError e = error_of(cal.camera2_to_camera1, rig);
    EXPECT_LT(e.rotation_deg, 1e-9);
    EXPECT_LT(e.translation_mm, 1e-9);
    for (double r : cal.normal_residual_deg) EXPECT_LT(r, 1e-9);
    for (double r : cal.plane_residual_mm) EXPECT_LT(r, 1e-9);
    // The wrong thickness moves t along the normals: the residuals say so.
    o.thickness_mm = c + 8.0;
    const DepthCalibration wrong = calibrate_depth_cameras(planes, o);
    EXPECT_GT(error_of(wrong.camera2_to_camera1, rig).translation_mm, 1.0);
  }
}

TEST(CalibrateDepthCameras, RefusesTooFewParallelOrCoplanarPoses) {
  const DepthRig rig = seed_depth_rig();
  std::vector<BoardPlanes> planes = exact_planes(rig, random_board_poses(rig, 4, 2), 10.0);
  const auto message = [&](std::vector<BoardPlanes> p) {
    try {
      calibrate_depth_cameras(p, {10.0});
    } catch (const InvalidInput& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  EXPECT_NE(message({planes[0], planes[1]}).find("k >= 3"), std::string::npos);
  EXPECT_NE(message({planes[0], planes[1], planes[0]}).find("poses 1 and 3"), std::string::npos);
  // Three poses tilted about the one (world x) axis: normals in one plane.
  std::vector<RigidTransform> about_x;
  for (double deg : {-30.0, 0.0, 25.0})
    about_x.push_back({Eigen::AngleAxisd(deg * M_PI / 180.0, Vec3::UnitX()).toRotationMatrix(), Vec3(0, 0, 1000)});
  EXPECT_NE(message(exact_planes(rig, about_x, 10.0)).find("one axis only"), std::string::npos);
  planes[1].normal1 *= 2.0;
  EXPECT_NE(message(planes).find("unit vectors"), std::string::npos);
}

TEST(CalibrateDepthCameras, RenderedNoiselessBoardsGiveTheRigExactly) {
  const DepthRig rig = seed_depth_rig();
  const std::vector<RigidTransform> poses = random_board_poses(rig, 3, 1);
  RansacPlaneOptions ro;
  ro.inlier_distance_mm = 1e-6;  // only the large sides (no noise): the thin edges are off the plane
  DepthCalibrationOptions co;
  co.thickness_mm = 10.0;
  std::vector<BoardCapture> exact;  // not rounded to the cameras' 1 mm units
  for (const RigidTransform& pose : poses) {
    const TriMesh m = board_mesh({}, pose);
    exact.push_back({render_depth_image(m, rig.camera1, rig.world_to_camera1),
                     render_depth_image(m, rig.camera2, rig.world_to_camera2), "pose"});
  }
  const DepthImageCalibration r = calibrate_from_depth_images(exact, rig.camera1, rig.camera2, {}, ro, co);
  const CalibrationError e = error_of(r.calibration.camera2_to_camera1, rig);
  EXPECT_LT(e.rotation_deg, 1e-7);
  EXPECT_LT(e.translation_mm, 1e-6);
}

TEST(CalibrateDepthCameras, WithOneMillimetreNoiseTheErrorIsWithinTheBarForEveryK) {
  // The quality bar of issue 17: rotation < 0.5°, translation < 5 mm from
  // synthetic boards with 1 mm depth noise. 4 random pose sets per k, depths
  // rounded to 1 mm, 2 % of the pixels random outliers.
  const DepthRig rig = seed_depth_rig();
  DepthCalibrationOptions co;
  co.thickness_mm = 10.0;
  std::printf("k  rotation error (deg) mean / max   translation error (mm) mean / max\n");
  for (int k : {3, 6, 10}) {
    double rot_sum = 0, rot_max = 0, tr_sum = 0, tr_max = 0;
    const int runs = 4;
    for (int s = 0; s < runs; ++s) {
      const auto seed = static_cast<unsigned>(100 * k + s);
      const std::vector<RigidTransform> poses = random_board_poses(rig, k, seed);
      const DepthImageCalibration r = calibrate_from_depth_images(
          synthetic_board_captures(rig, poses, {}, {1.0, 0.02, seed}), rig.camera1, rig.camera2, {}, {}, co);
      const CalibrationError e = error_of(r.calibration.camera2_to_camera1, rig);
      rot_sum += e.rotation_deg;
      tr_sum += e.translation_mm;
      rot_max = std::max(rot_max, e.rotation_deg);
      tr_max = std::max(tr_max, e.translation_mm);
      EXPECT_LT(e.rotation_deg, 0.5) << "k " << k << " seed " << seed;
      EXPECT_LT(e.translation_mm, 5.0) << "k " << k << " seed " << seed;
    }
    std::printf("%-2d %.4f / %.4f                    %.3f / %.3f\n", k, rot_sum / runs, rot_max, tr_sum / runs, tr_max);
  }
}
