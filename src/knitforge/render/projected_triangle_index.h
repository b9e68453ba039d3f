#pragma once
/// \file projected_triangle_index.h
/// Ray tests for an orthographic view along z: a bounding-volume hierarchy
/// over triangles given in NDC (camera.h), answering "which triangle does
/// the ray through image point (x, y) hit first?" (seed §1.A.2, the ray tests
/// of Alg. 1.2). Because the camera transformation is projective, a ray from
/// the camera is a line parallel to z in NDC, so the test is a 2D
/// point-in-triangle query plus a depth comparison.
///
/// Built by recursive median splits of the centroids along the longer image
/// axis (leaves of at most 4 triangles); a query descends into boxes that
/// contain the point and whose nearest depth can beat the best hit so far.

#include <array>
#include <vector>

#include "knitforge/geometry/vec.h"

namespace knitforge {

class ProjectedTriangleIndex {
 public:
  /// The first triangle hit by a ray.
  struct Hit {
    int triangle = -1;                ///< index into the triangles given to the constructor, -1 = no hit
    double depth = 0.0;               ///< NDC depth of the hit point
    Vec3 barycentric = Vec3::Zero();  ///< of the hit point in that triangle
  };

  /// `triangles`: NDC corners of each triangle (any orientation; triangles
  /// whose projection has zero area are never hit).
  /// \throw InvalidInput when a corner is not finite (naming the triangle).
  explicit ProjectedTriangleIndex(std::vector<std::array<Vec3, 3>> triangles);

  /// The nearest (smallest depth) triangle whose projection contains (x, y),
  /// boundary included up to a relative tolerance of 1e-12. Ties in depth go
  /// to the smaller triangle index.
  Hit first_hit(const Vec2& p) const;

  int size() const { return static_cast<int>(tri_.size()); }
  const std::array<Vec3, 3>& triangle(int i) const { return tri_[static_cast<size_t>(i)]; }

 private:
  struct Node {
    Vec3 lo = Vec3::Zero(), hi = Vec3::Zero();
    int left = -1, right = -1;  ///< children, -1 for a leaf
    int first = 0, count = 0;   ///< leaf: range in order_
  };
  int build(int first, int count, const std::vector<Vec2>& centroids);
  std::vector<std::array<Vec3, 3>> tri_;
  std::vector<int> order_;
  std::vector<Node> nodes_;
};

}  // namespace knitforge
