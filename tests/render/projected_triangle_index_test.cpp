#include "knitforge/render/projected_triangle_index.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "knitforge/util/errors.h"

namespace knitforge {
namespace {

// The same answer as a scan over all triangles, on random overlapping ones.
TEST(ProjectedTriangleIndex, MatchesBruteForce) {
  std::mt19937 rng(4);
  std::uniform_real_distribution<double> pos(-1.0, 1.0), off(-0.2, 0.2), depth(0.0, 5.0);
  std::vector<std::array<Vec3, 3>> tris;
  for (int i = 0; i < 300; ++i) {
    const Vec2 c(pos(rng), pos(rng));
    std::array<Vec3, 3> t;
    for (auto& p : t) p = Vec3(c.x() + off(rng), c.y() + off(rng), depth(rng));
    tris.push_back(t);
  }
  const ProjectedTriangleIndex index(tris);
  int hits = 0;
  for (int q = 0; q < 2000; ++q) {
    const Vec2 p(pos(rng), pos(rng));
    int best = -1;
    double best_depth = 0.0;
    for (int i = 0; i < static_cast<int>(tris.size()); ++i) {
      const auto& c = tris[static_cast<size_t>(i)];
      const double det =
          (c[1].x() - c[0].x()) * (c[2].y() - c[0].y()) - (c[1].y() - c[0].y()) * (c[2].x() - c[0].x());
      if (det == 0.0) continue;
      const double u =
          ((p.x() - c[0].x()) * (c[2].y() - c[0].y()) - (p.y() - c[0].y()) * (c[2].x() - c[0].x())) / det;
      const double v =
          ((c[1].x() - c[0].x()) * (p.y() - c[0].y()) - (c[1].y() - c[0].y()) * (p.x() - c[0].x())) / det;
      if (u < 0 || v < 0 || u + v > 1) continue;
      const double d = (1 - u - v) * c[0].z() + u * c[1].z() + v * c[2].z();
      if (best < 0 || d < best_depth) {
        best = i;
        best_depth = d;
      }
    }
    const auto h = index.first_hit(p);
    ASSERT_EQ(h.triangle, best) << q;
    if (best >= 0) {
      ++hits;
      EXPECT_NEAR(h.depth, best_depth, 1e-12);
      EXPECT_NEAR(h.barycentric.sum(), 1.0, 1e-12);
    }
  }
  EXPECT_GT(hits, 200);
}

TEST(ProjectedTriangleIndex, EmptyAndInvalid) {
  const ProjectedTriangleIndex empty({});
  EXPECT_EQ(empty.first_hit(Vec2(0, 0)).triangle, -1);
  std::vector<std::array<Vec3, 3>> bad = {{Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, NAN, 0)}};
  EXPECT_THROW(ProjectedTriangleIndex{bad}, InvalidInput);
}

}  // namespace
}  // namespace knitforge
