// Collision-free steps (collision_free_step.h) with one vertex and one or two
// triangles: a move through a still triangle, a triangle swept through a
// still vertex, each stopped before the crossing with a tenth of the start
// distance kept; a vertex resting on a still face next to a fast face far
// away is not held back; per-vertex fractions.
#include "knitforge/sim/collision_free_step.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

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

// Many vertices (enough for the threaded search, ranges on all hardware
// threads): the fraction of the whole set is the smallest of the vertices'
// own fractions, each found alone, wherever the limiting vertex lies (the
// first, a middle or the last range), for a still and a moving body.
TEST(CollisionFreeStep, ManyVerticesGiveTheSmallestOfTheirOwnFractions) {
  const TriMesh m = floor_triangles(true);
  const KinematicBody body(m);
  std::vector<Vec3> end = m.vertices;
  for (int k = 0; k < 3; ++k) end[k] += Vec3(0, 0, 0.5);  // the floor rises 0.5 mm
  const int n = 5000;
  Eigen::VectorXd x0(3 * n), x1(3 * n);
  for (int v = 0; v < n; ++v) {
    // Scattered over the floor at 1 to 3 mm, drifting down by 0.5 to 1.5 mm.
    const double a = 0.001 * v;
    x0.segment<3>(3 * v) = Vec3(-4 + 8 * std::fmod(7.3 * a, 1.0), -4 + 8 * std::fmod(3.1 * a, 1.0), 1 + 2 * std::fmod(5.7 * a, 1.0));
    x1.segment<3>(3 * v) = x0.segment<3>(3 * v) - Vec3(0, 0, 0.5 + std::fmod(11.9 * a, 1.0));
  }
  for (const int limiting : {0, n / 2, n - 1}) {
    Eigen::VectorXd y1 = x1;
    y1.segment<3>(3 * limiting) = x0.segment<3>(3 * limiting) - Vec3(0, 0, 4.0);  // through the floor
    double still = 1.0, moving = 1.0;
    for (int v = 0; v < n; ++v) {
      const Eigen::VectorXd a = x0.segment<3>(3 * v), b = y1.segment<3>(3 * v);
      still = std::min(still, collision_free_step(body, a, b));
      moving = std::min(moving, collision_free_step(body, end, a, b));
    }
    ASSERT_LT(still, 1.0);
    EXPECT_EQ(collision_free_step(body, x0, y1), still) << "limiting vertex " << limiting;
    EXPECT_EQ(collision_free_step(body, end, x0, y1), moving) << "limiting vertex " << limiting;
    std::vector<double> per_vertex;
    EXPECT_EQ(collision_free_step(body, end, x0, y1, {}, &per_vertex), moving);
    ASSERT_EQ(per_vertex.size(), static_cast<size_t>(n));
    for (const int v : {0, 1, n / 2, limiting, n - 1}) {
      const Eigen::VectorXd a = x0.segment<3>(3 * v), b = y1.segment<3>(3 * v);
      std::vector<double> own;
      EXPECT_EQ(per_vertex[v], collision_free_step(body, end, a, b, {}, &own)) << "vertex " << v;
    }
  }
}

}  // namespace
}  // namespace knitforge
