#pragma once
/// \file body_pose.h
/// Named poses of a body model, by joint name (so they work for the
/// generated model and for SMPL-format models, whose T-pose rest and joint
/// names are the same): "t-pose" (all rotations zero: arms horizontal),
/// "a-pose" (arms lowered 45 degrees, legs 3 degrees further apart) and
/// "relaxed" (arms lowered 65 degrees, elbows and knees slightly bent, head
/// turned a little), the "another pose" of the fitting bars.

#include <string>
#include <vector>

#include "knitforge/body/body_model.h"

namespace knitforge {

/// Names accepted by pose_preset().
std::vector<std::string> pose_preset_names();

/// Zero shape and translation, the named pose.
/// \throw InvalidInput for an unknown name (listing the names) or a model
///        without the joints the pose moves.
BodyParams pose_preset(const BodyModel& model, const std::string& name);

/// Sets the rotation (axis-angle, rad) of a joint by name.
/// \throw InvalidInput when the model has no such joint.
void set_joint_rotation(const BodyModel& model, BodyParams& params, const std::string& joint, const Vec3& axis_angle);

}  // namespace knitforge
