#include "knitforge/geometry/mesh_measures.h"

#include <cmath>
#include <limits>

#include <gtest/gtest.h>

#include "geometry/test_meshes.h"
#include "knitforge/util/errors.h"

namespace knitforge {
namespace {

TEST(MeshMeasures, AreasNormalsOfAGrid) {
  const TriMesh m = test::square_grid(3, 2.0);
  EXPECT_DOUBLE_EQ(total_area(m), 36.0);
  for (double a : face_areas(m)) EXPECT_DOUBLE_EQ(a, 2.0);
  for (const Vec3& n : face_normals(m)) EXPECT_EQ(n, Vec3(0, 0, 1));
  for (const Vec3& n : vertex_normals(m)) EXPECT_NEAR((n - Vec3(0, 0, 1)).norm(), 0.0, 1e-15);
  const BoundingBox box = bounding_box(m);
  EXPECT_EQ(box.min, Vec3(0, 0, 0));
  EXPECT_EQ(box.max, Vec3(6, 6, 0));
  EXPECT_EQ(box.center(), Vec3(3, 3, 0));
  const EdgeLengthStats s = edge_length_stats(m);
  EXPECT_EQ(s.count, 33);
  EXPECT_DOUBLE_EQ(s.min, 2.0);
  EXPECT_DOUBLE_EQ(s.max, 2.0 * std::sqrt(2.0));
  EXPECT_NEAR(s.mean, (24 * 2.0 + 9 * 2.0 * std::sqrt(2.0)) / 33.0, 1e-12);
}

TEST(MeshMeasures, TetrahedronVertexNormalsPointOutward) {
  const TriMesh m = test::tetrahedron();
  const auto n = vertex_normals(m);
  for (int v = 0; v < 4; ++v) EXPECT_NEAR((n[v] - m.vertices[v].normalized()).norm(), 0.0, 1e-12);
  // Regular tetrahedron with edge 2√2: area 4 · (√3/4) · 8.
  EXPECT_NEAR(total_area(m), 8.0 * std::sqrt(3.0), 1e-12);
  EXPECT_EQ(face_normal(TriMesh{{{0, 0, 0}, {1, 0, 0}, {2, 0, 0}}, {{0, 1, 2}}}, 0), Vec3::Zero());
  EXPECT_THROW(bounding_box(TriMesh{}), InvalidInput);
}

TEST(MeshMeasures, ClosestPointOnTriangleMatchesDenseSampling) {
  const Vec3 a(0, 0, 0), b(4, 0, 0), c(1, 3, 0);
  const Vec3 queries[] = {{1, 1, 2}, {-2, -1, 1}, {6, -1, 0}, {2, -3, -1}, {3, 3, 1}, {0, 5, 0}, {-1, 1, 0}};
  for (const Vec3& p : queries) {
    double best = std::numeric_limits<double>::infinity();
    const int n = 400;
    for (int i = 0; i <= n; ++i) {
      for (int j = 0; i + j <= n; ++j) {
        const Vec3 q = a + (b - a) * (double(i) / n) + (c - a) * (double(j) / n);
        best = std::min(best, (q - p).norm());
      }
    }
    const Vec3 q = closest_point_on_triangle(p, a, b, c);
    EXPECT_NEAR((q - p).norm(), best, 0.02) << p.transpose();
    EXPECT_LE((q - p).norm(), best + 1e-12);
    EXPECT_DOUBLE_EQ(point_triangle_distance(p, a, b, c), (q - p).norm());
  }
  // Interior projection is exact.
  EXPECT_NEAR((closest_point_on_triangle(Vec3(1, 1, 5), a, b, c) - Vec3(1, 1, 0)).norm(), 0.0, 1e-15);
  // Degenerate triangle (a segment).
  EXPECT_NEAR(point_triangle_distance(Vec3(1, 1, 0), a, b, Vec3(2, 0, 0)), 1.0, 1e-15);
  EXPECT_EQ(closest_point_on_segment(Vec3(9, 1, 0), a, b), b);
}

}  // namespace
}  // namespace knitforge
