#pragma once
/// \file pose_from_keypoints.h
/// The initial placement and pose of the body model from 3D joint
/// keypoints (seed §5.2.1/§5.A: triangulated OpenPose keypoints give the
/// initial parameters, there through VPoser; here directly), the start of
/// `knitforge body fit --keypoints`.
///
/// Keypoints are named by the model's joints. With the rest joints of the
/// start's shape (scaled first, see below), the joints are visited
/// parents first; for joint j, its targets are the observed joints of its
/// subtree nearest to it (in every branch, the first observed joint below
/// j). With the current forward kinematics (joints below j still in the
/// start pose):
///  - the root gets the rigid motion (rotation and translation, weighted
///    Kabsch, rigid_align()) that best moves the root (when observed) and
///    its targets onto their keypoints;
///  - another joint j keeps its position and gets the rotation about it:
///    with one target, the smallest rotation turning the direction to the
///    target onto the direction to its keypoint (the twist about the bone
///    stays the start's); with more, the rotation best aligning the unit
///    directions (orthogonal Procrustes);
///  - joints without targets (leaves, unobserved branches) keep the start's
///    rotation.
/// Scale: when the model has a "stature" shape parameter and at least three
/// bones (parent and child both observed), the stature is set to the
/// template's times the mean ratio of observed to rest bone lengths (within
/// [0.7, 1.3]): the shape is then shape_from_measurements() of that
/// stature (the other lengths follow the height, the girths are the
/// template's); otherwise the start's shape is kept.
/// Deterministic; cost O(J^2) plus the shape step.

#include <map>
#include <string>

#include "knitforge/body/body_model.h"

namespace knitforge {

/// Result of pose_from_keypoints().
struct KeypointPose {
  BodyParams params;
  double rms_mm = 0.0;     ///< of the observed joints to their keypoints, after
  double scale = 1.0;      ///< the bone length ratio applied (1: none)
  int joints_used = 0;     ///< keypoints that name a joint of the model
};

/// See the file comment. `start` gives the shape and the rotations of the
/// joints the keypoints do not determine (e.g. the a-pose).
/// \throw InvalidInput when a keypoint names no joint of the model (listing
///        the names), is not finite, or fewer than 3 keypoints are given.
KeypointPose pose_from_keypoints(const BodyModel& model, const std::map<std::string, Vec3>& keypoints_mm,
                                 const BodyParams& start);

}  // namespace knitforge
