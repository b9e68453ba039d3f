#pragma once
/// \file openpose_json.h
/// 2D keypoints of one person in OpenPose's JSON output format (the
/// detector the seed uses, §5.4.4):
///
///   { "version": 1.3, "people": [ { "pose_keypoints_2d": [x0, y0, c0, x1, y1, c1, ...] } ] }
///
/// pixel coordinates (x right, y down) and a confidence per keypoint, in
/// the COCO-18 layout (18 keypoints, body_keypoints.h's order) or BODY_25
/// (25: its MidHip and six foot points are dropped, the rest mapped to
/// COCO-18). A confidence of 0 means "not detected". The first person is
/// used.

#include <array>
#include <string>

#include <nlohmann/json.hpp>

#include "knitforge/body/body_keypoints.h"

namespace knitforge {

/// One person's keypoints (COCO-18 order).
struct PersonKeypoints {
  KeypointPixels px = zero_keypoint_pixels();  ///< (0, 0) where not present
  std::array<bool, kNumBodyKeypoints> present{};
  int people_in_file = 0;  ///< how many people the file lists
};

/// Reads the first person. `what` names the source in messages.
/// \throw InvalidInput naming `what` and the element: no "people" array or
///        no person, "pose_keypoints_2d" missing, not 54 or 75 numbers, a
///        non-finite or negative coordinate of a detected keypoint.
PersonKeypoints openpose_keypoints_from_json(const nlohmann::json& json, const std::string& what);

/// The COCO-18 JSON of one person (confidence 1 for present keypoints, 0
/// and coordinates 0 for the others).
nlohmann::json openpose_keypoints_to_json(const PersonKeypoints& person);

}  // namespace knitforge
