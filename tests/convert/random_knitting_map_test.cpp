#include "knitforge/convert/random_knitting_map.h"

#include "knitforge/convert/map_knittability.h"

#include <gtest/gtest.h>

#include "convert/map_test_helpers.h"
#include "knitforge/convert/map_to_stitch_mesh.h"
#include "knitforge/convert/stitch_mesh_to_map.h"
#include "knitforge/core/stitch_adjacency.h"

using namespace knitforge;
using namespace knitforge::test;

namespace {

int count_cells(const KnittingMap& m, CellType t) {
  int n = 0;
  for (CellType c : m.cells) n += c == t;
  return n;
}

// Independent checks of the seed §1.2.2 constraints on the map's mesh.
void expect_knittable(const KnittingMap& map) {
  const KnittabilityReport r = check_knittability(map);
  EXPECT_TRUE(r.ok()) << r.text() << draw_map(map);
  const StitchMesh mesh = map_to_stitch_mesh_topology(map, KnitParams{});
  const StitchAdjacency adj(mesh);
  EXPECT_TRUE(one_stroke_in_index_order(mesh)) << draw_map(map);
  EXPECT_EQ(count_boundary_apexes(mesh), 0) << draw_map(map);
  for (int s = 0; s < mesh.num_stitches(); ++s) {
    const StitchType t = mesh.stitches[s].type;
    if (t == StitchType::Increase || t == StitchType::Decrease) {
      for (Side side : {Side::Left, Side::Right}) {
        const int o = adj.neighbor(s, side);
        EXPECT_FALSE(o >= 0 && mesh.stitches[o].type == t) << "neighbouring " << name(t) << " at stitch " << s;
      }
    }
  }
  // No four stacked short-row ends in one column.
  for (int c = 0; c < map.cols; ++c) {
    int run = 0;
    for (int r = 0; r < map.rows; ++r) {
      const CellType t = map.at(r, c);
      run = (t == CellType::ShortRowLeft || t == CellType::ShortRowRight) ? run + 1 : 0;
      EXPECT_LT(run, 4) << "column " << c << "\n" << draw_map(map);
    }
  }
  // Short-row ends come in stacked pairs of the same type.
  for (int r = 0; r < map.rows; ++r) {
    for (int c = 0; c < map.cols; ++c) {
      const CellType t = map.at(r, c);
      if (t != CellType::ShortRowLeft && t != CellType::ShortRowRight) continue;
      const bool below = r > 0 && map.at(r - 1, c) == t, above = r + 1 < map.rows && map.at(r + 1, c) == t;
      EXPECT_TRUE(below || above) << "unpaired short-row end at (" << r << ", " << c << ")";
    }
  }
}

}  // namespace

TEST(RandomKnittingMap, DeterministicForASeed) {
  RandomMapOptions o;
  o.seed = 7;
  o.rows = 30;
  o.cols = 25;
  o.short_row_ends = 16;
  o.short_columns = 6;
  const KnittingMap a = random_knitting_map(o), b = random_knitting_map(o);
  EXPECT_TRUE(a == b);
  o.seed = 8;
  EXPECT_FALSE(random_knitting_map(o) == a);
}

TEST(RandomKnittingMap, HasTheRequestedFeaturesAndIsKnittable) {
  for (uint64_t seed = 1; seed <= 40; ++seed) {
    RandomMapOptions o;
    o.seed = seed;
    o.rows = 8 + static_cast<int>(seed % 17);
    o.cols = 8 + static_cast<int>((seed * 7) % 19);
    o.short_row_ends = 2 * static_cast<int>(seed % 4);
    o.short_columns = static_cast<int>(seed % 3);
    o.boundary_shaping = seed % 2 == 0;
    SCOPED_TRACE(seed);
    const KnittingMap m = random_knitting_map(o);
    EXPECT_EQ(m.rows, o.rows);
    EXPECT_EQ(m.cols, o.cols);
    EXPECT_EQ(count_cells(m, CellType::ShortRowLeft) + count_cells(m, CellType::ShortRowRight), o.short_row_ends);
    const StitchMesh mesh = map_to_stitch_mesh_topology(m, KnitParams{});
    std::vector<int> wales;
    for (const Stitch& s : mesh.stitches) wales.push_back(s.wale);
    // short columns: columns whose stitches do not span every row.
    int short_cols = 0;
    for (int c = 0; c < m.cols; ++c) {
      bool inc = false, dec = false;
      for (int r = 0; r < m.rows; ++r) inc |= m.at(r, c) == CellType::Increase, dec |= m.at(r, c) == CellType::Decrease;
      short_cols += inc || dec;
    }
    EXPECT_EQ(short_cols, o.short_columns);
    expect_knittable(m);
    if (o.boundary_shaping) {
      int roles = 0;
      for (const Stitch& s : mesh.stitches) roles |= s.roles;
      if (o.rows >= 12 && o.cols >= 10) {
        EXPECT_TRUE(roles & kRoleOutsideIncrease) << draw_map(m);
      }
    }
  }
}

TEST(RandomKnittingMap, DenseShortRowsAndColumns) {
  RandomMapOptions o;
  o.seed = 3;
  o.rows = 40;
  o.cols = 40;
  o.short_row_ends = 2 * (o.rows - 3) - 4;  // all but two of the allowed turns
  o.short_columns = 20;
  const KnittingMap m = random_knitting_map(o);
  EXPECT_EQ(count_cells(m, CellType::ShortRowLeft) + count_cells(m, CellType::ShortRowRight), o.short_row_ends);
  expect_knittable(m);
}

// Dense short rows used to stack a second turn pair on a wale held since its
// first (four stacked ends across collapsed cells, which the checker
// rejects); every map the generator returns passes the checker.
TEST(RandomKnittingMap, DenseMapsPassTheKnittabilityCheck) {
  int made = 0;
  for (int size : {30, 60}) {
    for (uint64_t seed = 1; seed <= 12; ++seed) {
      RandomMapOptions o;
      o.seed = seed;
      o.rows = size;
      o.cols = size;
      o.short_row_ends = 2 * (size - 3) - 4;
      o.short_columns = size / 3;
      KnittingMap m;
      try {
        m = random_knitting_map(o);
      } catch (const InvalidInput&) {
        continue;  // "use fewer or another seed": allowed, never a bad map
      }
      ++made;
      EXPECT_TRUE(check_knittability(m).ok()) << "size " << size << " seed " << seed;
    }
  }
  EXPECT_GE(made, 18);
}

TEST(RandomKnittingMap, RejectsInfeasibleRequests) {
  RandomMapOptions o;
  o.rows = 10;
  o.cols = 10;
  o.short_row_ends = 3;
  EXPECT_THROW(random_knitting_map(o), InvalidInput);
  o.short_row_ends = 2 * 8;  // at most 2 * (rows - 3) = 14
  EXPECT_THROW(random_knitting_map(o), InvalidInput);
  o.short_row_ends = 0;
  o.short_columns = 9;  // at most cols - 2 = 8
  EXPECT_THROW(random_knitting_map(o), InvalidInput);
  o.short_columns = 0;
  o.rows = 3;
  EXPECT_THROW(random_knitting_map(o), InvalidInput);
}
