#pragma once
/// \file keypoint_views.h
/// Calibrated views with 2D keypoints, as read from the keypoints JSON file
/// of `knitforge body fit --keypoints` (docs/formats.md), and the 3D
/// keypoints triangulated from them (seed §5.A, triangulate_rays.h):
///
///   { "units": "mm",
///     "cameras": [
///       { "name": "front",
///         "K": [[800, 0, 320], [0, 800, 240], [0, 0, 1]],
///         "R": [[1, 0, 0], [0, 0, -1], [0, 1, 0]],
///         "t": [0, 900, 3000],
///         "keypoints": { "left_shoulder": [402.5, 118.0], "left_elbow": [455.1, 210.9] } } ] }
///
/// Per camera: intrinsics K (pixels), the world-to-camera rotation R and
/// translation t (x_c = R x + t, in "units": mm (default), cm or m) and the
/// keypoints as pixel coordinates (u right, v down) by the body model's
/// joint names (e.g. "pelvis", "left_elbow"; body_model.h). A keypoint seen
/// in fewer than two views is left out (and reported); R must be a rotation
/// (orthonormal, det +1, to 1e-6).

#include <map>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "knitforge/body/triangulate_rays.h"

namespace knitforge {

/// One view: its camera and keypoints.
struct KeypointView {
  std::string name;
  PinholeCamera camera;
  std::map<std::string, Vec2> keypoints;  ///< pixel by joint name
};

/// Reads the views. `what` names the source in messages.
/// \throw InvalidInput naming `what`, the camera and the key for a missing
///        or malformed field, a non-rotation R, an unknown unit, or no camera.
std::vector<KeypointView> keypoint_views_from_json(const nlohmann::json& json, const std::string& what);

/// A triangulated keypoint.
struct Keypoint3d {
  Vec3 point_mm = Vec3::Zero();
  int views = 0;
  double rms_ray_distance_mm = 0.0;
};

/// Result of triangulate_keypoints().
struct TriangulatedKeypoints {
  std::map<std::string, Keypoint3d> points;
  std::vector<std::string> skipped;  ///< seen in fewer than two views
};

/// Every keypoint seen in at least two views, by triangulate_rays().
/// \throw InvalidInput as triangulate_rays() (parallel rays), naming the
///        keypoint.
TriangulatedKeypoints triangulate_keypoints(const std::vector<KeypointView>& views);

}  // namespace knitforge
