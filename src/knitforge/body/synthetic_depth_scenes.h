#pragma once
/// \file synthetic_depth_scenes.h
/// Synthetic data for depth-camera calibration and fusion, with known
/// answers: the seed's dual-camera rig (§5.3, Fig. 5.4), a calibration
/// board in random poses, and depth-camera noise. `knitforge body
/// render-depth` writes them as files; the tests measure the calibration
/// and fusion errors on them.

#include <vector>

#include <nlohmann/json.hpp>

#include "knitforge/body/depth_image.h"
#include "knitforge/evaluate/rigid_align.h"
#include "knitforge/geometry/tri_mesh.h"

namespace knitforge {

/// Two depth cameras and where they stand (world frame: z up, the person
/// facing -y, as body make writes bodies).
struct DepthRig {
  DepthCamera camera1;
  DepthCamera camera2;
  RigidTransform world_to_camera1;  ///< x_1 = R x + t
  RigidTransform world_to_camera2;
};

/// The seed's setup: two cameras facing each other about 2 m apart, the
/// person between them facing camera 1. Camera 1 stands at (0, -distance/2,
/// height) looking along +y, level; camera 2 near (0, +distance/2, height)
/// looking back along -y, set up by hand: 60 mm to the side, 40 mm higher,
/// turned by 3° (yaw), -4° (pitch), 1.5° (roll), so the calibration has
/// something to find. Both cameras: 480 x 640 pixels (portrait), fx = fy =
/// 280 px (98° vertical field of view, as a wide-angle depth camera's: a
/// 1.8 m person, feet to head, fits at 0.85 m), 1 mm depth units.
DepthRig seed_depth_rig(double distance_mm = 2000.0, double height_mm = 900.0);

/// Camera 2's frame to camera 1's: what calibration finds.
RigidTransform camera2_to_camera1(const DepthRig& rig);

/// The rig as JSON: {"camera1": intrinsics, "camera2": ..., "world_to_camera1":
/// {"R", "t"}, "world_to_camera2": ..., "camera2_to_camera1": {"R", "t"}}.
nlohmann::json depth_rig_to_json(const DepthRig& rig);
/// \throw InvalidInput naming `what` and the field.
DepthRig depth_rig_from_json(const nlohmann::json& json, const std::string& what);

/// A rigid motion as JSON {"R": rows, "t": [x, y, z] (mm)} and back.
nlohmann::json rigid_transform_to_json(const RigidTransform& T);
/// \throw InvalidInput naming `what` when R is not a rotation or a field is
///        missing or malformed.
RigidTransform rigid_transform_from_json(const nlohmann::json& json, const std::string& what);

/// A flat board of uniform thickness.
struct BoardSize {
  double width_mm = 600.0;
  double height_mm = 450.0;
  double thickness_mm = 10.0;
};

/// The board as a closed box mesh (12 triangles) placed by `pose` (board
/// frame: width along x, height along z, thickness along y, centred at the
/// origin; its two large sides face -y and +y).
TriMesh board_mesh(const BoardSize& size, const RigidTransform& pose);

/// k board poses between the rig's cameras, as a person holding the board
/// would: the centre within ±150 mm (x, z) and ±100 mm (y) of the rig's
/// middle, the board tilted by 15-40° about an axis in its plane whose
/// direction goes round the circle from pose to pose (360°/k apart, ±20°,
/// from a random start) and turned in its plane by up to ±30°; each pose's normal at least 10° from
/// every earlier one (the seed: no pose parallel to an earlier one).
/// Deterministic for a seed.
std::vector<RigidTransform> random_board_poses(const DepthRig& rig, int k, unsigned seed);

/// Depth-camera noise.
struct DepthNoise {
  double sigma_mm = 1.0;          ///< Gaussian noise on every measured depth
  double outlier_fraction = 0.0;  ///< pixels replaced by a uniform depth in [300, 4000] mm (clutter, flying pixels)
  unsigned seed = 1;
};

/// Adds `noise` to the image in place (deterministic for a seed; depths kept > 0).
void add_depth_noise(DepthImage& image, const DepthNoise& noise);

}  // namespace knitforge
