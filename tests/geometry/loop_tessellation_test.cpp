#include "knitforge/geometry/loop_tessellation.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <vector>

#include "knitforge/geometry/halfedges.h"
#include "knitforge/util/errors.h"

using namespace knitforge;

namespace {

std::vector<Vec3> circle(double r, int n, double phase = 0.0, double z = 0.0) {
  std::vector<Vec3> out;
  for (int i = 0; i < n; ++i) {
    const double t = phase + 2.0 * std::numbers::pi * i / n;
    out.emplace_back(r * std::cos(t), r * std::sin(t), z);
  }
  return out;
}

Vec3 corner(const std::vector<Vec3>& a, const std::vector<Vec3>& b, int v) {
  const int m = static_cast<int>(a.size());
  return v < m ? a[v] : b[v - m];
}

// The band between an outer and an inner concentric circle (both CCW) must
// tile the annulus: every triangle positively oriented (normal +z), no edge
// used twice in one direction, boundary = the two loops.
void check_annulus(int m, int n, double phase) {
  const double R = 50.0, r = 30.0;
  const auto a = circle(R, m), b = circle(r, n, phase);
  const LoopTessellation band = loop_tessellation(a, b);
  ASSERT_EQ(static_cast<int>(band.triangles.size()), m + n);
  double signed_area = 0.0, abs_area = 0.0;
  for (const auto& t : band.triangles) {
    const Vec3 av = (corner(a, b, t[1]) - corner(a, b, t[0])).cross(corner(a, b, t[2]) - corner(a, b, t[0]));
    EXPECT_GT(av.z(), 1e-3) << "degenerate or flipped triangle";
    signed_area += 0.5 * av.z();
    abs_area += 0.5 * av.norm();
  }
  // Non-crossing: all triangles positive and the signed total equals the
  // polygon annulus area, so they do not overlap.
  const double poly_area = 0.5 * m * R * R * std::sin(2 * std::numbers::pi / m) -
                           0.5 * n * r * r * std::sin(2 * std::numbers::pi / n);
  EXPECT_NEAR(signed_area, poly_area, 1e-9 * poly_area);
  EXPECT_NEAR(abs_area, poly_area, 1e-9 * poly_area);
  const double analytic = std::numbers::pi * (R * R - r * r);
  EXPECT_NEAR(signed_area, analytic, 0.03 * analytic);
  // An oriented annulus: manifold, consistently oriented, two boundary loops.
  const Halfedges he = build_halfedges(m + n, band.triangles);
  const auto loops = he.boundary_loops();
  ASSERT_EQ(loops.size(), 2u);
  EXPECT_EQ(static_cast<int>(loops[0].size() + loops[1].size()), m + n);
  // A's edges are traversed forwards.
  for (int i = 0; i < m; ++i) {
    bool found = false;
    for (const auto& t : band.triangles)
      for (int k = 0; k < 3; ++k) found = found || (t[k] == i && t[(k + 1) % 3] == (i + 1) % m);
    EXPECT_TRUE(found) << "edge a" << i;
  }
}

std::vector<std::array<int, 3>> naive_zip(int m, int n) {
  std::vector<std::array<int, 3>> out;
  int i = 0, j = 0;
  while (i < m || j < n) {
    // advance the loop that is behind in parameter
    if (j >= n || (i < m && (i + 1) * n <= (j + 1) * m)) {
      out.push_back({i % m, (i + 1) % m, m + j % n});
      ++i;
    } else {
      out.push_back({i % m, m + (j + 1) % n, m + j % n});
      ++j;
    }
  }
  return out;
}

}  // namespace

TEST(LoopTessellation, EqualConcentricCirclesTileTheAnnulus) { check_annulus(48, 48, 0.0); }
TEST(LoopTessellation, UnequalConcentricCirclesTileTheAnnulus) { check_annulus(60, 25, 0.3); }
TEST(LoopTessellation, InnerLoopLongerTilesTheAnnulus) { check_annulus(20, 45, 1.0); }

