#include "knitforge/geometry/shape_up.h"

#include <gtest/gtest.h>

#include <cmath>

#include <Eigen/Geometry>

#include "knitforge/util/errors.h"

using namespace knitforge;

namespace {

// An n x n grid of unit squares with targets 1 x 1, started from a
// deformed, non-planar layout.
struct Grid {
  std::vector<Vec3> start;
  ShapeUpPolygons poly;
};
Grid grid(int n, double noise) {
  Grid g;
  for (int i = 0; i <= n; ++i) {
    for (int j = 0; j <= n; ++j) {
      g.start.emplace_back(j * (1 + noise * std::sin(3.0 * i + j)), i * (1 + noise * std::cos(i - 2.0 * j)),
                           noise * std::sin(1.3 * i * j));
    }
  }
  const std::vector<Vec3> sq = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(1, 1, 0), Vec3(0, 1, 0)};
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j) {
      const int a = i * (n + 1) + j;
      g.poly.add({a, a + 1, a + n + 2, a + n + 1}, sq, 1.0);
    }
  }
  return g;
}

}  // namespace

TEST(ShapeUp, SinglePolygonReachesItsTargetExactly) {
  ShapeUpPolygons p;
  // A non-planar target (tetrahedron corners): exercises the SVD path.
  p.add({0, 1, 2, 3}, {Vec3(0, 0, 0), Vec3(2, 0, 0), Vec3(0, 3, 0), Vec3(0, 0, 1)}, 2.0);
  const std::vector<Vec3> start = {Vec3(1, 1, 1), Vec3(2, 1.5, 1), Vec3(1, 4, 0.5), Vec3(0.5, 1, 2)};
  const ShapeUpResult r = shape_up(start, p);
  EXPECT_TRUE(r.converged);
  EXPECT_LE(r.energy.back(), 1e-18);
  EXPECT_EQ(r.positions[0], start[0]);  // the fixed vertex
  EXPECT_NEAR((r.positions[1] - r.positions[0]).norm(), 2.0, 1e-8);
  EXPECT_NEAR((r.positions[2] - r.positions[0]).norm(), 3.0, 1e-8);
  EXPECT_NEAR((r.positions[3] - r.positions[0]).norm(), 1.0, 1e-8);
  // Proper rotation, not a reflection: the signed volume keeps its sign.
  const double vol = (r.positions[1] - r.positions[0]).cross(r.positions[2] - r.positions[0]).dot(r.positions[3] - r.positions[0]);
  EXPECT_NEAR(vol, 6.0, 1e-7);
}

TEST(ShapeUp, EnergyIsNonIncreasingAndGridBecomesRigid) {
  const Grid g = grid(8, 0.2);
  for (int depth : {0, 5}) {
    SCOPED_TRACE(depth);
    ShapeUpOptions o;
    o.max_iterations = 3000;
    o.tolerance = 1e-13;
    o.anderson_depth = depth;
    const ShapeUpResult r = shape_up(g.start, g.poly, o);
    ASSERT_GE(r.energy.size(), 3u);
    EXPECT_EQ(static_cast<int>(r.energy.size()), r.iterations + 1);
    for (size_t k = 1; k < r.energy.size(); ++k) EXPECT_LE(r.energy[k], r.energy[k - 1] * (1 + 1e-12)) << k;
    EXPECT_LT(r.energy.back(), 1e-6 * r.energy.front());
    EXPECT_EQ(r.positions[0], g.start[0]);
    // Every edge close to unit length.
    for (int f = 0; f < g.poly.num_polygons(); ++f) {
      for (int k = 0; k < 4; ++k) {
        const int a = g.poly.vertices[4 * f + k], b = g.poly.vertices[4 * f + (k + 1) % 4];
        EXPECT_NEAR((r.positions[a] - r.positions[b]).norm(), 1.0, 1e-3);
      }
    }
  }
}

TEST(ShapeUp, AndersonAccelerationNeedsFewerIterations) {
  const Grid g = grid(12, 0.3);
  ShapeUpOptions o;
  o.max_iterations = 40;
  o.tolerance = 0;
  o.anderson_depth = 0;
  const double plain = shape_up(g.start, g.poly, o).energy.back();
  o.anderson_depth = 5;
  const double accelerated = shape_up(g.start, g.poly, o).energy.back();
  EXPECT_LT(accelerated, plain);
}

TEST(ShapeUp, SolverIsReusableAndEnergyMatches) {
  const Grid g = grid(4, 0.1);
  const ShapeUpSolver solver(static_cast<int>(g.start.size()), g.poly);
  ShapeUpOptions o;
  o.max_iterations = 3;
  const ShapeUpResult a = solver.solve(g.start, o), b = solver.solve(g.start, o);
  EXPECT_EQ(a.positions, b.positions);
  EXPECT_EQ(a.iterations, 3);
  EXPECT_FALSE(a.converged);
  EXPECT_DOUBLE_EQ(solver.energy(a.positions), a.energy.back());
  EXPECT_DOUBLE_EQ(solver.energy(g.start), a.energy.front());
}

TEST(ShapeUp, TwoComponentsAreEachPinned) {
  ShapeUpPolygons p;
  const std::vector<Vec3> tri = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0)};
  p.add({0, 1, 2}, tri, 1.0);
  p.add({3, 4, 5}, tri, 1.0);
  const std::vector<Vec3> start = {Vec3(0, 0, 0), Vec3(2, 0, 0), Vec3(0, 2, 0),
                                   Vec3(10, 0, 0), Vec3(10.5, 0, 0), Vec3(10, 0.5, 0)};
  const ShapeUpResult r = shape_up(start, p);
  EXPECT_EQ(r.positions[0], start[0]);
  EXPECT_EQ(r.positions[3], start[3]);
  EXPECT_NEAR((r.positions[4] - r.positions[3]).norm(), 1.0, 1e-6);
  EXPECT_NEAR((r.positions[1] - r.positions[0]).norm(), 1.0, 1e-6);
}

TEST(ShapeUp, RejectsBadInput) {
  ShapeUpPolygons p;
  EXPECT_THROW(p.add({0, 1}, {Vec3::Zero()}, 1.0), InvalidInput);
  p.add({0, 1, 2}, {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0)}, 1.0);
  EXPECT_THROW(ShapeUpSolver(2, p), InvalidInput);  // vertex 2 out of range
  ShapeUpPolygons rep;
  rep.add({0, 1, 1}, {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0)}, 1.0);
  EXPECT_THROW(ShapeUpSolver(3, rep), InvalidInput);
  ShapeUpPolygons w = p;
  w.weights[0] = 0;
  EXPECT_THROW(ShapeUpSolver(3, w), InvalidInput);
  // A fixed set that leaves the second component's translation free.
  ShapeUpPolygons two = p;
  two.add({3, 4, 5}, {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0)}, 1.0);
  EXPECT_THROW(ShapeUpSolver(6, two, {0}), InvalidInput);
  EXPECT_NO_THROW(ShapeUpSolver(6, two, {0, 4}));
  const ShapeUpSolver s(3, p);
  EXPECT_THROW(s.solve({Vec3::Zero(), Vec3::Zero()}), InvalidInput);
  EXPECT_THROW(s.solve({Vec3::Zero(), Vec3(std::nan(""), 0, 0), Vec3::Zero()}), InvalidInput);
}
