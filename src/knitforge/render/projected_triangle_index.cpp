#include "knitforge/render/projected_triangle_index.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

#include <fmt/core.h>

#include "knitforge/util/errors.h"

namespace knitforge {

ProjectedTriangleIndex::ProjectedTriangleIndex(std::vector<std::array<Vec3, 3>> triangles)
    : tri_(std::move(triangles)) {
  std::vector<Vec2> centroids(tri_.size());
  for (size_t i = 0; i < tri_.size(); ++i) {
    for (const Vec3& c : tri_[i]) {
      if (!c.allFinite()) throw InvalidInput(fmt::format("projected triangle {} has a non-finite corner", i));
    }
    centroids[i] = ((tri_[i][0] + tri_[i][1] + tri_[i][2]) / 3.0).head<2>();
  }
  order_.resize(tri_.size());
  std::iota(order_.begin(), order_.end(), 0);
  if (!tri_.empty()) {
    nodes_.reserve(tri_.size() / 2 + 1);
    build(0, static_cast<int>(tri_.size()), centroids);
  }
}

int ProjectedTriangleIndex::build(int first, int count, const std::vector<Vec2>& centroids) {
  const int id = static_cast<int>(nodes_.size());
  nodes_.emplace_back();
  Vec3 lo = Vec3::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
  for (int i = first; i < first + count; ++i) {
    for (const Vec3& c : tri_[static_cast<size_t>(order_[static_cast<size_t>(i)])]) {
      lo = lo.cwiseMin(c);
      hi = hi.cwiseMax(c);
    }
  }
  nodes_[static_cast<size_t>(id)].lo = lo;
  nodes_[static_cast<size_t>(id)].hi = hi;
  if (count <= 4) {
    nodes_[static_cast<size_t>(id)].first = first;
    nodes_[static_cast<size_t>(id)].count = count;
    return id;
  }
  const int axis = (hi.x() - lo.x()) >= (hi.y() - lo.y()) ? 0 : 1;
  const int half = count / 2;
  auto b = order_.begin() + first;
  std::nth_element(b, b + half, b + count, [&](int a, int c) {
    const double ka = centroids[static_cast<size_t>(a)][axis], kc = centroids[static_cast<size_t>(c)][axis];
    return ka < kc || (ka == kc && a < c);
  });
  const int l = build(first, half, centroids);
  const int r = build(first + half, count - half, centroids);
  nodes_[static_cast<size_t>(id)].left = l;
  nodes_[static_cast<size_t>(id)].right = r;
  return id;
}

ProjectedTriangleIndex::Hit ProjectedTriangleIndex::first_hit(const Vec2& p) const {
  Hit best;
  if (nodes_.empty()) return best;
  int stack[128];
  int top = 0;
  stack[top++] = 0;
  while (top > 0) {
    const Node& n = nodes_[static_cast<size_t>(stack[--top])];
    if (p.x() < n.lo.x() || p.x() > n.hi.x() || p.y() < n.lo.y() || p.y() > n.hi.y()) continue;
    if (best.triangle >= 0 && n.lo.z() > best.depth) continue;
    if (n.left >= 0) {
      if (top + 2 > 128) continue;  // depth is O(log n); cannot happen for < 2^60 triangles
      stack[top++] = n.right;
      stack[top++] = n.left;
      continue;
    }
    for (int i = n.first; i < n.first + n.count; ++i) {
      const int t = order_[static_cast<size_t>(i)];
      const auto& c = tri_[static_cast<size_t>(t)];
      const double x0 = c[0].x(), y0 = c[0].y();
      const double e1x = c[1].x() - x0, e1y = c[1].y() - y0, e2x = c[2].x() - x0, e2y = c[2].y() - y0;
      const double det = e1x * e2y - e1y * e2x;
      if (det == 0.0) continue;
      const double px = p.x() - x0, py = p.y() - y0;
      const double u = (px * e2y - py * e2x) / det;
      const double v = (e1x * py - e1y * px) / det;
      const double tol = -1e-12;
      if (u < tol || v < tol || 1.0 - u - v < tol) continue;
      const double depth = (1.0 - u - v) * c[0].z() + u * c[1].z() + v * c[2].z();
      if (best.triangle < 0 || depth < best.depth || (depth == best.depth && t < best.triangle)) {
        best.triangle = t;
        best.depth = depth;
        best.barycentric = Vec3(1.0 - u - v, u, v);
      }
    }
  }
  return best;
}

}  // namespace knitforge
