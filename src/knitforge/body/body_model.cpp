#include "knitforge/body/body_model.h"

#include <cmath>

#include <fmt/core.h>

#include "knitforge/util/errors.h"

namespace knitforge {

namespace {

constexpr std::array<const char*, kNumBodyParts> kPartNames = {
    "head",      "neck",       "torso-front", "torso-back", "left-sleeve", "right-sleeve",
    "left-hand", "right-hand", "left-leg",    "right-leg",  "left-foot",   "right-foot"};

bool finite(const Eigen::MatrixXd& m) { return m.allFinite(); }

}  // namespace

std::string body_part_name(BodyPart part) { return kPartNames[static_cast<size_t>(part)]; }

BodyPart body_part_from_name(const std::string& name) {
  for (int i = 0; i < kNumBodyParts; ++i) {
    if (name == kPartNames[static_cast<size_t>(i)]) return static_cast<BodyPart>(i);
  }
  std::string all;
  for (const char* n : kPartNames) all += (all.empty() ? "" : ", ") + std::string(n);
  throw InvalidInput(fmt::format("unknown body part '{}'; the parts are: {}", name, all));
}

bool is_unfitted_part(BodyPart part) {
  switch (part) {
    case BodyPart::Head:
    case BodyPart::LeftHand:
    case BodyPart::RightHand:
    case BodyPart::LeftFoot:
    case BodyPart::RightFoot:
      return true;
    default:
      return false;
  }
}

int BodyModel::joint_index(const std::string& joint_name) const {
  for (int j = 0; j < num_joints(); ++j) {
    if (joint_names[static_cast<size_t>(j)] == joint_name) return j;
  }
  return -1;
}

BodyParams zero_params(const BodyModel& model) {
  BodyParams p;
  p.shape = Eigen::VectorXd::Zero(model.num_shapes());
  p.joint_rotations.assign(static_cast<size_t>(model.num_joints()), Vec3::Zero());
  return p;
}

void validate_body_model(const BodyModel& m) {
  const std::string who = fmt::format("body model '{}'", m.name);
  const int V = m.num_vertices(), J = m.num_joints();
  if (V < 4 || m.faces.empty()) throw InvalidInput(who + ": needs at least 4 vertices and one face");
  for (int i = 0; i < V; ++i) {
    if (!m.template_vertices[static_cast<size_t>(i)].allFinite())
      throw InvalidInput(fmt::format("{}: template vertex {} is not finite", who, i));
  }
  for (int f = 0; f < m.num_faces(); ++f) {
    for (int k : m.faces[static_cast<size_t>(f)]) {
      if (k < 0 || k >= V)
        throw InvalidInput(fmt::format("{}: face {} uses vertex {}, outside [0, {})", who, f, k, V));
    }
  }
  if (m.shape_basis.rows() != 3 * V)
    throw InvalidInput(fmt::format("{}: shape basis has {} rows, expected 3 x {} vertices = {}", who,
                                   m.shape_basis.rows(), V, 3 * V));
  if (static_cast<int>(m.shape_names.size()) != m.num_shapes())
    throw InvalidInput(fmt::format("{}: {} shape names for {} shape parameters", who, m.shape_names.size(),
                                   m.num_shapes()));
  if (!finite(m.shape_basis)) throw InvalidInput(who + ": shape basis has non-finite entries");
  if (J < 1) throw InvalidInput(who + ": has no joints");
  if (m.has_pose_basis()) {
    if (m.pose_basis.rows() != 3 * V || m.pose_basis.cols() != 9 * (J - 1))
      throw InvalidInput(fmt::format("{}: pose basis is {} x {}, expected {} x {} (3V x 9(J-1))", who,
                                     m.pose_basis.rows(), m.pose_basis.cols(), 3 * V, 9 * (J - 1)));
    if (!finite(m.pose_basis)) throw InvalidInput(who + ": pose basis has non-finite entries");
  }
  if (static_cast<int>(m.joint_names.size()) != J)
    throw InvalidInput(fmt::format("{}: {} joint names for {} joints", who, m.joint_names.size(), J));
  if (m.parents[0] != -1) throw InvalidInput(fmt::format("{}: joint 0 must be the root (parent -1)", who));
  for (int j = 1; j < J; ++j) {
    const int p = m.parents[static_cast<size_t>(j)];
    if (p < 0 || p >= j)
      throw InvalidInput(fmt::format("{}: joint {} ('{}') has parent {}; parents must precede their children",
                                     who, j, m.joint_names[static_cast<size_t>(j)], p));
  }
  if (m.joint_regressor.rows() != J || m.joint_regressor.cols() != V)
    throw InvalidInput(fmt::format("{}: joint regressor is {} x {}, expected {} x {} (J x V)", who,
                                   m.joint_regressor.rows(), m.joint_regressor.cols(), J, V));
  for (int j = 0; j < J; ++j) {
    double sum = 0.0;
    for (RowSparse::InnerIterator it(m.joint_regressor, j); it; ++it) {
      if (!std::isfinite(it.value()))
        throw InvalidInput(fmt::format("{}: joint regressor row {} has a non-finite entry", who, j));
      sum += it.value();
    }
    if (std::abs(sum - 1.0) > 1e-3)
      throw InvalidInput(fmt::format("{}: joint regressor row {} ('{}') sums to {}, not 1", who, j,
                                     m.joint_names[static_cast<size_t>(j)], sum));
  }
  if (m.skinning_weights.rows() != V || m.skinning_weights.cols() != J)
    throw InvalidInput(fmt::format("{}: skinning weights are {} x {}, expected {} x {} (V x J)", who,
                                   m.skinning_weights.rows(), m.skinning_weights.cols(), V, J));
  for (int i = 0; i < V; ++i) {
    double sum = 0.0;
    for (RowSparse::InnerIterator it(m.skinning_weights, i); it; ++it) {
      if (!(it.value() >= 0.0) || !std::isfinite(it.value()))
        throw InvalidInput(fmt::format("{}: skinning weight of vertex {} for joint {} is {} (must be >= 0)",
                                       who, i, it.col(), it.value()));
      sum += it.value();
    }
    if (std::abs(sum - 1.0) > 1e-6)
      throw InvalidInput(fmt::format("{}: skinning weights of vertex {} sum to {}, not 1", who, i, sum));
  }
  if (!m.vertex_parts.empty() && static_cast<int>(m.vertex_parts.size()) != V)
    throw InvalidInput(fmt::format("{}: {} part labels for {} vertices", who, m.vertex_parts.size(), V));
  if (!m.part_fields.empty()) {
    if (m.part_fields.size() != static_cast<size_t>(kNumBodyParts))
      throw InvalidInput(fmt::format("{}: {} part fields, expected {}", who, m.part_fields.size(), kNumBodyParts));
    for (const auto& f : m.part_fields) {
      if (static_cast<int>(f.size()) != V)
        throw InvalidInput(fmt::format("{}: a part field has {} values for {} vertices", who, f.size(), V));
    }
  }
  for (const auto& [name, v] : m.landmarks) {
    if (v < 0 || v >= V)
      throw InvalidInput(fmt::format("{}: landmark '{}' is vertex {}, outside [0, {})", who, name, v, V));
  }
}

void validate_body_params(const BodyModel& model, const BodyParams& p) {
  if (p.shape.size() != model.num_shapes())
    throw InvalidInput(fmt::format("body parameters: {} shape values, the model '{}' has {}", p.shape.size(),
                                   model.name, model.num_shapes()));
  if (!p.shape.allFinite()) throw InvalidInput("body parameters: a shape value is not finite");
  if (static_cast<int>(p.joint_rotations.size()) != model.num_joints())
    throw InvalidInput(fmt::format("body parameters: {} joint rotations, the model '{}' has {} joints",
                                   p.joint_rotations.size(), model.name, model.num_joints()));
  for (size_t j = 0; j < p.joint_rotations.size(); ++j) {
    if (!p.joint_rotations[j].allFinite())
      throw InvalidInput(fmt::format("body parameters: rotation of joint {} ('{}') is not finite", j,
                                     model.joint_names[j]));
  }
  if (!p.translation_mm.allFinite()) throw InvalidInput("body parameters: translation is not finite");
}

}  // namespace knitforge
