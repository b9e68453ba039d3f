#include "knitforge/body/shape_body.h"

#include <fmt/core.h>

#include "knitforge/util/errors.h"

namespace knitforge {

std::vector<Vec3> regress_joints(const BodyModel& model, const std::vector<Vec3>& vertices) {
  std::vector<Vec3> joints(static_cast<size_t>(model.num_joints()), Vec3::Zero());
  for (int j = 0; j < model.num_joints(); ++j) {
    Vec3 sum = Vec3::Zero();
    for (RowSparse::InnerIterator it(model.joint_regressor, j); it; ++it) {
      sum += it.value() * vertices[static_cast<size_t>(it.col())];
    }
    joints[static_cast<size_t>(j)] = sum;
  }
  return joints;
}

ShapedBody shape_body(const BodyModel& model, const Eigen::VectorXd& shape) {
  if (shape.size() != model.num_shapes())
    throw InvalidInput(fmt::format("shape_body: {} shape values, the model '{}' has {}", shape.size(), model.name,
                                   model.num_shapes()));
  if (!shape.allFinite()) throw InvalidInput("shape_body: a shape value is not finite");
  ShapedBody out;
  const int V = model.num_vertices();
  out.vertices = model.template_vertices;
  if (model.num_shapes() > 0 && shape.cwiseAbs().maxCoeff() > 0.0) {
    const Eigen::VectorXd d = model.shape_basis * shape;
    for (int i = 0; i < V; ++i) out.vertices[static_cast<size_t>(i)] += d.segment<3>(3 * i);
  }
  out.joints = regress_joints(model, out.vertices);
  return out;
}

}  // namespace knitforge
