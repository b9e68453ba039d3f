// Forward kinematics and linear blend skinning (body/skin_body.h) on the tiny
// tube model of test_bodies.h.
#include "knitforge/body/skin_body.h"

#include <gtest/gtest.h>

#include <numbers>

#include "body/test_bodies.h"
#include "knitforge/body/axis_angle.h"
#include "knitforge/util/errors.h"

namespace knitforge {
namespace {

constexpr double kPi = std::numbers::pi;

TEST(SkinBody, RestPoseIsTheShapedBodyMovedByTheTranslation) {
  for (bool pose_basis : {false, true}) {
    const BodyModel m = test::tube_body_model(pose_basis);
    validate_body_model(m);
    BodyParams p = zero_params(m);
    p.shape << 3.0, -2.0;
    p.translation_mm = {5.0, -7.0, 11.0};
    const ShapedBody s = shape_body(m, p.shape);
    const PosedBody posed = pose_body(m, p);
    for (int i = 0; i < m.num_vertices(); ++i)
      EXPECT_LT((posed.vertices[i] - (s.vertices[i] + p.translation_mm)).norm(), 1e-12) << i;
    for (int j = 0; j < m.num_joints(); ++j) {
      EXPECT_LT((posed.joints[j] - (s.joints[j] + p.translation_mm)).norm(), 1e-12);
      EXPECT_LT((posed.joint_rotations[j] - Mat3::Identity()).norm(), 1e-15);
    }
  }
}

TEST(SkinBody, ShapeIsTemplatePlusBasisAndJointsAreRegressed) {
  const BodyModel m = test::tube_body_model(false);
  Eigen::VectorXd beta(2);
  beta << 1.5, 0.5;
  const ShapedBody s = shape_body(m, beta);
  const Eigen::VectorXd d = m.shape_basis * beta;
  for (int i = 0; i < m.num_vertices(); ++i)
    EXPECT_LT((s.vertices[i] - m.template_vertices[i] - d.segment<3>(3 * i)).norm(), 1e-12);
  // The regressor of test_bodies.h averages rings 0, 4 and 8.
  for (int j = 0; j < 3; ++j) {
    Vec3 mean = Vec3::Zero();
    for (int k = 0; k < 8; ++k) mean += s.vertices[32 * j + k] / 8.0;
    EXPECT_LT((s.joints[j] - mean).norm(), 1e-12);
  }
  EXPECT_THROW(shape_body(m, Eigen::VectorXd::Zero(3)), InvalidInput);
}

TEST(SkinBody, RootRotationMovesTheWholeBodyRigidlyAboutTheRootJoint) {
  const BodyModel m = test::tube_body_model(false);
  BodyParams p = zero_params(m);
  p.joint_rotations[0] = {0.3, -0.5, 0.8};
  const Mat3 R = rotation_from_axis_angle(p.joint_rotations[0]);
  const ShapedBody s = shape_body(m, p.shape);
  const PosedBody posed = pose_body(m, p);
  for (int i = 0; i < m.num_vertices(); ++i) {
    const Vec3 expect = R * (s.vertices[i] - s.joints[0]) + s.joints[0];
    EXPECT_LT((posed.vertices[i] - expect).norm(), 1e-10) << i;
  }
}

TEST(SkinBody, BendingTheMiddleJointLeavesTheRootPartAndCarriesTheTip) {
  const BodyModel m = test::tube_body_model(false);
  BodyParams p = zero_params(m);
  p.joint_rotations[1] = {0, 0, kPi / 2};  // bend the chain to +y at x = 40
  const PosedBody posed = pose_body(m, p);
  const ShapedBody s = shape_body(m, p.shape);
  // The tip joint swings from (80, 0, 0) to (40, 40, 0).
  EXPECT_LT((posed.joints[2] - (s.joints[1] + Vec3(0, s.joints[2].x() - s.joints[1].x(), 0))).norm(), 1e-9);
  // Vertices weighted only to the root (x <= 0) do not move; vertices weighted
  // only to the tip chain below joint 1 (x >= 80) move rigidly with it.
  const Mat3 R = rotation_from_axis_angle(p.joint_rotations[1]);
  for (int i = 0; i < m.num_vertices(); ++i) {
    const double x = m.template_vertices[i].x();
    if (x <= 0.0) {
      EXPECT_LT((posed.vertices[i] - s.vertices[i]).norm(), 1e-12);
    }
    if (x >= 80.0) {
      EXPECT_LT((posed.vertices[i] - (R * (s.vertices[i] - s.joints[1]) + s.joints[1])).norm(), 1e-9);
    }
  }
  // Linear blend skinning: a vertex with weights w0 = w1 = 1/2 is the average
  // of the two rigid maps.
  const int i = 2 * 8;  // ring x = 20
  const Vec3 expect = 0.5 * s.vertices[i] + 0.5 * (R * (s.vertices[i] - s.joints[1]) + s.joints[1]);
  EXPECT_LT((posed.vertices[i] - expect).norm(), 1e-9);
}

TEST(SkinBody, PoseCorrectivesAreAddedBeforeSkinning) {
  const BodyModel m = test::tube_body_model(true);
  BodyParams p = zero_params(m);
  p.joint_rotations[2] = {0.2, 0.1, -0.4};
  const PosedBody posed = pose_body(m, p);
  const Mat3 D = rotation_from_axis_angle(p.joint_rotations[2]) - Mat3::Identity();
  Eigen::VectorXd feature = Eigen::VectorXd::Zero(18);
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) feature(9 + 3 * r + c) = D(r, c);
  const Eigen::VectorXd offset = m.pose_basis * feature;
  for (int i = 0; i < m.num_vertices(); ++i)
    EXPECT_LT((posed.rest_vertices[i] - m.template_vertices[i] - offset.segment<3>(3 * i)).norm(), 1e-12);
  // Root vertices (weight 1 on joint 0, unrotated) show the offset as is.
  EXPECT_LT((posed.vertices[0] - posed.rest_vertices[0]).norm(), 1e-12);
}

TEST(SkinBody, RejectsMismatchedParameters) {
  const BodyModel m = test::tube_body_model(false);
  BodyParams p = zero_params(m);
  p.joint_rotations.pop_back();
  EXPECT_THROW(pose_body(m, p), InvalidInput);
  p = zero_params(m);
  p.translation_mm.x() = std::numeric_limits<double>::infinity();
  EXPECT_THROW(pose_body(m, p), InvalidInput);
}

}  // namespace
}  // namespace knitforge
