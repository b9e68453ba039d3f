#include "knitforge/evaluate/surface_distance.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

#include <fmt/core.h>

#include "knitforge/geometry/mesh_measures.h"
#include "knitforge/util/errors.h"

namespace knitforge {

namespace {

constexpr int kLeafSize = 4;

// Squared distance from p to the box [lo, hi] (0 inside).
// In scalars (the same bits as the Eigen expression, (lo - p).cwiseMax(p -
// hi).cwiseMax(0).squaredNorm()): every closest-point query tests many
// boxes, and the Eigen temporaries dominated body fitting under the
// sanitizers.
double box_distance2(const Vec3& p, const Eigen::Vector3d& lo, const Eigen::Vector3d& hi) {
  const double dx = std::max(std::max(lo.x() - p.x(), p.x() - hi.x()), 0.0);
  const double dy = std::max(std::max(lo.y() - p.y(), p.y() - hi.y()), 0.0);
  const double dz = std::max(std::max(lo.z() - p.z(), p.z() - hi.z()), 0.0);
  return (dx * dx + dy * dy) + dz * dz;
}

}  // namespace

SurfaceBvh::SurfaceBvh(const TriMesh& mesh) {
  const int nf = mesh.num_faces();
  const int nv = mesh.num_vertices();
  if (nf == 0) throw InvalidInput("surface distance: the target surface has no faces");
  tri_.resize(nf);
  normal_.reserve(nf);
  std::vector<Vec3> centroids(nf);
  for (int f = 0; f < nf; ++f) {
    for (int k = 0; k < 3; ++k) {
      const int v = mesh.faces[f][k];
      if (v < 0 || v >= nv) {
        throw InvalidInput(
            fmt::format("surface distance: face {} corner {} is vertex {} (valid: 0..{})", f, k, v, nv - 1));
      }
      if (!mesh.vertices[v].allFinite()) {
        throw InvalidInput(
            fmt::format("surface distance: vertex {} of face {} has a non-finite position", v, f));
      }
    }
  }
  face_ids_.resize(nf);
  std::iota(face_ids_.begin(), face_ids_.end(), 0);
  for (int f = 0; f < nf; ++f) {
    const auto& t = mesh.faces[f];
    centroids[f] = (mesh.vertices[t[0]] + mesh.vertices[t[1]] + mesh.vertices[t[2]]) / 3.0;
  }
  nodes_.reserve(2 * static_cast<size_t>(nf) / kLeafSize + 2);
  build(0, nf, centroids);
  slot_of_face_.resize(nf);
  for (int i = 0; i < nf; ++i) slot_of_face_[face_ids_[i]] = i;
  for (int i = 0; i < nf; ++i) {
    const auto& t = mesh.faces[face_ids_[i]];
    tri_[i] = {mesh.vertices[t[0]], mesh.vertices[t[1]], mesh.vertices[t[2]]};
    normal_.push_back(face_normal(mesh, face_ids_[i]));
  }
  // Node boxes enclose the triangles, filled bottom-up once tri_ is in slot order.
  for (int n = static_cast<int>(nodes_.size()) - 1; n >= 0; --n) {
    Node& node = nodes_[n];
    if (node.left < 0) {
      node.lo = tri_[node.first][0];
      node.hi = node.lo;
      for (int i = node.first; i < node.first + node.count; ++i) {
        for (const Vec3& c : tri_[i]) {
          node.lo = node.lo.cwiseMin(c);
          node.hi = node.hi.cwiseMax(c);
        }
      }
    } else {
      node.lo = nodes_[node.left].lo.cwiseMin(nodes_[node.right].lo);
      node.hi = nodes_[node.left].hi.cwiseMax(nodes_[node.right].hi);
    }
  }
}

// Children get larger indices than their parent, so the bottom-up pass in the
// constructor can fill the boxes in reverse index order.
int SurfaceBvh::build(int first, int count, std::vector<Vec3>& centroids) {
  const int id = static_cast<int>(nodes_.size());
  nodes_.push_back(Node{});
  nodes_[id].first = first;
  nodes_[id].count = count;
  if (count <= kLeafSize) return id;
  Eigen::Vector3d lo = centroids[face_ids_[first]], hi = lo;
  for (int i = first; i < first + count; ++i) {
    lo = lo.cwiseMin(centroids[face_ids_[i]]);
    hi = hi.cwiseMax(centroids[face_ids_[i]]);
  }
  int axis = 0;
  (hi - lo).maxCoeff(&axis);
  const int mid = first + count / 2;
  // Ties broken by face index, so the tree does not depend on the
  // implementation of nth_element.
  std::nth_element(face_ids_.begin() + first, face_ids_.begin() + mid, face_ids_.begin() + first + count,
                   [&](int a, int b) {
                     const double ca = centroids[a][axis], cb = centroids[b][axis];
                     return ca < cb || (ca == cb && a < b);
                   });
  const int left = build(first, mid - first, centroids);
  const int right = build(mid, first + count - mid, centroids);
  nodes_[id].left = left;
  nodes_[id].right = right;
  return id;
}

ClosestPoint SurfaceBvh::closest_point(const Vec3& p, int hint_face) const {
  if (!p.allFinite()) throw InvalidInput("surface distance: the query point is not finite");
  ClosestPoint best;
  double best2 = std::numeric_limits<double>::infinity();
  // Boxes farther than the hint face are pruned from the start; the closest
  // point is at most that far, so every face that could be (or tie with)
  // it is still visited, in the same order: the same result.
  double bound2 = std::numeric_limits<double>::infinity();
  if (hint_face >= 0 && hint_face < num_faces()) {
    const auto& t = tri_[slot_of_face_[hint_face]];
    bound2 = (closest_point_on_triangle(p, t[0], t[1], t[2]) - p).squaredNorm();
  }
  int best_slot_face = std::numeric_limits<int>::max();
  int best_slot = 0;
  int best_feature = 0;
  int stack[128];
  int top = 0;
  stack[top++] = 0;
  while (top > 0) {
    const Node& node = nodes_[stack[--top]];
    if (box_distance2(p, node.lo, node.hi) > std::min(best2, bound2)) continue;
    if (node.left < 0) {
      for (int i = node.first; i < node.first + node.count; ++i) {
        const TrianglePoint c = closest_triangle_point(p, tri_[i][0], tri_[i][1], tri_[i][2]);
        const double d2 = (c.point - p).squaredNorm();
        if (d2 < best2 || (d2 == best2 && face_ids_[i] < best_slot_face)) {
          best2 = d2;
          best.point = c.point;
          best.region = c.region;
          best_feature = c.feature;
          best.face = face_ids_[i];
          best_slot_face = face_ids_[i];
          best_slot = i;
        }
      }
      continue;
    }
    const double dl = box_distance2(p, nodes_[node.left].lo, nodes_[node.left].hi);
    const double dr = box_distance2(p, nodes_[node.right].lo, nodes_[node.right].hi);
    // Push the farther child first so the nearer one is visited first.
    const double limit = std::min(best2, bound2);
    if (dl <= dr) {
      if (dr <= limit) stack[top++] = node.right;
      if (dl <= limit) stack[top++] = node.left;
    } else {
      if (dl <= limit) stack[top++] = node.left;
      if (dr <= limit) stack[top++] = node.right;
    }
  }
  best.distance = std::sqrt(best2);
  best.normal = normal_[best_slot];
  if (best.region == TrianglePoint::Region::Edge) {
    const auto& t = tri_[best_slot];
    const Vec3 e = t[(best_feature + 1) % 3] - t[best_feature];
    if (e.norm() > 0) best.edge = e.normalized();
  }
  return best;
}

Mat3 ClosestPoint::half_squared_distance_hessian() const {
  switch (region) {
    case TrianglePoint::Region::Face:
      return normal * normal.transpose();
    case TrianglePoint::Region::Edge:
      return Mat3::Identity() - edge * edge.transpose();
    case TrianglePoint::Region::Vertex:
      break;
  }
  return Mat3::Identity();
}

std::vector<ClosestPoint> closest_points_on_surface(const TriMesh& surface, std::span<const Vec3> points) {
  for (size_t i = 0; i < points.size(); ++i) {
    if (!points[i].allFinite()) {
      throw InvalidInput(fmt::format("surface distance: query point {} is not finite", i));
    }
  }
  const SurfaceBvh bvh(surface);
  std::vector<ClosestPoint> out(points.size());
  for (size_t i = 0; i < points.size(); ++i) out[i] = bvh.closest_point(points[i]);
  return out;
}

std::vector<double> distances_to_surface(const TriMesh& surface, std::span<const Vec3> points) {
  const std::vector<ClosestPoint> cp = closest_points_on_surface(surface, points);
  std::vector<double> out(cp.size());
  for (size_t i = 0; i < cp.size(); ++i) out[i] = cp[i].distance;
  return out;
}

}  // namespace knitforge
