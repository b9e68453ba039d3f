#include "knitforge/render/camera.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include <fmt/core.h>

#include "knitforge/util/errors.h"

namespace knitforge {

ViewTransform view_transform(const Camera& c) {
  if (!c.eye.allFinite() || !c.target.allFinite() || !c.up.allFinite()) {
    throw InvalidInput("camera: eye, target and up must be finite");
  }
  const Vec3 dir = c.target - c.eye;
  if (dir.norm() <= 0.0)
    throw InvalidInput("camera: eye and target coincide; move the eye away from the target");
  if (!(c.aspect > 0.0) || !std::isfinite(c.aspect)) throw InvalidInput("camera: aspect must be positive");
  ViewTransform t;
  t.eye = c.eye;
  t.forward = dir.normalized();
  const Vec3 r = t.forward.cross(c.up);
  if (c.up.norm() <= 0.0 || r.norm() <= 1e-9 * c.up.norm()) {
    throw InvalidInput(
        "camera: the up direction is zero or parallel to the view direction; choose another up");
  }
  t.right = r.normalized();
  t.up = t.right.cross(t.forward);
  t.orthographic = c.orthographic;
  if (c.orthographic) {
    if (!(c.ortho_height > 0.0) || !std::isfinite(c.ortho_height)) {
      throw InvalidInput("camera: ortho_height must be positive (mm)");
    }
    t.sy = 2.0 / c.ortho_height;
    t.sx = t.sy / c.aspect;
  } else {
    if (!(c.fov_y_degrees > 0.0 && c.fov_y_degrees < 180.0)) {
      throw InvalidInput(fmt::format("camera: fov_y_degrees = {} must be in (0, 180)", c.fov_y_degrees));
    }
    if (!(c.near > 0.0) || !std::isfinite(c.near)) throw InvalidInput("camera: near must be positive (mm)");
    t.sy = 1.0 / std::tan(0.5 * c.fov_y_degrees * std::numbers::pi / 180.0);
    t.sx = t.sy / c.aspect;
    t.near = c.near;
  }
  return t;
}

Camera frame_points(std::span<const Vec3> points, double aspect, bool orthographic,
                    const Vec3& view_direction, const Vec3& up) {
  if (points.empty()) throw InvalidInput("frame_points: nothing to frame (no points)");
  if (!(aspect > 0.0) || !std::isfinite(aspect)) throw InvalidInput("frame_points: aspect must be positive");
  Vec3 lo = points[0], hi = points[0];
  for (const Vec3& p : points) {
    if (!p.allFinite()) throw InvalidInput("frame_points: a point is not finite");
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  const double len = view_direction.norm();
  if (!(len > 0.0) || view_direction.normalized().cross(up).norm() < 1e-9) {
    throw InvalidInput("frame_points: the view direction is zero or parallel to up");
  }
  const Vec3 centre = 0.5 * (lo + hi);
  const double radius = std::max(0.5 * (hi - lo).norm(), 1e-6);
  Camera c;
  c.target = centre;
  c.up = up;
  c.aspect = aspect;
  c.orthographic = orthographic;
  const Vec3 dir = view_direction / len;
  // the view basis of the result (as view_transform() builds it)
  const Vec3 forward = -dir;
  const Vec3 right = forward.cross(up).normalized();
  const Vec3 vup = right.cross(forward);
  const double fill = 1.0 / 1.05;  // 5% margin
  if (orthographic) {
    double h = 0.0;
    for (int k = 0; k < 8; ++k) {
      const Vec3 q = Vec3(k & 1 ? hi.x() : lo.x(), k & 2 ? hi.y() : lo.y(), k & 4 ? hi.z() : lo.z()) - centre;
      h = std::max({h, 2.0 * std::abs(q.dot(vup)), 2.0 * std::abs(q.dot(right)) / aspect});
    }
    c.ortho_height = std::max(h, 1e-6) / fill;
    c.eye = centre + 3.0 * radius * dir;
  } else {
    const double ty = std::tan(0.5 * c.fov_y_degrees * std::numbers::pi / 180.0) * fill, tx = ty * aspect;
    double d = 0.0;
    for (int k = 0; k < 8; ++k) {
      const Vec3 q = Vec3(k & 1 ? hi.x() : lo.x(), k & 2 ? hi.y() : lo.y(), k & 4 ? hi.z() : lo.z()) - centre;
      const double z = q.dot(forward);
      d = std::max({d, std::abs(q.dot(right)) / tx - z, std::abs(q.dot(vup)) / ty - z, radius * 1e-3 - z});
    }
    c.eye = centre + std::max(d, 1e-6) * dir;
    c.near = 1e-3 * radius;
  }
  return c;
}

}  // namespace knitforge
