#pragma once
/// \file camera.h
/// A look-at camera (perspective or orthographic) and its transformation to
/// normalised device coordinates (NDC), shared by the raster preview and the
/// vector drawing (seed §1.A.2, "NDC transformation").
///
/// NDC here: x to the right and y up, both in [-1, 1] over the image;
/// z is a depth that grows away from the camera and is an affine function of
/// 1/distance for a perspective camera (z = -1/d, d the distance along the
/// view direction) and of the distance for an orthographic one (z = d). With
/// this choice the camera transformation is projective, so lines and planes
/// stay lines and planes in NDC, the projection to the image is orthographic
/// (drop z), and z interpolates linearly across a projected triangle.

#include <span>

#include "knitforge/geometry/vec.h"

namespace knitforge {

struct Camera {
  Vec3 eye{0.0, 0.0, 100.0};    ///< camera position (mm)
  Vec3 target{0.0, 0.0, 0.0};   ///< point looked at (mm)
  Vec3 up{0.0, 1.0, 0.0};       ///< approximate up direction
  bool orthographic = false;    ///< orthographic instead of perspective projection
  double fov_y_degrees = 30.0;  ///< perspective: vertical field of view, in (0, 180)
  double ortho_height = 100.0;  ///< orthographic: height of the view (mm), > 0
  double aspect = 1.0;          ///< image width / height, > 0
  /// Perspective: points nearer than this distance along the view direction
  /// (mm) cannot be projected (see ViewTransform::in_front).
  double near = 1e-3;
};

/// World -> NDC for one camera.
struct ViewTransform {
  Vec3 eye = Vec3::Zero();
  Vec3 right = Vec3::UnitX(), up = Vec3::UnitY(),
       forward = -Vec3::UnitZ();  ///< orthonormal, right-handed view basis
  bool orthographic = false;
  double sx = 1.0,
         sy = 1.0;  ///< NDC scale: perspective 1/(tan(fov/2) aspect), 1/tan(fov/2); ortho 2/(h aspect), 2/h
  double near = 1e-3;

  /// Distance of p along the view direction (negative behind the camera).
  double distance(const Vec3& p) const { return (p - eye).dot(forward); }
  /// True when p can be projected (orthographic: always; perspective:
  /// distance(p) >= near).
  bool in_front(const Vec3& p) const { return orthographic || distance(p) >= near; }
  /// NDC of p (see the file comment). \pre in_front(p).
  Vec3 to_ndc(const Vec3& p) const {
    const Vec3 q = p - eye;
    const double x = q.dot(right), y = q.dot(up), d = q.dot(forward);
    if (orthographic) return {sx * x, sy * y, d};
    return {sx * x / d, sy * y / d, -1.0 / d};
  }
};

/// The transformation of a camera.
/// \throw InvalidInput when eye == target, up is parallel to the view
///        direction or zero, a value is not finite, or fov_y_degrees,
///        ortho_height, aspect or near are out of range (naming the field).
ViewTransform view_transform(const Camera& camera);

/// A camera that frames the bounding box of `points`: it looks at the box
/// centre from `view_direction` (the direction from the target to the eye,
/// normalised internally), with `up` as given and the default field of view,
/// from the nearest distance (perspective) or with the smallest view height
/// (orthographic) at which all eight box corners are inside the image with a
/// 5% margin.
/// \throw InvalidInput when `points` is empty or not finite, aspect <= 0 or
///        view_direction is zero or parallel to up.
Camera frame_points(std::span<const Vec3> points, double aspect, bool orthographic = false,
                    const Vec3& view_direction = Vec3(0.25, -0.35, 1.0), const Vec3& up = Vec3::UnitY());

}  // namespace knitforge
