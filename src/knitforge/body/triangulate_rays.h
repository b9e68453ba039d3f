#pragma once
/// \file triangulate_rays.h
/// 3D keypoints from several calibrated views (seed §5.A, eq. 5.14-5.16):
/// the point nearest, in the least-squares sense, to the rays through the
/// keypoint's detections.
///
/// Camera model (pinhole, no distortion): a world point x (mm) has camera
/// coordinates x_c = R x + t and pixel (u, v) with (u, v, 1)^T ~ K x_c
/// (u to the right, v down, the camera looking along +z of its frame). The
/// ray of pixel (u, v) is d x (x - a) = 0 with a = -R^T t (the camera
/// centre, R a = -t) and d = R^T K^-1 (u, v, 1)^T normalised. The seed
/// writes R d = (u, v, 1)^T, i.e. normalised image coordinates; with
/// pixels the intrinsics K come first.
///
/// Eq. 5.14: x* = argmin_x sum_i |d_i x (x - a_i)|^2, solved as the linear
/// least-squares problem of eq. 5.15/5.16: M = the stacked [d_i]x (3n x 3),
/// b = the stacked d_i x a_i (the seed prints a_i x d_i, whose sign would
/// give the mirror point -x*: [d]x x - [d]x a = d x x - d x a), normal
/// equations M^T M x = M^T b, which is the 3 x 3 system
/// sum_i (I - d_i d_i^T) x = sum_i (I - d_i d_i^T) a_i. Exact for n >= 2
/// noiseless, non-parallel rays.

#include <span>
#include <vector>

#include "knitforge/geometry/vec.h"

namespace knitforge {

/// A calibrated pinhole camera (see the file comment).
struct PinholeCamera {
  Mat3 K = Mat3::Identity();  ///< intrinsics (pixels): [fx s cx; 0 fy cy; 0 0 1]
  Mat3 R = Mat3::Identity();  ///< world-to-camera rotation
  Vec3 t = Vec3::Zero();      ///< world-to-camera translation (mm)
};

/// A ray: origin and unit direction.
struct Ray {
  Vec3 origin = Vec3::Zero();
  Vec3 direction = Vec3::UnitZ();
};

/// The ray of a pixel. \throw InvalidInput when K is singular or the
/// values are not finite.
Ray camera_ray(const PinholeCamera& camera, const Vec2& pixel);

/// The pixel of a world point. \throw InvalidInput for a point behind or on
/// the camera's plane (z_c <= 0).
Vec2 project_to_pixel(const PinholeCamera& camera, const Vec3& point);

/// Result of triangulate_rays().
struct RayPoint {
  Vec3 point = Vec3::Zero();
  /// Root mean square distance of the point to the rays (mm).
  double rms_distance_mm = 0.0;
  /// Smallest over largest eigenvalue of M^T M (0: parallel rays, 1: three
  /// orthogonal directions).
  double conditioning = 0.0;
};

/// Eq. 5.14-5.16 (file comment). The ray directions need not be unit (they
/// are normalised here).
/// \throw InvalidInput for fewer than 2 rays, a zero or non-finite
///        direction, or rays so close to parallel that the point is not
///        determined (conditioning below 1e-8).
RayPoint triangulate_rays(std::span<const Ray> rays);

}  // namespace knitforge
