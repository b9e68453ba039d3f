#pragma once
/// \file body_keypoints.h
/// The 18 keypoints of the seed's single-image reconstruction (§5.4.4:
/// "13 body joints and 5 face landmarks", OpenPose's COCO-18 layout, in
/// its order): nose, neck, right shoulder, elbow, wrist, left shoulder,
/// elbow, wrist, right hip, knee, ankle, left hip, knee, ankle, right eye,
/// left eye, right ear, left ear.
///
/// On a body of our model form (body_model.h): the 13 body keypoints are
/// the posed joints of the same names ("neck" -> the model's neck joint);
/// the 5 face landmarks are template vertices of the head (the vertices
/// whose largest skinning weight is the "head" joint) chosen on the rest
/// body: the nose is the front-most head vertex a little below the head's
/// middle height, the eyes the front-most at ±35° to the side above it, the
/// ears the outermost at the middle height. Being vertices, they follow
/// shape and pose.

#include <array>
#include <string>

#include "knitforge/body/body_model.h"
#include "knitforge/body/skin_body.h"

namespace knitforge {

inline constexpr int kNumBodyKeypoints = 18;

/// Pixel positions of the 18 keypoints (Eigen leaves a Vec2 uninitialised,
/// so the arrays below start from this: all (0, 0)).
using KeypointPixels = std::array<Vec2, kNumBodyKeypoints>;
inline KeypointPixels zero_keypoint_pixels() {
  KeypointPixels px;
  px.fill(Vec2::Zero());
  return px;
}

/// OpenPose COCO-18 names in order: "nose", "neck", "right_shoulder", ...
const std::array<std::string, kNumBodyKeypoints>& body_keypoint_names();

/// Which of the model's joints and vertices give the keypoints.
struct BodyKeypointRig {
  std::array<int, kNumBodyKeypoints> joint{};   ///< the joint, or -1 for a face landmark
  std::array<int, kNumBodyKeypoints> vertex{};  ///< the template vertex of a face landmark, or -1
};

/// Finds the rig (file comment).
/// \throw InvalidInput naming the joint when the model lacks one of the 13
///        joints or a "head" joint with vertices.
BodyKeypointRig body_keypoint_rig(const BodyModel& model);

/// The keypoints of a posed body (mm, world frame), in the order above.
std::array<Vec3, kNumBodyKeypoints> body_keypoints(const BodyKeypointRig& rig, const PosedBody& posed);

/// The pelvis centre's stand-in: the midpoint of the two hips
/// (keypoints 8 and 11), used to centre depths (§5.4.4).
Vec3 keypoint_pelvis(const std::array<Vec3, kNumBodyKeypoints>& keypoints);

}  // namespace knitforge
