// Collision-free steps (collision_free_step.h) with one vertex and one or two
// triangles: a move through a still triangle, a triangle swept through a
// still vertex, each stopped before the crossing with a tenth of the start
// distance kept; a vertex resting on a still face next to a fast face far
// away is not held back; per-vertex fractions.
#include "knitforge/sim/collision_free_step.h"

#include <gtest/gtest.h>

#include "knitforge/geometry/mesh_measures.h"

namespace knitforge {
namespace {

// A triangle in the plane z = 0 around the origin, and a second one far away
// (x = 100) when `two`.
TriMesh floor_triangles(bool two) {
  TriMesh m;
  m.vertices = {{-10, -10, 0}, {10, -10, 0}, {0, 10, 0}};
  m.faces = {{0, 1, 2}};
  if (two) {
    m.vertices.insert(m.vertices.end(), {{90, -10, 0}, {110, -10, 0}, {100, 10, 0}});
    m.faces.push_back({3, 4, 5});
  }
  return m;
}

Eigen::VectorXd point(double x, double y, double z) { return Eigen::Vector3d(x, y, z); }

double distance_to(const TriMesh& m, const std::vector<Vec3>& pos, int f, const Vec3& p) {
  const auto& t = m.faces[f];
  return (closest_point_on_triangle(p, pos[t[0]], pos[t[1]], pos[t[2]]) - p).norm();
}

TEST(CollisionFreeStep, StopsAVertexBeforeAStillTriangle) {
  const KinematicBody body(floor_triangles(false));
  const Eigen::VectorXd a = point(0, 0, 2), b = point(0, 0, -2);  // straight through, 2 mm each side
  const double t = collision_free_step(body, a, b);
  // Stopped above the floor, keeping a tenth of the 2 mm (4 t <= 1.8), not too early.
  EXPECT_GT(t, 0.25);
  EXPECT_LE(4 * t, 1.8 + 1e-12);
  // A move that stays well away is free.
  EXPECT_EQ(collision_free_step(body, a, point(0, 0, 5)), 1.0);
}

TEST(CollisionFreeStep, StopsATriangleSweptThroughAStillVertex) {
  const TriMesh m = floor_triangles(false);
  const KinematicBody body(m);
  std::vector<Vec3> up;
  for (const Vec3& v : m.vertices) up.push_back(v + Vec3(0, 0, 4));  // rises 4 mm through the vertex at z = 1
  const Eigen::VectorXd x = point(0, 0, 1);
  const double t = collision_free_step(body, up, x, x);
  ASSERT_LT(t, 1.0);
  EXPECT_GT(t, 0.1);
  std::vector<Vec3> at;
  for (size_t k = 0; k < m.vertices.size(); ++k) at.push_back(m.vertices[k] + t * (up[k] - m.vertices[k]));
  EXPECT_GE(distance_to(m, at, 0, Vec3(0, 0, 1)), 0.1 - 1e-12);  // a tenth of the 1 mm kept
  // The vertex moving up with the triangle, ahead of it: free.
  EXPECT_EQ(collision_free_step(body, up, x, point(0, 0, 5)), 1.0);
}

TEST(CollisionFreeStep, AVertexOnAStillFaceIsNotHeldBackByAFastFaceFarAway) {
  const TriMesh m = floor_triangles(true);
  const KinematicBody body(m);
  std::vector<Vec3> end = m.vertices;
  for (int k = 3; k < 6; ++k) end[k] += Vec3(0, 30, 0);  // the far triangle slides 30 mm in its plane
  Eigen::VectorXd x(6);
  x << 0, 0, 0.01, 100, 40, 30;  // 0.01 mm above the still triangle; the second vertex far from both
  std::vector<double> per_vertex;
  EXPECT_EQ(collision_free_step(body, end, x, x, {}, &per_vertex), 1.0);
  EXPECT_EQ(per_vertex, std::vector<double>({1.0, 1.0}));
  // The second vertex in the far triangle's way, 1 mm above its end position: only it is limited.
  x.segment<3>(3) = Vec3(100, 25, 0.5);
  const double t = collision_free_step(body, end, x, x, {}, &per_vertex);
  EXPECT_EQ(per_vertex[0], 1.0);
  EXPECT_LT(per_vertex[1], 1.0);
  EXPECT_EQ(t, per_vertex[1]);
  // Skipped vertices count as free.
  EXPECT_EQ(collision_free_step(body, end, x, x, {0, 1}, &per_vertex), 1.0);
  EXPECT_EQ(per_vertex[1], 1.0);
}

}  // namespace
}  // namespace knitforge
