// Jacobians of the posed body (body/body_jacobian.h) against central finite
// differences of pose_body(apply_increment(...)).
#include "knitforge/body/body_jacobian.h"

#include <gtest/gtest.h>

#include <random>

#include "body/test_bodies.h"
#include "knitforge/body/axis_angle.h"
#include "knitforge/body/body_pose.h"
#include "knitforge/body/generated_body.h"
#include "knitforge/util/errors.h"

namespace knitforge {
namespace {

// Central differences of the posed vertices (and joints) of the columns
// `cols` of the increment; step h for every column.
struct Numeric {
  Eigen::MatrixXd vertices, joints;
};
Numeric numeric_jacobian(const BodyModel& m, const BodyParams& p, const std::vector<int>& ids,
                         const std::vector<int>& cols, double h) {
  const BodyParamLayout L(m);
  Numeric out{Eigen::MatrixXd::Zero(3 * static_cast<int>(ids.size()), L.size()),
              Eigen::MatrixXd::Zero(3 * m.num_joints(), L.size())};
  for (int c : cols) {
    Eigen::VectorXd d = Eigen::VectorXd::Zero(L.size());
    d(c) = h;
    const PosedBody a = pose_body(m, apply_increment(m, p, d));
    const PosedBody b = pose_body(m, apply_increment(m, p, -d));
    for (size_t r = 0; r < ids.size(); ++r)
      out.vertices.block<3, 1>(3 * static_cast<int>(r), c) = (a.vertices[ids[r]] - b.vertices[ids[r]]) / (2 * h);
    for (int j = 0; j < m.num_joints(); ++j) out.joints.block<3, 1>(3 * j, c) = (a.joints[j] - b.joints[j]) / (2 * h);
  }
  return out;
}

BodyParams random_params(const BodyModel& m, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  BodyParams p = zero_params(m);
  for (int k = 0; k < m.num_shapes(); ++k) p.shape(k) = 2.0 * u(rng);
  for (auto& r : p.joint_rotations) r = 0.8 * Vec3(u(rng), u(rng), u(rng));
  p.translation_mm = 10.0 * Vec3(u(rng), u(rng), u(rng));
  return p;
}

TEST(BodyJacobian, MatchesFiniteDifferencesOnTheTubeModel) {
  for (bool pose_basis : {false, true}) {
    const BodyModel m = test::tube_body_model(pose_basis);
    const BodyParams p = random_params(m, pose_basis ? 11u : 5u);
    const PosedBody posed = pose_body(m, p);
    std::vector<int> ids(static_cast<size_t>(m.num_vertices()));
    for (int i = 0; i < m.num_vertices(); ++i) ids[static_cast<size_t>(i)] = i;
    const BodyParamLayout L(m);
    std::vector<int> cols(static_cast<size_t>(L.size()));
    for (int c = 0; c < L.size(); ++c) cols[static_cast<size_t>(c)] = c;
    const Numeric num = numeric_jacobian(m, p, ids, cols, 1e-5);
    const Eigen::MatrixXd Jv = posed_vertex_jacobian(m, posed);
    const Eigen::MatrixXd Jj = posed_joint_jacobian(m, posed);
    ASSERT_EQ(Jv.rows(), 3 * m.num_vertices());
    ASSERT_EQ(Jv.cols(), L.size());
    // Rotation columns are in mm / rad (~100), the others ~1: relative test.
    EXPECT_LT((Jv - num.vertices).cwiseAbs().maxCoeff(), 1e-6 * (1.0 + Jv.cwiseAbs().maxCoeff()))
        << "pose basis " << pose_basis;
    EXPECT_LT((Jj - num.joints).cwiseAbs().maxCoeff(), 1e-6 * (1.0 + Jj.cwiseAbs().maxCoeff()));
    // With correctives, the tip joint's increment moves even a root vertex.
    if (pose_basis) {
      EXPECT_GT(Jv.middleCols<3>(L.rotation(2)).topRows(3).norm(), 1e-3);
    }
  }
}

TEST(BodyJacobian, SubsetRowsEqualTheFullJacobiansRows) {
  const BodyModel m = test::tube_body_model(true);
  const BodyParams p = random_params(m, 2u);
  const PosedBody posed = pose_body(m, p);
  const Eigen::MatrixXd full = posed_vertex_jacobian(m, posed);
  const std::vector<int> ids = {7, 0, 45};
  const Eigen::MatrixXd sub = posed_vertex_jacobian(m, posed, ids);
  ASSERT_EQ(sub.rows(), 9);
  for (int r = 0; r < 3; ++r) EXPECT_EQ(sub.middleRows<3>(3 * r), full.middleRows<3>(3 * ids[r]));
  const std::vector<int> bad = {m.num_vertices()};
  EXPECT_THROW(posed_vertex_jacobian(m, posed, bad), InvalidInput);
}

TEST(BodyJacobian, ApplyIncrementComposesOnTheRight) {
  const BodyModel m = test::tube_body_model(false);
  const BodyParams p = random_params(m, 9u);
  const BodyParamLayout L(m);
  Eigen::VectorXd d = Eigen::VectorXd::Zero(L.size());
  d.segment<3>(L.rotation(1)) = Vec3(0.1, -0.2, 0.05);
  d(L.shape(1)) = 0.5;
  d(0) = 3.0;
  const BodyParams q = apply_increment(m, p, d);
  const Mat3 expect = rotation_from_axis_angle(p.joint_rotations[1]) * rotation_from_axis_angle({0.1, -0.2, 0.05});
  EXPECT_LT((rotation_from_axis_angle(q.joint_rotations[1]) - expect).norm(), 1e-12);
  EXPECT_EQ(q.joint_rotations[0], p.joint_rotations[0]);
  EXPECT_DOUBLE_EQ(q.shape(1), p.shape(1) + 0.5);
  EXPECT_DOUBLE_EQ(q.translation_mm.x(), p.translation_mm.x() + 3.0);
  EXPECT_THROW(apply_increment(m, p, Eigen::VectorXd::Zero(L.size() + 1)), InvalidInput);
}

TEST(BodyJacobian, MatchesFiniteDifferencesOnTheGeneratedBodyInAPose) {
  const BodyModel& m = generated_body();
  BodyParams p = pose_preset(m, "relaxed");
  p.shape(0) = 40.0;   // stature
  p.shape(4) = -30.0;  // chest
  p.translation_mm = {12, -5, 3};
  const PosedBody posed = pose_body(m, p);
  // Landmarks on the torso, arm and leg, plus spread-out vertices.
  std::vector<int> ids;
  for (const auto& [name, v] : m.landmarks) ids.push_back(v);
  for (int i = 0; i < m.num_vertices(); i += m.num_vertices() / 40) ids.push_back(i);
  const BodyParamLayout L(m);
  std::vector<int> cols;
  for (int c = 0; c < L.size(); ++c) cols.push_back(c);
  const Numeric num = numeric_jacobian(m, p, ids, cols, 1e-4);
  const Eigen::MatrixXd Jv = posed_vertex_jacobian(m, posed, ids);
  const Eigen::MatrixXd Jj = posed_joint_jacobian(m, posed);
  EXPECT_LT((Jv - num.vertices).cwiseAbs().maxCoeff(), 1e-5 * Jv.cwiseAbs().maxCoeff());
  EXPECT_LT((Jj - num.joints).cwiseAbs().maxCoeff(), 1e-5 * Jj.cwiseAbs().maxCoeff());
}

}  // namespace
}  // namespace knitforge
