// The initial pose from 3D keypoints (body/pose_from_keypoints.h) and what
// it buys the fit (seed §5.A): a body turned away from the default pose.
#include "knitforge/body/pose_from_keypoints.h"

#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <random>

#include "knitforge/body/body_measurements.h"
#include "knitforge/body/body_pose.h"
#include "knitforge/body/fit_body.h"
#include "knitforge/body/generated_body.h"
#include "knitforge/body/keypoint_views.h"
#include "knitforge/body/skin_body.h"
#include "knitforge/util/errors.h"
#include "test_bodies.h"

namespace knitforge {
namespace {

// OpenPose's 13 body joints and the pelvis (its "MidHip"), by our names.
const std::vector<std::string> kObserved = {"pelvis",      "neck",        "head",          "left_shoulder",
                                            "right_shoulder", "left_elbow", "right_elbow",   "left_wrist",
                                            "right_wrist", "left_hip",    "right_hip",     "left_knee",
                                            "right_knee",  "left_ankle",  "right_ankle"};

std::map<std::string, Vec3> joints_of(const BodyModel& m, const PosedBody& posed, const std::vector<std::string>& names) {
  std::map<std::string, Vec3> k;
  for (const std::string& n : names) k[n] = posed.joints[static_cast<size_t>(m.joint_index(n))];
  return k;
}

TEST(PoseFromKeypoints, ExactJointsGiveThePoseBack) {
  const BodyModel& m = generated_body();
  BodyParams p = pose_preset(m, "relaxed");
  set_joint_rotation(m, p, "pelvis", {0.0, 0.0, 2.0});  // turned by 115 degrees
  p.translation_mm = {300.0, -150.0, 40.0};
  const PosedBody posed = pose_body(m, p);
  const KeypointPose kp = pose_from_keypoints(m, joints_of(m, posed, m.joint_names), pose_preset(m, "a-pose"));
  std::printf("all %d joints exact: rms %.3g mm, scale %.4f\n", kp.joints_used, kp.rms_mm, kp.scale);
  EXPECT_LT(kp.rms_mm, 0.5);
  EXPECT_NEAR(kp.scale, 1.0, 1e-6);
  const PosedBody again = pose_body(m, kp.params);
  for (int j = 0; j < m.num_joints(); ++j)
    EXPECT_LT((again.joints[static_cast<size_t>(j)] - posed.joints[static_cast<size_t>(j)]).norm(), 0.5) << m.joint_names[static_cast<size_t>(j)];
}

TEST(PoseFromKeypoints, KeypointsFromViewsLetTheFitFindATurnedBody) {
  // The target: taller, in the t-pose, turned to face +x (90 degrees from
  // the initial a-pose facing -y), moved; a scan with 2 mm noise (the
  // model's own mesh: the fit uses no vertex correspondence).
  const BodyModel& m = generated_body();
  BodyParams target = zero_params(m);
  target.shape(static_cast<int>(Measurement::Stature)) = 60.0;
  target.shape(static_cast<int>(Measurement::ChestGirth)) = 40.0;
  set_joint_rotation(m, target, "pelvis", {0.0, 0.0, std::numbers::pi / 2});
  set_joint_rotation(m, target, "left_shoulder", {0.0, 0.3, 0.0});
  target.translation_mm = {400.0, 250.0, 0.0};
  const PosedBody posed = pose_body(m, target);
  TriMesh scan = posed_mesh(m, posed);
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> noise(-2.0, 2.0);
  for (Vec3& v : scan.vertices) v += Vec3(noise(rng), noise(rng), noise(rng));

  // Four calibrated views around it, 1 px noise on the 2D keypoints.
  std::normal_distribution<double> px(0.0, 1.0);
  std::vector<KeypointView> views;
  for (int i = 0; i < 4; ++i) {
    const double a = 2.0 * std::numbers::pi * (i + 0.3) / 4;
    const Vec3 centre(400.0, 250.0, 950.0);
    const Vec3 eye = centre + Vec3(3000.0 * std::cos(a), 3000.0 * std::sin(a), 300.0);
    const Vec3 z = (centre - eye).normalized(), x = z.cross(Vec3::UnitZ()).normalized(), y = z.cross(x);
    KeypointView v;
    v.camera.R.row(0) = x.transpose();
    v.camera.R.row(1) = y.transpose();
    v.camera.R.row(2) = z.transpose();
    v.camera.t = -v.camera.R * eye;
    v.camera.K << 1000, 0, 500, 0, 1000, 700, 0, 0, 1;
    for (const auto& [name, p] : joints_of(m, posed, kObserved))
      v.keypoints[name] = project_to_pixel(v.camera, p) + Vec2(px(rng), px(rng));
    views.push_back(v);
  }
  const TriangulatedKeypoints tk = triangulate_keypoints(views);
  std::map<std::string, Vec3> points;
  double tri = 0.0;
  for (const auto& [name, k] : tk.points) {
    points[name] = k.point_mm;
    tri = std::max(tri, (k.point_mm - posed.joints[static_cast<size_t>(m.joint_index(name))]).norm());
  }
  const KeypointPose kp = pose_from_keypoints(m, points, pose_preset(m, "a-pose"));
  std::printf("keypoints: %zu triangulated (largest error %.1f mm); initial joints %.1f mm rms, scale %.3f\n",
              points.size(), tri, kp.rms_mm, kp.scale);
  EXPECT_LT(kp.rms_mm, 25.0);

  BodyFitOptions o;
  o.max_iterations = 30;
  const BodyParams plain = place_on_scan(m, pose_preset(m, "a-pose"), scan);
  auto t0 = std::chrono::steady_clock::now();
  const BodyFitResult from_box = fit_body(m, scan, plain, o);
  auto t1 = std::chrono::steady_clock::now();
  const BodyFitResult from_keys = fit_body(m, scan, kp.params, o);
  auto t2 = std::chrono::steady_clock::now();
  std::printf("default init: rms %.2f -> %.2f mm in %d iterations (%.1f s); keypoint init: rms %.2f -> %.2f mm in %d "
              "iterations (%.1f s)\n",
              from_box.initial_rms_mm, from_box.rms_mm, from_box.iterations,
              std::chrono::duration<double>(t1 - t0).count(), from_keys.initial_rms_mm, from_keys.rms_mm,
              from_keys.iterations, std::chrono::duration<double>(t2 - t1).count());
  EXPECT_LT(from_keys.rms_mm, 3.0);
  EXPECT_GT(from_box.rms_mm, 3.0 * from_keys.rms_mm);  // the default start lands in a wrong minimum
  const BodyMeasurements want = measure_body(m, shape_body(m, target.shape));
  const BodyMeasurements got = measure_body(m, shape_body(m, from_keys.params.shape));
  for (Measurement q : {Measurement::Stature, Measurement::ChestGirth, Measurement::WaistGirth, Measurement::HipGirth})
    EXPECT_NEAR(got[static_cast<size_t>(q)], want[static_cast<size_t>(q)], 10.0) << measurement_info(q).key;
}

TEST(PoseFromKeypoints, RejectsUnknownJointsAndTooFewKeypoints) {
  // The small test body (joints root, middle, tip): no model build needed.
  const BodyModel m = test::tube_body_model(false);
  const BodyParams a = zero_params(m);
  EXPECT_THROW(pose_from_keypoints(m, {{"nose", {0, 0, 0}}, {"root", {0, 0, 0}}, {"tip", {0, 0, 1}}}, a),
               InvalidInput);
  EXPECT_THROW(pose_from_keypoints(m, {{"root", {0, 0, 0}}, {"tip", {0, 0, 500}}}, a), InvalidInput);
  // Three keypoints of a bent tube give its joints back (no stature parameter: no scale).
  BodyParams p = zero_params(m);
  p.joint_rotations[1] = {0.0, 0.0, 0.6};
  p.translation_mm = {5.0, -3.0, 2.0};
  const PosedBody posed = pose_body(m, p);
  const KeypointPose kp =
      pose_from_keypoints(m, {{"root", posed.joints[0]}, {"middle", posed.joints[1]}, {"tip", posed.joints[2]}}, a);
  EXPECT_LT(kp.rms_mm, 1e-9);
  EXPECT_EQ(kp.scale, 1.0);
}

}  // namespace
}  // namespace knitforge
