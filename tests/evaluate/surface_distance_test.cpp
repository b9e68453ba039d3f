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

// A hint face (ICP's last match) only prunes: the answer is the same face,
// point and distance as without one, for good, bad, tied and invalid hints.
TEST(SurfaceDistance, HintGivesTheSameAnswer) {
  const TriMesh m = random_sheet(30, 3);
  const SurfaceBvh bvh(m);
  std::mt19937 rng(4);
  std::uniform_real_distribution<double> u(-5, 35), z(-6, 6);
  std::uniform_int_distribution<int> face(0, m.num_faces() - 1);
  for (int k = 0; k < 2000; ++k) {
    const Vec3 p(u(rng), u(rng), z(rng));
    const ClosestPoint plain = bvh.closest_point(p);
    for (int hint : {plain.face, face(rng), face(rng), -1, m.num_faces(), plain.face ^ 1}) {
      const ClosestPoint hinted = bvh.closest_point(p, hint);
      EXPECT_EQ(hinted.face, plain.face) << k << " hint " << hint;
      EXPECT_EQ(hinted.distance, plain.distance);
      EXPECT_EQ(hinted.point, plain.point);
      EXPECT_EQ(hinted.normal, plain.normal);
    }
  }
  // Exact ties: above the shared diagonal of a flat square, both triangles
  // are closest; the smaller face index wins, whichever one is the hint.
  TriMesh sq;
  sq.vertices = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(1, 1, 0), Vec3(0, 1, 0)};
  sq.faces = {{0, 1, 2}, {0, 2, 3}};
  const SurfaceBvh tie(sq);
  for (int hint : {-1, 0, 1}) {
    const ClosestPoint c = tie.closest_point(Vec3(0.5, 0.5, 2.0), hint);
    EXPECT_EQ(c.face, 0) << "hint " << hint;
    EXPECT_EQ(c.distance, 2.0);
  }
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

// The gradient of half the squared distance is p - closest(p); its
// derivative by central differences must be the Hessian the closest point
// reports, for query points whose closest point lies inside a face, on an
// edge and at a corner.
TEST(SurfaceDistance, HalfSquaredDistanceHessianMatchesFiniteDifferences) {
  TriMesh m;
  m.vertices = {Vec3(0, 0, 0), Vec3(10, 0, 0), Vec3(0, 10, 0), Vec3(10, 10, 4)};
  m.faces = {{0, 1, 2}, {1, 3, 2}};
  const SurfaceBvh bvh(m);
  using R = TrianglePoint::Region;
  const struct {
    Vec3 p;
    R region;
  } cases[] = {{Vec3(2, 3, 5), R::Face}, {Vec3(5, -4, 3), R::Edge}, {Vec3(-3, -2, 1), R::Vertex},
               {Vec3(12, 5, -2), R::Edge}};
  for (const auto& c : cases) {
    const ClosestPoint cp = bvh.closest_point(c.p);
    EXPECT_EQ(cp.region, c.region) << c.p.transpose();
    const Mat3 H = cp.half_squared_distance_hessian();
    const double h = 1e-4;
    for (int j = 0; j < 3; ++j) {
      const Vec3 d = h * Vec3::Unit(j);
      const Vec3 gp = (c.p + d) - bvh.closest_point(c.p + d).point;
      const Vec3 gm = (c.p - d) - bvh.closest_point(c.p - d).point;
      EXPECT_LT(((gp - gm) / (2 * h) - H.col(j)).norm(), 1e-6) << c.p.transpose() << " column " << j;
    }
  }
}

}  // namespace
}  // namespace knitforge
