#include "knitforge/body/fuse_point_clouds.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>

#include <Eigen/Eigenvalues>
#include <fmt/core.h>

#include "knitforge/util/errors.h"

namespace knitforge {

OrientedPoints depth_to_oriented_points(const DepthImage& image, const DepthCamera& camera, const DepthRange& range,
                                        const DepthNormalOptions& o) {
  if (o.radius_px < 1 || o.radius_px > 10 || !(o.max_gap_mm > 0.0) || o.min_neighbours < 2)
    throw InvalidInput("depth normals: radius must be 1..10 pixels, the gap positive, at least 2 neighbours");
  std::vector<int> pixels;
  const std::vector<Vec3> pts = depth_to_points(image, camera, range, &pixels);
  // Point index per pixel (-1: none).
  std::vector<int> at(static_cast<size_t>(image.width) * static_cast<size_t>(image.height), -1);
  for (size_t i = 0; i < pixels.size(); ++i) at[static_cast<size_t>(pixels[i])] = static_cast<int>(i);
  OrientedPoints out;
  const double gap2 = o.max_gap_mm * o.max_gap_mm;
  for (size_t i = 0; i < pts.size(); ++i) {
    const int u = pixels[i] % image.width, v = pixels[i] / image.width;
    const Vec3& p = pts[i];
    Vec3 sum = Vec3::Zero();
    Mat3 sum2 = Mat3::Zero();
    int n = 0;
    for (int dv = -o.radius_px; dv <= o.radius_px; ++dv) {
      for (int du = -o.radius_px; du <= o.radius_px; ++du) {
        const int uu = u + du, vv = v + dv;
        if (uu < 0 || vv < 0 || uu >= image.width || vv >= image.height) continue;
        const int j = at[static_cast<size_t>(vv) * static_cast<size_t>(image.width) + static_cast<size_t>(uu)];
        if (j < 0) continue;
        const Vec3 q = pts[static_cast<size_t>(j)] - p;  // relative to p: well conditioned
        if (q.squaredNorm() > gap2) continue;
        sum += q;
        sum2 += q * q.transpose();
        ++n;
      }
    }
    if (n - 1 < o.min_neighbours) continue;
    const Vec3 mean = sum / n;
    const Mat3 cov = sum2 / n - mean * mean.transpose();
    const Eigen::SelfAdjointEigenSolver<Mat3> eig(cov);
    if (!(eig.eigenvalues()(1) > 0.0)) continue;  // neighbours on a line: no plane
    Vec3 normal = eig.eigenvectors().col(0).normalized();
    if (normal.dot(p) > 0.0) normal = -normal;  // towards the camera at the origin
    out.points.push_back(p);
    out.normals.push_back(normal);
  }
  return out;
}

OrientedPoints fuse_point_clouds(const OrientedPoints& cloud1, const OrientedPoints& cloud2,
                                 const RigidTransform& camera2_to_camera1, const FusePointOptions& o) {
  if (cloud1.points.size() != cloud1.normals.size() || cloud2.points.size() != cloud2.normals.size())
    throw InvalidInput("fuse_point_clouds: every point needs one normal");
  if (!(o.voxel_mm > 0.0) || !std::isfinite(o.voxel_mm))
    throw InvalidInput(fmt::format("fuse_point_clouds: voxel {} mm must be a positive number", o.voxel_mm));
  struct Cell {
    Vec3 sum = Vec3::Zero();
    Vec3 normal = Vec3::Zero();
    int count = 0;
  };
  std::map<std::array<int64_t, 3>, Cell> cells;
  const auto add = [&](const Vec3& p, const Vec3& n) {
    const Eigen::Array3d g = (p / o.voxel_mm).array().floor();
    if (!g.allFinite() || (g.abs() > 1e15).any())
      throw InvalidInput(fmt::format("fuse_point_clouds: point ({:.1f}, {:.1f}, {:.1f}) mm is off the voxel grid "
                                     "(not finite, or the voxel is too small)",
                                     p.x(), p.y(), p.z()));
    Cell& c = cells[{static_cast<int64_t>(g(0)), static_cast<int64_t>(g(1)), static_cast<int64_t>(g(2))}];
    c.sum += p;
    c.normal += n;
    ++c.count;
  };
  for (size_t i = 0; i < cloud1.points.size(); ++i) add(cloud1.points[i], cloud1.normals[i]);
  for (size_t i = 0; i < cloud2.points.size(); ++i)
    add(camera2_to_camera1.apply(cloud2.points[i]), camera2_to_camera1.rotation * cloud2.normals[i]);
  OrientedPoints out;
  out.points.reserve(cells.size());
  out.normals.reserve(cells.size());
  for (const auto& [key, c] : cells) {
    const double len = c.normal.norm();
    if (!(len > 1e-6 * c.count)) continue;  // opposite normals cancelled: no orientation
    out.points.push_back(c.sum / c.count);
    out.normals.push_back(c.normal / len);
  }
  return out;
}

}  // namespace knitforge
