#pragma once
/// \file shape_body.h
/// The shape stage of a body model (SMPL's first step): the template plus
/// the shape blend shapes, and the rest joints regressed from the shaped
/// vertices. No pose; see skin_body.h.

#include <vector>

#include <Eigen/Core>

#include "knitforge/body/body_model.h"

namespace knitforge {

/// A shaped body in its rest pose.
struct ShapedBody {
  std::vector<Vec3> vertices;  ///< V: template + shape_basis * shape (mm)
  std::vector<Vec3> joints;    ///< J: joint_regressor * vertices (mm)
};

/// V_s = T + S beta, J = R V_s.
/// \throw InvalidInput when shape.size() != model.num_shapes() or a value is
///        not finite.
ShapedBody shape_body(const BodyModel& model, const Eigen::VectorXd& shape);

/// The rest joints of a shape (joint_regressor * shaped vertices).
std::vector<Vec3> regress_joints(const BodyModel& model, const std::vector<Vec3>& vertices);

}  // namespace knitforge