TEST(LoopTessellation, EqualLoopsAboveEachOtherGiveVerticalBridges) {
  const auto a = circle(20.0, 16, 0.0, 10.0), b = circle(20.0, 16, 0.0, 0.0);
  const LoopTessellation band = loop_tessellation(a, b);
  // The optimum: the 16 vertical bridges (length 10) plus one diagonal per
  // quad; the cost is the sum of these 32 distinct bridges.
  int verticals = 0;
  for (const auto& t : band.triangles)
    for (int k = 0; k < 3; ++k) {
      const int u = t[k], v = t[(k + 1) % 3];
      if (u < 16 && v >= 16 && v - 16 == u) ++verticals;
    }
  // every vertical bridge is used by two triangles (once in each direction)
  EXPECT_EQ(verticals, 16);
  const double chord = 2 * 20.0 * std::sin(std::numbers::pi / 16);
  EXPECT_NEAR(band.cost, 16 * 10.0 + 16 * std::hypot(10.0, chord), 1e-9);
  EXPECT_NEAR(loop_tessellation_cost(a, b, band.triangles), band.cost, 1e-9);
}

TEST(LoopTessellation, OptimumIsNotWorseThanTheNaiveZip) {
  // Offset, unequal, non-circular loops.
  std::vector<Vec3> a, b;
  for (int i = 0; i < 37; ++i) {
    const double t = 2 * std::numbers::pi * i / 37;
    a.emplace_back(60 * std::cos(t), 35 * std::sin(t), 0.0);
  }
  for (int i = 0; i < 23; ++i) {
    const double t = 2 * std::numbers::pi * i / 23 + 0.7;
    b.emplace_back(8 + 25 * std::cos(t), -3 + 20 * std::sin(t), 15.0);
  }
  for (auto cost : {LoopTessellationCost::BridgeLength, LoopTessellationCost::TriangleArea}) {
    LoopTessellationOptions o;
    o.cost = cost;
    const LoopTessellation band = loop_tessellation(a, b, o);
    const auto naive = naive_zip(37, 23);
    const double naive_cost = loop_tessellation_cost(a, b, naive, cost);
    EXPECT_LE(band.cost, naive_cost + 1e-9);
    EXPECT_NEAR(loop_tessellation_cost(a, b, band.triangles, cost), band.cost, 1e-9 * band.cost);
    EXPECT_TRUE(band.exhaustive);
    // The seed's shortest-bridge start is never better than the exhaustive optimum.
    o.max_exhaustive_work = 0.0;
    const LoopTessellation seed = loop_tessellation(a, b, o);
    EXPECT_FALSE(seed.exhaustive);
    EXPECT_GE(seed.cost, band.cost - 1e-9);
    EXPECT_NO_THROW(build_halfedges(60, seed.triangles));
  }
  // Brute force over all start pairs agrees with the exhaustive search.
  std::vector<Vec3> sa(a.begin(), a.begin() + 7), sb(b.begin(), b.begin() + 5);
  const double best = loop_tessellation(sa, sb).cost;
  for (int s = 0; s < 7; ++s) {
    std::vector<Vec3> ra;
    for (int i = 0; i < 7; ++i) ra.push_back(sa[(i + s) % 7]);
    EXPECT_NEAR(loop_tessellation(ra, sb).cost, best, 1e-9);
  }
}

TEST(LoopTessellation, RejectsBadLoops) {
  const auto a = circle(10, 8);
  EXPECT_THROW(loop_tessellation(a, std::vector<Vec3>{Vec3(0, 0, 0), Vec3(1, 0, 0)}), InvalidInput);
  auto bad = circle(5, 6);
  bad[2].x() = std::nan("");
  EXPECT_THROW(loop_tessellation(a, bad), InvalidInput);
}
