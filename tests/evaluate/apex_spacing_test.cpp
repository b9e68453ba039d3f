#include "knitforge/evaluate/apex_spacing.h"

#include <cmath>
#include <random>

#include <gtest/gtest.h>

#include "knitforge/util/errors.h"

namespace knitforge {
namespace {

Stitch stitch(StitchType type, std::array<int, 4> v) {
  Stitch s;
  s.type = type;
  s.v = v;
  return s;
}

TEST(ApexSpacing, NearestApexOfEachShapingStitch) {
  StitchMesh m;
  m.vertices = {Vec3(0, 0, 0), Vec3(3, 0, 0), Vec3(3, 4, 0), Vec3(1, 1, 0), Vec3(2, 1, 0), Vec3(9, 9, 9)};
  // Apexes: vertex 0 (left end), vertex 1 (right end), vertex 2 (increase);
  // vertex 0 is also the apex of a second short-row end (counted once); the
  // knit stitch has none.
  m.stitches = {stitch(StitchType::ShortRowLeft, {0, 3, 4, -1}), stitch(StitchType::ShortRowRight, {3, 1, 4, -1}),
                stitch(StitchType::ShortRowRight, {4, 0, 3, -1}), stitch(StitchType::Increase, {2, 4, 3, -1}),
                stitch(StitchType::Knit, {3, 4, 5, 0})};
  const ApexSpacing a = apex_spacing(m);
  ASSERT_EQ(a.apexes, (std::vector<int>{0, 1, 2}));
  ASSERT_EQ(a.nearest.size(), 3u);
  EXPECT_DOUBLE_EQ(a.nearest[0], 3.0);
  EXPECT_DOUBLE_EQ(a.nearest[1], 3.0);
  EXPECT_DOUBLE_EQ(a.nearest[2], 4.0);
  EXPECT_EQ(a.stats.count, 3);
  EXPECT_DOUBLE_EQ(a.stats.min, 3.0);
  EXPECT_DOUBLE_EQ(a.stats.max, 4.0);
}

TEST(ApexSpacing, SweepMatchesBruteForce) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-50, 50);
  StitchMesh m;
  for (int i = 0; i < 600; ++i) m.vertices.emplace_back(u(rng), u(rng), 0.2 * u(rng));
  // Some apexes share an x coordinate (ties in the sweep order).
  m.vertices[10].x() = m.vertices[11].x() = m.vertices[12].x();
  for (int i = 0; i + 2 < 600; i += 3) m.stitches.push_back(stitch(StitchType::Decrease, {i + 1, i + 2, i, -1}));
  const ApexSpacing a = apex_spacing(m);
  ASSERT_EQ(a.apexes.size(), 200u);
  for (size_t i = 0; i < a.apexes.size(); ++i) {
    double best = INFINITY;
    for (size_t j = 0; j < a.apexes.size(); ++j) {
      if (j != i) best = std::min(best, (m.vertices[a.apexes[i]] - m.vertices[a.apexes[j]]).norm());
    }
    EXPECT_DOUBLE_EQ(a.nearest[i], best) << i;
  }
}

TEST(ApexSpacing, FewerThanTwoApexesAndBadInput) {
  StitchMesh m;
  m.vertices = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(1, 1, 0), Vec3(0, 1, 0)};
  m.stitches = {stitch(StitchType::Knit, {0, 1, 2, 3})};
  EXPECT_TRUE(apex_spacing(m).apexes.empty());
  m.stitches.push_back(stitch(StitchType::ShortRowLeft, {0, 1, 2, -1}));
  const ApexSpacing one = apex_spacing(m);
  EXPECT_EQ(one.apexes.size(), 1u);
  EXPECT_TRUE(one.nearest.empty());
  EXPECT_EQ(one.stats.count, 0);
  m.stitches.push_back(stitch(StitchType::ShortRowLeft, {7, 1, 2, -1}));
  EXPECT_THROW(apex_spacing(m), TopologyError);
  m.stitches.back().v[0] = 3;
  m.vertices[3].x() = NAN;
  EXPECT_THROW(apex_spacing(m), InvalidInput);
}

}  // namespace
}  // namespace knitforge
