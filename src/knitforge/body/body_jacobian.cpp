#include "knitforge/body/body_jacobian.h"

#include <fmt/core.h>

#include "knitforge/body/axis_angle.h"
#include "knitforge/util/errors.h"

namespace knitforge {

namespace {

void check_posed(const BodyModel& model, const PosedBody& posed) {
  if (static_cast<int>(posed.vertices.size()) != model.num_vertices() ||
      static_cast<int>(posed.joints.size()) != model.num_joints() ||
      static_cast<int>(posed.rest_joints.size()) != model.num_joints())
    throw InvalidInput("body Jacobian: the posed body does not belong to this model");
}

// d(rest joint j)/d(shape k): J x (3K), column block k.
Eigen::MatrixXd rest_joint_shape_derivative(const BodyModel& model) {
  const int J = model.num_joints(), K = model.num_shapes();
  Eigen::MatrixXd d = Eigen::MatrixXd::Zero(3 * J, K);
  for (int j = 0; j < J; ++j) {
    for (RowSparse::InnerIterator it(model.joint_regressor, j); it; ++it) {
      d.middleRows<3>(3 * j) += it.value() * model.shape_basis.middleRows<3>(3 * static_cast<int>(it.col()));
    }
  }
  return d;
}

// d(posed joint origin o_j)/d(shape k): 3J x K (recursion down the tree).
Eigen::MatrixXd posed_joint_shape_derivative(const BodyModel& model, const PosedBody& posed,
                                             const Eigen::MatrixXd& dJ) {
  const int J = model.num_joints();
  Eigen::MatrixXd d(3 * J, model.num_shapes());
  for (int j = 0; j < J; ++j) {
    const int p = model.parents[static_cast<size_t>(j)];
    if (p < 0) {
      d.middleRows<3>(3 * j) = dJ.middleRows<3>(3 * j);
    } else {
      d.middleRows<3>(3 * j) = d.middleRows<3>(3 * p) + posed.joint_rotations[static_cast<size_t>(p)] *
                                                            (dJ.middleRows<3>(3 * j) - dJ.middleRows<3>(3 * p));
    }
  }
  return d;
}

}  // namespace

BodyParams apply_increment(const BodyModel& model, const BodyParams& params, const Eigen::VectorXd& delta) {
  const BodyParamLayout L(model);
  if (delta.size() != L.size())
    throw InvalidInput(fmt::format("apply_increment: {} values, expected {}", delta.size(), L.size()));
  if (!delta.allFinite()) throw InvalidInput("apply_increment: the increment is not finite");
  BodyParams out = params;
  out.translation_mm += delta.segment<3>(L.translation());
  for (int j = 0; j < L.num_joints; ++j) {
    const Vec3 d = delta.segment<3>(L.rotation(j));
    if (d.squaredNorm() == 0.0) continue;
    const auto sj = static_cast<size_t>(j);
    out.joint_rotations[sj] =
        axis_angle_from_rotation(rotation_from_axis_angle(params.joint_rotations[sj]) * rotation_from_axis_angle(d));
  }
  if (L.num_shapes > 0) out.shape += delta.segment(L.shape(0), L.num_shapes);
  return out;
}

Eigen::MatrixXd posed_vertex_jacobian(const BodyModel& model, const PosedBody& posed,
                                      std::span<const int> vertex_ids) {
  check_posed(model, posed);
  const BodyParamLayout L(model);
  const int V = model.num_vertices(), J = model.num_joints(), K = model.num_shapes();
  std::vector<int> all;
  if (vertex_ids.empty()) {
    all.resize(static_cast<size_t>(V));
    for (int i = 0; i < V; ++i) all[static_cast<size_t>(i)] = i;
    vertex_ids = all;
  }
  const Eigen::MatrixXd dJ = rest_joint_shape_derivative(model);
  const Eigen::MatrixXd dO = posed_joint_shape_derivative(model, posed, dJ);
  // Pose-corrective derivative helpers: vec_r(R_j [e_m]x) per joint and axis.
  std::vector<Eigen::Matrix<double, 9, 3>> dfeature;
  if (model.has_pose_basis()) {
    dfeature.resize(static_cast<size_t>(J));
    for (int j = 1; j < J; ++j) {
      for (int m = 0; m < 3; ++m) {
        const Mat3 d = posed.local_rotations[static_cast<size_t>(j)] * skew(Vec3::Unit(m));
        for (int r = 0; r < 3; ++r)
          for (int c = 0; c < 3; ++c) dfeature[static_cast<size_t>(j)](3 * r + c, m) = d(r, c);
      }
    }
  }
  Eigen::MatrixXd jac = Eigen::MatrixXd::Zero(3 * static_cast<Eigen::Index>(vertex_ids.size()), L.size());
  for (size_t r = 0; r < vertex_ids.size(); ++r) {
    const int i = vertex_ids[r];
    if (i < 0 || i >= V)
      throw InvalidInput(fmt::format("body Jacobian: vertex {} is outside [0, {})", i, V));
    auto block = jac.middleRows<3>(3 * static_cast<Eigen::Index>(r));
    const Vec3& u = posed.rest_vertices[static_cast<size_t>(i)];
    Mat3 blend = Mat3::Zero();  // sum_l w_l Q_l
    // The rotation and shape blocks written out in scalars, each entry by the
    // operations and in the order of the Eigen expressions they replaced
    // (noted beside them; the same bits, checked entry by entry against the
    // expressions in the Release and the sanitizer builds): the fits build
    // this Jacobian every iteration, and unoptimised fixed-size Eigen
    // products were a quarter of a body fit's time under the sanitizers.
    const Eigen::Index row = 3 * static_cast<Eigen::Index>(r);
    for (RowSparse::InnerIterator it(model.skinning_weights, i); it; ++it) {
      const int l = static_cast<int>(it.col());
      const double w = it.value();
      const auto sl = static_cast<size_t>(l);
      const Mat3& Q = posed.joint_rotations[sl];
      blend += w * Q;
      const Vec3 x = Q * (u - posed.rest_joints[sl]) + posed.joints[sl];
      // += w I (its zeros add nothing to the translation block's zeros)
      for (int a = 0; a < 3; ++a) jac(row + a, L.translation() + a) += w;
      // -= (w [x - joint k]x) R_k for k and its ancestors
      for (int k = l; k >= 0; k = model.parents[static_cast<size_t>(k)]) {
        const auto sk = static_cast<size_t>(k);
        const Vec3& o = posed.joints[sk];
        const double e0 = x[0] - o.x(), e1 = x[1] - o.y(), e2 = x[2] - o.z();
        const double S[3][3] = {{w * 0.0, w * -e2, w * e1}, {w * e2, w * 0.0, w * -e0}, {w * -e1, w * e0, w * 0.0}};
        const Mat3& R = posed.joint_rotations[sk];
        const Eigen::Index c0 = L.rotation(k);
        for (int b = 0; b < 3; ++b)
          for (int a = 0; a < 3; ++a)
            jac(row + a, c0 + b) -= (S[a][0] * R(0, b) + S[a][1] * R(1, b)) + S[a][2] * R(2, b);
      }
      // += w (Q (shape basis rows - dJ rows) + dO rows)
      const Eigen::Index s0 = L.shape(0);
      for (int c = 0; c < K; ++c) {
        double D[3];
        for (int a = 0; a < 3; ++a) D[a] = model.shape_basis(3 * i + a, c) - dJ(3 * l + a, c);
        const double t[3][3] = {{Q(0, 0) * D[0], Q(0, 1) * D[1], Q(0, 2) * D[2]},
                                {Q(1, 0) * D[0], Q(1, 1) * D[1], Q(1, 2) * D[2]},
                                {Q(2, 0) * D[0], Q(2, 1) * D[1], Q(2, 2) * D[2]}};
        // Eigen sums rows 0 and 1 (a packet) as (t0 + t1) + t2, the last row as t0 + (t1 + t2).
        jac(row + 0, s0 + c) += w * (((t[0][0] + t[0][1]) + t[0][2]) + dO(3 * l + 0, c));
        jac(row + 1, s0 + c) += w * (((t[1][0] + t[1][1]) + t[1][2]) + dO(3 * l + 1, c));
        jac(row + 2, s0 + c) += w * ((t[2][0] + (t[2][1] + t[2][2])) + dO(3 * l + 2, c));
      }
    }
    if (model.has_pose_basis()) {
      for (int j = 1; j < J; ++j) {
        const Eigen::Matrix<double, 3, 9> P = model.pose_basis.block<3, 9>(3 * i, 9 * (j - 1));
        block.middleCols<3>(L.rotation(j)) += blend * P * dfeature[static_cast<size_t>(j)];
      }
    }
  }
  return jac;
}

Eigen::MatrixXd posed_joint_jacobian(const BodyModel& model, const PosedBody& posed) {
  check_posed(model, posed);
  const BodyParamLayout L(model);
  const int J = model.num_joints(), K = model.num_shapes();
  const Eigen::MatrixXd dJ = rest_joint_shape_derivative(model);
  const Eigen::MatrixXd dO = posed_joint_shape_derivative(model, posed, dJ);
  Eigen::MatrixXd jac = Eigen::MatrixXd::Zero(3 * J, L.size());
  for (int j = 0; j < J; ++j) {
    auto block = jac.middleRows<3>(3 * j);
    block.middleCols<3>(L.translation()) = Mat3::Identity();
    const Vec3& o = posed.joints[static_cast<size_t>(j)];
    for (int k = model.parents[static_cast<size_t>(j)]; k >= 0; k = model.parents[static_cast<size_t>(k)]) {
      const auto sk = static_cast<size_t>(k);
      block.middleCols<3>(L.rotation(k)) = -skew(o - posed.joints[sk]) * posed.joint_rotations[sk];
    }
    if (K > 0) block.middleCols(L.shape(0), K) = dO.middleRows<3>(3 * j);
  }
  return jac;
}

}  // namespace knitforge
