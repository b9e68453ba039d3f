#include "knitforge/evaluate/surface_distance.h"

#include <cmath>
#include <limits>
#include <random>

#include <gtest/gtest.h>

#include "knitforge/geometry/mesh_measures.h"
#include "knitforge/util/errors.h"

namespace knitforge {
namespace {

// A crumpled random sheet plus a few degenerate triangles.
TriMesh random_sheet(int n, uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1, 1);
  TriMesh m;
  for (int i = 0; i <= n; ++i) {
    for (int j = 0; j <= n; ++j) m.vertices.emplace_back(j + 0.3 * u(rng), i + 0.3 * u(rng), 2 * u(rng));
  }
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j) {
      const int a = i * (n + 1) + j, b = a + 1, c = a + n + 2, d = a + n + 1;
      m.faces.push_back({a, b, c});
      m.faces.push_back({a, c, d});
    }
  }
  m.faces.push_back({0, 0, 5});  // a segment
  m.faces.push_back({7, 7, 7});  // a point
  return m;
}

TEST(SurfaceDistance, MatchesBruteForce) {
  const TriMesh m = random_sheet(30, 1);
  std::mt19937 rng(2);
  std::uniform_real_distribution<double> u(-5, 35), z(-6, 6);
  std::vector<Vec3> pts;
  for (int k = 0; k < 2000; ++k) pts.emplace_back(u(rng), u(rng), z(rng));
  pts.push_back(m.vertices[17]);    // on the surface
  pts.emplace_back(1e4, -3e3, 50);  // far away
  const std::vector<ClosestPoint> cp = closest_points_on_surface(m, pts);
  ASSERT_EQ(cp.size(), pts.size());
  for (size_t i = 0; i < pts.size(); ++i) {
    double best = std::numeric_limits<double>::infinity();
    for (const auto& f : m.faces) {
      best = std::min(best,
                      point_triangle_distance(pts[i], m.vertices[f[0]], m.vertices[f[1]], m.vertices[f[2]]));
    }
    EXPECT_NEAR(cp[i].distance, best, 1e-12) << i;
    // The reported point lies on the reported face at the reported distance.
    ASSERT_GE(cp[i].face, 0);
    const auto& f = m.faces[cp[i].face];
    EXPECT_NEAR(point_triangle_distance(pts[i], m.vertices[f[0]], m.vertices[f[1]], m.vertices[f[2]]),
                cp[i].distance, 1e-12);
    EXPECT_NEAR((cp[i].point - pts[i]).norm(), cp[i].distance, 1e-9);
  }
  EXPECT_EQ(cp[pts.size() - 2].distance, 0.0);
  const std::vector<double> d = distances_to_surface(m, pts);
  for (size_t i = 0; i < pts.size(); ++i) EXPECT_EQ(d[i], cp[i].distance);
}

TEST(SurfaceDistance, SingleTriangleAndDegenerateOnly) {
  TriMesh m;
  m.vertices = {Vec3(0, 0, 0), Vec3(4, 0, 0), Vec3(0, 4, 0)};
  m.faces = {{0, 1, 2}};
  const SurfaceBvh bvh(m);
  EXPECT_EQ(bvh.num_faces(), 1);
  EXPECT_DOUBLE_EQ(bvh.closest_point(Vec3(1, 1, 3)).distance, 3.0);
  EXPECT_DOUBLE_EQ(bvh.closest_point(Vec3(-3, 0, 4)).distance, 5.0);
  TriMesh seg;
  seg.vertices = {Vec3(0, 0, 0), Vec3(2, 0, 0)};
  seg.faces = {{0, 1, 1}};
  EXPECT_DOUBLE_EQ(SurfaceBvh(seg).closest_point(Vec3(1, 0, 2)).distance, 2.0);
}

TEST(SurfaceDistance, BadInputThrows) {
  TriMesh m;
  m.vertices = {Vec3(0, 0, 0), Vec3(4, 0, 0), Vec3(0, 4, 0)};
  EXPECT_THROW(SurfaceBvh{m}, InvalidInput);  // no faces
  m.faces = {{0, 1, 3}};
  EXPECT_THROW(SurfaceBvh{m}, InvalidInput);
  m.faces = {{0, 1, 2}};
  m.vertices[1].y() = NAN;
  EXPECT_THROW(SurfaceBvh{m}, InvalidInput);
  m.vertices[1].y() = 0;
  const std::vector<Vec3> bad = {Vec3(0, 0, 0), Vec3(NAN, 0, 0)};
  EXPECT_THROW(distances_to_surface(m, bad), InvalidInput);
  EXPECT_THROW(SurfaceBvh(m).closest_point(Vec3(INFINITY, 0, 0)), InvalidInput);
}

}  // namespace
}  // namespace knitforge
