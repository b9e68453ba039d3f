// Support stitches of order_courses() (seed §3.2.3 Fig. 3.5(b), §3.2.4): a
// course transition that needs support over several wales is bridged in map
// space, and the result passes both knittability checkers.

#include <gtest/gtest.h>

#include "knitforge/convert/map_knittability.h"
#include "knitforge/convert/stitch_mesh_to_map.h"
#include "knitforge/core/knittability.h"
#include "knitforge/core/stitch_adjacency.h"
#include "knitforge/design/shortrow/order_courses.h"

namespace knitforge {
namespace {

/// Adds a knit stitch with the given corners (BL BR TR TL), direction and wale.
void add_knit(StitchMesh& m, int bl, int br, int tr, int tl, int dir, int wale) {
  Stitch s;
  s.type = StitchType::Knit;
  s.v = {bl, br, tr, tl};
  s.direction = static_cast<int8_t>(dir);
  s.wale = wale;
  m.stitches.push_back(s);
}

/// Rows of a 6 x 4 vertex grid: course A = columns 0..1 (left to right),
/// course B = columns 0..5 right to left on top of A (columns 2..5 have
/// nothing below: the fabric widens by four wales), course C = columns 0..5
/// left to right on top of B. A ends at column 1, B starts at column 5: the
/// transition needs four support stitches under B.
StitchMesh widening_mesh() {
  StitchMesh m;
  auto id = [](int x, int y) { return y * 7 + x; };
  for (int y = 0; y < 4; ++y) {
    for (int x = 0; x < 7; ++x) m.vertices.emplace_back(3.0 * x, 2.0 * y, 0.0);
  }
  for (int x = 0; x < 2; ++x) add_knit(m, id(x, 0), id(x + 1, 0), id(x + 1, 1), id(x, 1), +1, x);
  for (int x = 0; x < 6; ++x) add_knit(m, id(x, 1), id(x + 1, 1), id(x + 1, 2), id(x, 2), -1, x);
  for (int x = 0; x < 6; ++x) add_knit(m, id(x, 2), id(x + 1, 2), id(x + 1, 3), id(x, 3), +1, x);
  return m;
}

int count_one_stroke(const StitchMesh& m) {
  const StitchAdjacency adj(m);
  int first = -1;
  for (int s = 0; s < m.num_stitches(); ++s) {
    if (adj.previous_stitch(s) < 0) {
      if (first >= 0) return -1;  // two starts: not one stroke
      first = s;
    }
  }
  int visited = 0;
  for (int s = first; s >= 0 && visited <= m.num_stitches(); s = adj.next_stitch(s)) ++visited;
  return visited;
}

TEST(ShortRowBranches, SupportOverSeveralWalesMakesOneStroke) {
  StitchMesh m = widening_mesh();
  ASSERT_FALSE(check_knittability(m).ok());
  const CourseOrder o = order_courses(m);
  EXPECT_EQ(o.num_courses, 3);
  EXPECT_EQ(o.support_stitches, 4);
  EXPECT_EQ(o.fixed_breaks, 1);
  EXPECT_TRUE(o.breaks.empty());
  EXPECT_EQ(o.cyclic_edges, 0);
  ASSERT_EQ(m.num_stitches(), 2 + 6 + 6 + 4);
  // The support stitches continue course A under B, in B's columns.
  for (int s = 14; s < 18; ++s) {
    EXPECT_EQ(m.stitches[s].course, 0);
    EXPECT_EQ(m.stitches[s].direction, 1);
    EXPECT_EQ(m.stitches[s].wale, s - 14 + 2);
  }
  EXPECT_EQ(count_one_stroke(m), m.num_stitches());
  const KnittabilityReport mesh_check = check_knittability(m);
  EXPECT_TRUE(mesh_check.violations.empty()) << mesh_check.violations.front().message;
  const KnittingMap map = stitch_mesh_to_map(m);
  EXPECT_EQ(map.rows, 3);
  EXPECT_EQ(map.cols, 6);
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 6; ++c) EXPECT_EQ(map.at(r, c), CellType::Knit) << r << "," << c;
  }
  KnitParams p;
  const KnittabilityReport map_check = check_knittability(map, p);
  EXPECT_TRUE(map_check.violations.empty()) << map_check.violations.front().message;
}

/// Two branches side by side (a slit between columns 1 and 2 above course
/// B): the yarn cannot return from the left branch to the right one without
/// crossing a wale that is still being knitted, so no support is added there
/// and the break is reported instead of producing an invalid mesh.
TEST(ShortRowBranches, BlockedBranchIsReportedNotPatched) {
  StitchMesh m;
  auto id = [](int x, int y) { return y * 5 + x; };
  for (int y = 0; y < 4; ++y) {
    for (int x = 0; x < 5; ++x) m.vertices.emplace_back(3.0 * x, 2.0 * y, 0.0);
  }
  // Duplicate vertices on the slit x = 2 for y = 2, 3 (right branch side).
  const int s2 = m.num_vertices();
  m.vertices.emplace_back(6.0, 4.0, 0.0);
  m.vertices.emplace_back(6.0, 6.0, 0.0);
  auto right = [&](int x, int y) { return (x == 2 && y >= 2) ? s2 + (y - 2) : id(x, y); };
  for (int x = 0; x < 4; ++x) add_knit(m, id(x, 0), id(x + 1, 0), id(x + 1, 1), id(x, 1), +1, x);
  for (int x = 0; x < 4; ++x) add_knit(m, id(x, 1), id(x + 1, 1), id(x + 1, 2), id(x, 2), -1, x);
  for (int x = 0; x < 2; ++x) add_knit(m, id(x, 2), id(x + 1, 2), id(x + 1, 3), id(x, 3), +1, x);
  for (int x = 2; x < 4; ++x) add_knit(m, right(x, 2), right(x + 1, 2), right(x + 1, 3), right(x, 3), +1, x);
  const int before = m.num_stitches();
  const CourseOrder o = order_courses(m);
  EXPECT_EQ(o.num_courses, 4);
  EXPECT_EQ(o.support_stitches, 0);
  EXPECT_EQ(m.num_stitches(), before);
  EXPECT_EQ(o.breaks.size(), 1u);
  EXPECT_FALSE(check_knittability(m).ok());
}

}  // namespace
}  // namespace knitforge
