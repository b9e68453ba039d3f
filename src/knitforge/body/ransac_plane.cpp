#include "knitforge/body/ransac_plane.h"

#include <algorithm>
#include <cmath>
#include <random>

#include <Eigen/Eigenvalues>
#include <fmt/core.h>

#include "knitforge/util/errors.h"

namespace knitforge {

namespace {

// Indices of the points within `distance` of the plane.
std::vector<int> inliers_of(std::span<const Vec3> points, const Vec3& n, const Vec3& p, double distance) {
  std::vector<int> in;
  for (size_t i = 0; i < points.size(); ++i)
    if (std::abs(n.dot(points[i] - p)) <= distance) in.push_back(static_cast<int>(i));
  return in;
}

}  // namespace

RansacPlane fit_plane(std::span<const Vec3> points) {
  if (points.size() < 3) throw InvalidInput(fmt::format("fit_plane: {} points; a plane needs at least 3", points.size()));
  Vec3 c = Vec3::Zero();
  for (const Vec3& q : points) c += q;
  c /= static_cast<double>(points.size());
  Mat3 cov = Mat3::Zero();
  for (const Vec3& q : points) cov += (q - c) * (q - c).transpose();
  const Eigen::SelfAdjointEigenSolver<Mat3> eig(cov);
  // Eigenvalues ascending: the plane needs two directions of spread.
  if (!(eig.eigenvalues()(1) > 1e-12 * std::max(1.0, eig.eigenvalues()(2))))
    throw InvalidInput(fmt::format("fit_plane: the {} points are collinear or coincide; no plane through them",
                                   points.size()));
  RansacPlane plane;
  plane.normal = eig.eigenvectors().col(0).normalized();
  if (plane.normal.dot(c) > 0.0) plane.normal = -plane.normal;
  plane.point = c;
  double s2 = 0.0;
  for (const Vec3& q : points) s2 += std::pow(plane.normal.dot(q - c), 2);
  plane.rms_mm = std::sqrt(s2 / static_cast<double>(points.size()));
  plane.inliers.resize(points.size());
  for (size_t i = 0; i < points.size(); ++i) plane.inliers[i] = static_cast<int>(i);
  plane.inlier_fraction = 1.0;
  return plane;
}

RansacPlane ransac_plane(std::span<const Vec3> points, const RansacPlaneOptions& o) {
  if (points.size() < 3) throw InvalidInput(fmt::format("ransac_plane: {} points; a plane needs at least 3", points.size()));
  if (!(o.inlier_distance_mm > 0.0) || o.max_iterations < 1 || !(o.confidence > 0.0 && o.confidence < 1.0) ||
      o.refinements < 0 || !(o.min_inlier_fraction >= 0.0 && o.min_inlier_fraction <= 1.0))
    throw InvalidInput("ransac_plane: options out of range (inlier distance > 0, iterations >= 1, 0 < confidence < 1, "
                       "refinements >= 0, inlier fraction in [0, 1])");
  const auto n_points = static_cast<int>(points.size());
  std::mt19937 rng(o.seed);
  std::uniform_int_distribution<int> pick(0, n_points - 1);
  const double d = o.inlier_distance_mm;
  int best_count = 0;
  Vec3 best_n = Vec3::UnitZ(), best_p = Vec3::Zero();
  int needed = o.max_iterations, it = 0;
  for (; it < needed; ++it) {
    const int a = pick(rng), b = pick(rng), c = pick(rng);
    const Vec3 n = (points[static_cast<size_t>(b)] - points[static_cast<size_t>(a)])
                       .cross(points[static_cast<size_t>(c)] - points[static_cast<size_t>(a)]);
    const double len = n.norm();
    if (!(len > 1e-9)) continue;  // a degenerate sample (repeated or collinear points)
    const Vec3 nu = n / len;
    const Vec3& p = points[static_cast<size_t>(a)];
    int count = 0;
    for (const Vec3& q : points) count += std::abs(nu.dot(q - p)) <= d ? 1 : 0;
    if (count > best_count) {
      best_count = count;
      best_n = nu;
      best_p = p;
      const double w = static_cast<double>(count) / n_points;
      const double miss = 1.0 - w * w * w;
      if (miss <= 0.0) {
        needed = it + 1;
      } else {
        const double n_needed = std::ceil(std::log(1.0 - o.confidence) / std::log(miss));
        if (n_needed < needed) needed = std::max(it + 1, static_cast<int>(n_needed));
      }
    }
  }
  const auto too_few = [&](size_t count) {
    return static_cast<int>(count) < std::max(3, o.min_inliers) ||
           static_cast<double>(count) < o.min_inlier_fraction * n_points;
  };
  const auto no_plane = [&](size_t count) {
    return InvalidInput(fmt::format(
        "no plane found: the best plane of {} hypotheses holds {} of the {} points within {} mm ({:.0f} %); it needs "
        "at least {} points and {:.0f} % (crop the depth range to the board, or check the noise)",
        it, count, n_points, d, 100.0 * static_cast<double>(count) / n_points, std::max(3, o.min_inliers),
        100.0 * o.min_inlier_fraction));
  };
  if (too_few(static_cast<size_t>(best_count))) throw no_plane(static_cast<size_t>(best_count));
  std::vector<int> in = inliers_of(points, best_n, best_p, d);
  RansacPlane plane;
  for (int r = 0;; ++r) {
    std::vector<Vec3> sel(in.size());
    for (size_t i = 0; i < in.size(); ++i) sel[i] = points[static_cast<size_t>(in[i])];
    plane = fit_plane(sel);
    if (r == o.refinements) break;
    std::vector<int> next = inliers_of(points, plane.normal, plane.point, d);
    if (too_few(next.size())) throw no_plane(next.size());
    if (next == in) break;
    in = std::move(next);
  }
  plane.inliers = std::move(in);  // the points the plane was fitted to
  plane.inlier_fraction = static_cast<double>(plane.inliers.size()) / n_points;
  plane.iterations = it;
  return plane;
}

}  // namespace knitforge
