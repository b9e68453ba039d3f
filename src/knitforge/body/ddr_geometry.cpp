#include "knitforge/body/ddr_geometry.h"

#include <algorithm>
#include <cmath>

#include <fmt/core.h>

#include "knitforge/body/ddr_sample.h"
#include "knitforge/util/errors.h"

namespace knitforge {

std::pair<DepthImage, DepthImage> ddr_depth_images(const std::vector<float>& ddr, int size, double pelvis_depth_mm) {
  const size_t plane = static_cast<size_t>(size) * static_cast<size_t>(size);
  if (ddr.size() != 2 * plane)
    throw InvalidInput(fmt::format("a {0} x {0} DDR has {1} values, not {2}", size, ddr.size(), 2 * plane));
  DepthImage lo{size, size, std::vector<double>(plane, 0.0)}, hi = lo;
  for (size_t i = 0; i < plane; ++i) {
    const double a = ddr[i], b = ddr[plane + i];
    if (std::abs(a) <= kDdrForegroundThreshold && std::abs(b) <= kDdrForegroundThreshold) continue;
    lo.depth_mm[i] = pelvis_depth_mm + kDdrDepthUnitMm * a;
    hi.depth_mm[i] = pelvis_depth_mm + kDdrDepthUnitMm * std::max(a, b);
  }
  return {lo, hi};
}

OrientedPoints ddr_oriented_points(const std::vector<float>& ddr, const DepthCamera& camera, double pelvis_depth_mm) {
  const auto [lo, hi] = ddr_depth_images(ddr, camera.width, pelvis_depth_mm);
  DepthNormalOptions normals;
  const double pixel_mm = pelvis_depth_mm / camera.K(0, 0);
  normals.radius_px = 1;
  normals.max_gap_mm = 2.5 * pixel_mm;
  normals.min_neighbours = 3;
  OrientedPoints front = depth_to_oriented_points(lo, camera, {}, normals);
  const OrientedPoints back = depth_to_oriented_points(hi, camera, {}, normals);
  for (size_t i = 0; i < back.points.size(); ++i) {
    front.points.push_back(back.points[i]);
    front.normals.push_back(-back.normals[i]);
  }
  return front;
}

RigidTransform turn_about_vertical(const Vec3& pivot, double angle_rad) {
  RigidTransform t;
  const double c = std::cos(angle_rad), s = std::sin(angle_rad);
  t.rotation << c, 0, s, 0, 1, 0, -s, 0, c;
  t.translation = pivot - t.rotation * pivot;
  return t;
}

RigidTransform camera_to_body_frame(const Vec3& pelvis) {
  RigidTransform t;
  t.rotation << 1, 0, 0, 0, 0, 1, 0, -1, 0;
  t.translation = -(t.rotation * pelvis);
  return t;
}

DepthImage splat_min_depth(const std::vector<Vec3>& points, const DepthCamera& camera, const RigidTransform& transform) {
  DepthImage image{camera.width, camera.height,
                   std::vector<double>(static_cast<size_t>(camera.width) * static_cast<size_t>(camera.height), 0.0)};
  for (const Vec3& x : points) {
    const Vec3 y = transform.apply(x);
    if (!(y.z() > 0.0)) continue;
    const Vec3 p = camera.K * y;
    const int u = static_cast<int>(std::lround(p.x() / p.z())), v = static_cast<int>(std::lround(p.y() / p.z()));
    if (u < 0 || v < 0 || u >= camera.width || v >= camera.height) continue;
    double& d = image.depth_mm[static_cast<size_t>(v) * static_cast<size_t>(camera.width) + static_cast<size_t>(u)];
    if (d == 0.0 || y.z() < d) d = y.z();
  }
  return image;
}

DdrErrors ddr_errors(const std::vector<float>& predicted, const std::vector<float>& truth,
                     const std::vector<uint8_t>& foreground, int size) {
  const size_t plane = static_cast<size_t>(size) * static_cast<size_t>(size);
  if (predicted.size() != 2 * plane || truth.size() != 2 * plane || foreground.size() != plane)
    throw InvalidInput(fmt::format("ddr_errors: sizes {} / {} / {} do not fit a {} x {} DDR", predicted.size(),
                                   truth.size(), foreground.size(), size, size));
  DdrErrors e;
  const auto diff = [&](size_t c, int u, int v) {
    const size_t i = c * plane + static_cast<size_t>(v * size + u);
    return static_cast<double>(predicted[i]) - truth[i];
  };
  const auto fg = [&](int u, int v) { return u < size && v < size && foreground[static_cast<size_t>(v * size + u)] != 0; };
  for (int v = 0; v < size; ++v)
    for (int u = 0; u < size; ++u) {
      if (!fg(u, v)) continue;
      ++e.foreground;
      for (size_t c = 0; c < 2; ++c) {
        const double d = diff(c, u, v);
        e.ei += std::abs(d);
        double g = 0.0;
        if (fg(u + 1, v)) g += diff(c, u + 1, v) - d;
        if (fg(u, v + 1)) g += diff(c, u, v + 1) - d;
        e.eg += std::abs(g);
      }
    }
  if (e.foreground > 0) e.ep_cm = e.ei / (2.0 * e.foreground) * kDdrDepthUnitMm / 10.0;
  return e;
}

}  // namespace knitforge
