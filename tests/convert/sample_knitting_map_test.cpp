#include "knitforge/convert/sample_knitting_map.h"

#include <gtest/gtest.h>

#include "knitforge/convert/map_knittability.h"
#include "knitforge/convert/map_to_stitch_mesh.h"
#include "knitforge/convert/stitch_mesh_to_map.h"
#include "knitforge/core/stitch_mesh.h"
#include "knitforge/util/errors.h"

using namespace knitforge;

TEST(SampleKnittingMap, EveryBuiltInMapIsKnittableAndCanonical) {
  for (const auto& name : sample_map_names()) {
    SCOPED_TRACE(name);
    const KnittingMap map = sample_knitting_map(name);
    const KnittabilityReport report = check_knittability(map);
    EXPECT_TRUE(report.ok()) << report.text();
    const StitchMesh mesh = map_to_stitch_mesh_topology(map, KnitParams{});
    EXPECT_EQ(stitch_mesh_to_map(mesh), map);
  }
}

TEST(SampleKnittingMap, CupHasPairedTurnsOnDistinctColumns) {
  CupMapOptions o;
  o.wales = 30;
  o.turns = 5;
  const KnittingMap map = cup_knitting_map(o);
  int left = 0, right = 0;
  std::vector<int> per_column(map.cols, 0);
  for (int r = 0; r < map.rows; ++r) {
    for (int c = 0; c < map.cols; ++c) {
      if (map.at(r, c) == CellType::ShortRowLeft) ++left, ++per_column[c];
      if (map.at(r, c) == CellType::ShortRowRight) ++right, ++per_column[c];
    }
  }
  // Two wedges of `turns` turns per side, each turn a stacked pair.
  EXPECT_EQ(left, 2 * 2 * o.turns);
  EXPECT_EQ(right, 2 * 2 * o.turns);
  for (int c = 0; c < map.cols; ++c) EXPECT_TRUE(per_column[c] == 0 || per_column[c] == 2) << c;
  EXPECT_TRUE(check_knittability(map).ok());
}

TEST(SampleKnittingMap, RejectsBadOptionsAndNames) {
  CupMapOptions o;
  o.wales = 10;
  EXPECT_THROW(cup_knitting_map(o), InvalidInput);
  o = {};
  o.border_rows = 3;
  EXPECT_THROW(cup_knitting_map(o), InvalidInput);
  EXPECT_THROW(sample_knitting_map("nope"), InvalidInput);
}
