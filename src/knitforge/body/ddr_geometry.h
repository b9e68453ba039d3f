#pragma once
/// \file ddr_geometry.h
/// From a dual-depth representation (ddr_sample.h's normalisation) back to
/// 3D, and the pieces of the seed's view-based refinement (§5.4.4):
/// foreground pixels to oriented points, a point cloud turned about the
/// vertical axis and rendered as a new min-depth image, and the errors of a
/// predicted DDR (eq. 5.10-5.12).

#include <vector>

#include "knitforge/body/depth_image.h"
#include "knitforge/body/fuse_point_clouds.h"
#include "knitforge/evaluate/rigid_align.h"

namespace knitforge {

/// A foreground pixel of a predicted DDR has |I_min| or |I_max| above this
/// (normalised units; 0.01 = 1 cm, the seed's threshold).
inline constexpr double kDdrForegroundThreshold = 0.01;

/// The two channels of a DDR (2 x s x s, normalised) as z-depths (mm) of a
/// camera whose pelvis centre lies at `pelvis_depth_mm`; background pixels
/// (both channels within kDdrForegroundThreshold of 0) are 0. Pixels where
/// I_max < I_min are given I_max = I_min.
/// \throw InvalidInput when ddr does not hold 2 s^2 values.
std::pair<DepthImage, DepthImage> ddr_depth_images(const std::vector<float>& ddr, int size, double pelvis_depth_mm);

/// Oriented points of a DDR in the camera's frame (mm): the I_min points
/// with normals towards the camera, the I_max points with normals away from
/// it (depth_to_oriented_points() with a window scaled to the pixel size at
/// the pelvis: `spacing_mm`).
OrientedPoints ddr_oriented_points(const std::vector<float>& ddr, const DepthCamera& camera, double pelvis_depth_mm);

/// The camera-frame transform that turns points by `angle_rad` about the
/// vertical axis (the camera's y) through `pivot`: seeing the result is
/// seeing the body from a camera orbiting it by -angle.
RigidTransform turn_about_vertical(const Vec3& pivot, double angle_rad);

/// The frame reconstructions are given in: origin at the pelvis centre
/// (`pelvis`, camera frame), x to the picture's right, y away from the
/// camera, z up (a body facing the camera faces -y, as body_model.h).
RigidTransform camera_to_body_frame(const Vec3& pelvis);

/// Each point mapped by `transform` and splatted to its nearest pixel; a
/// pixel keeps the nearest depth (0: no point).
DepthImage splat_min_depth(const std::vector<Vec3>& points, const DepthCamera& camera, const RigidTransform& transform);

/// The errors of one predicted DDR against the truth, over the true
/// foreground pixels (M of them), in normalised units: ei = the L1 norm
/// (eq. 5.10's summand), ep_cm = ei / (2 M) in centimetres (eq. 5.11), eg =
/// the L1 norm of (∇_h + ∇_v)(prediction - truth) (eq. 5.12; forward
/// differences between foreground neighbours).
struct DdrErrors {
  double ei = 0.0;
  double ep_cm = 0.0;
  double eg = 0.0;
  int foreground = 0;
};
/// \throw InvalidInput on mismatched sizes.
DdrErrors ddr_errors(const std::vector<float>& predicted, const std::vector<float>& truth,
                     const std::vector<uint8_t>& foreground, int size);

}  // namespace knitforge
