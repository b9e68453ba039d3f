#include "knitforge/body/skin_body.h"

#include <fmt/core.h>

#include "knitforge/body/axis_angle.h"
#include "knitforge/util/errors.h"

namespace knitforge {

PosedBody skin_body(const BodyModel& model, const ShapedBody& shaped, const std::vector<Vec3>& rotations,
                    const Vec3& translation_mm) {
  const int V = model.num_vertices(), J = model.num_joints();
  if (static_cast<int>(rotations.size()) != J)
    throw InvalidInput(fmt::format("skin_body: {} joint rotations for a model with {} joints", rotations.size(), J));
  if (static_cast<int>(shaped.vertices.size()) != V || static_cast<int>(shaped.joints.size()) != J)
    throw InvalidInput("skin_body: the shaped body does not belong to this model (vertex or joint count differs)");
  if (!translation_mm.allFinite()) throw InvalidInput("skin_body: the translation is not finite");
  PosedBody out;
  out.local_rotations.resize(static_cast<size_t>(J));
  out.joint_rotations.resize(static_cast<size_t>(J));
  out.joints.resize(static_cast<size_t>(J));
  out.rest_joints = shaped.joints;
  for (int j = 0; j < J; ++j) {
    const auto sj = static_cast<size_t>(j);
    if (!rotations[sj].allFinite())
      throw InvalidInput(fmt::format("skin_body: rotation of joint {} ('{}') is not finite", j, model.joint_names[sj]));
    out.local_rotations[sj] = rotation_from_axis_angle(rotations[sj]);
    const int p = model.parents[sj];
    if (p < 0) {
      out.joint_rotations[sj] = out.local_rotations[sj];
      out.joints[sj] = shaped.joints[sj] + translation_mm;
    } else {
      const auto sp = static_cast<size_t>(p);
      out.joint_rotations[sj] = out.joint_rotations[sp] * out.local_rotations[sj];
      out.joints[sj] = out.joints[sp] + out.joint_rotations[sp] * (shaped.joints[sj] - shaped.joints[sp]);
    }
  }
  out.rest_vertices = shaped.vertices;
  if (model.has_pose_basis()) {
    Eigen::VectorXd feature(9 * (J - 1));
    for (int j = 1; j < J; ++j) {
      const Mat3 d = out.local_rotations[static_cast<size_t>(j)] - Mat3::Identity();
      for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c) feature(9 * (j - 1) + 3 * r + c) = d(r, c);
    }
    const Eigen::VectorXd offset = model.pose_basis * feature;
    for (int i = 0; i < V; ++i) out.rest_vertices[static_cast<size_t>(i)] += offset.segment<3>(3 * i);
  }
  out.vertices.assign(static_cast<size_t>(V), Vec3::Zero());
  for (int i = 0; i < V; ++i) {
    const Vec3& u = out.rest_vertices[static_cast<size_t>(i)];
    Vec3 v = Vec3::Zero();
    for (RowSparse::InnerIterator it(model.skinning_weights, i); it; ++it) {
      const auto j = static_cast<size_t>(it.col());
      v += it.value() * (out.joint_rotations[j] * (u - shaped.joints[j]) + out.joints[j]);
    }
    out.vertices[static_cast<size_t>(i)] = v;
  }
  return out;
}

PosedBody pose_body(const BodyModel& model, const BodyParams& params) {
  validate_body_params(model, params);
  return skin_body(model, shape_body(model, params.shape), params.joint_rotations, params.translation_mm);
}

TriMesh posed_mesh(const BodyModel& model, const PosedBody& posed) { return {posed.vertices, model.faces}; }

}  // namespace knitforge
