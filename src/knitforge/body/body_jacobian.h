#pragma once
/// \file body_jacobian.h
/// Derivatives of a posed body with respect to its parameters, for the
/// Gauss-Newton refinement of the fitter (fit_body.h).
///
/// The pose is varied by local increments, not by the axis-angle vectors
/// themselves: R_j <- R_j exp([d_j]x) (better conditioned; no singularity
/// at angle pi). For a point x moved by joint l, the increment of an
/// ancestor k (k = l included) moves it by (Q_k d_k) x (x - o_k); the shape
/// moves it by Q_l (dS - dJ_l) + do_l (rest vertex, rest joint and posed
/// joint derivatives); the pose-corrective blend shapes (when present) add
/// their derivative through the skinning. Exact (tested against finite
/// differences).

#include <span>
#include <vector>

#include <Eigen/Core>

#include "knitforge/body/body_model.h"
#include "knitforge/body/skin_body.h"

namespace knitforge {

/// Column layout of the parameter increment vector (N = 3 + 3J + K):
/// translation (mm) at 0..2, the rotation increment of joint j (rad) at
/// 3 + 3j .. 5 + 3j, shape parameter k at 3 + 3J + k.
struct BodyParamLayout {
  int num_joints = 0;
  int num_shapes = 0;
  explicit BodyParamLayout(const BodyModel& model)
      : num_joints(model.num_joints()), num_shapes(model.num_shapes()) {}
  int size() const { return 3 + 3 * num_joints + num_shapes; }
  static constexpr int translation() { return 0; }
  int rotation(int joint) const { return 3 + 3 * joint; }
  int shape(int k) const { return 3 + 3 * num_joints + k; }
};

/// Params after an increment (layout above): translation + d_t,
/// R_j exp([d_j]x) back to axis-angle, shape + d_s.
/// \throw InvalidInput when delta has the wrong size or is not finite.
BodyParams apply_increment(const BodyModel& model, const BodyParams& params, const Eigen::VectorXd& delta);

/// Jacobian of the posed vertices `vertex_ids` (all when empty): 3n x N,
/// rows 3r .. 3r+2 are d(vertex vertex_ids[r])/d(increment). `posed` must be
/// pose_body(model, params) of the same parameters.
/// \throw InvalidInput for a vertex index out of range or a posed body of
///        another model.
Eigen::MatrixXd posed_vertex_jacobian(const BodyModel& model, const PosedBody& posed,
                                      std::span<const int> vertex_ids = {});

/// Jacobian of the posed joint positions: 3J x N.
Eigen::MatrixXd posed_joint_jacobian(const BodyModel& model, const PosedBody& posed);

}  // namespace knitforge
