#include "knitforge/body/body_pose.h"

#include <numbers>

#include <fmt/core.h>

#include "knitforge/util/errors.h"

namespace knitforge {

namespace {
constexpr double kDeg = std::numbers::pi / 180.0;
}

std::vector<std::string> pose_preset_names() { return {"t-pose", "a-pose", "relaxed"}; }

void set_joint_rotation(const BodyModel& model, BodyParams& params, const std::string& joint, const Vec3& axis_angle) {
  const int j = model.joint_index(joint);
  if (j < 0) throw InvalidInput(fmt::format("body model '{}' has no joint '{}'", model.name, joint));
  params.joint_rotations[static_cast<size_t>(j)] = axis_angle;
}

BodyParams pose_preset(const BodyModel& model, const std::string& name) {
  BodyParams p = zero_params(model);
  if (name == "t-pose") return p;
  if (name == "a-pose") {
    // Rotating about +y lowers the left arm (+x) and raises the right one.
    set_joint_rotation(model, p, "left_shoulder", {0, 45 * kDeg, 0});
    set_joint_rotation(model, p, "right_shoulder", {0, -45 * kDeg, 0});
    set_joint_rotation(model, p, "left_hip", {0, -3 * kDeg, 0});
    set_joint_rotation(model, p, "right_hip", {0, 3 * kDeg, 0});
    return p;
  }
  if (name == "relaxed") {
    set_joint_rotation(model, p, "left_shoulder", {0, 65 * kDeg, -8 * kDeg});
    set_joint_rotation(model, p, "right_shoulder", {0, -65 * kDeg, 8 * kDeg});
    set_joint_rotation(model, p, "left_elbow", {0, 0, -15 * kDeg});
    set_joint_rotation(model, p, "right_elbow", {0, 0, 15 * kDeg});
    set_joint_rotation(model, p, "left_hip", {-6 * kDeg, -2 * kDeg, 0});
    set_joint_rotation(model, p, "right_hip", {4 * kDeg, 2 * kDeg, 0});
    set_joint_rotation(model, p, "left_knee", {8 * kDeg, 0, 0});
    set_joint_rotation(model, p, "neck", {0, 0, 10 * kDeg});
    return p;
  }
  std::string all;
  for (const auto& n : pose_preset_names()) all += (all.empty() ? "" : ", ") + n;
  throw InvalidInput(fmt::format("unknown pose '{}'; the poses are: {} (or a parameter JSON file)", name, all));
}

}  // namespace knitforge
