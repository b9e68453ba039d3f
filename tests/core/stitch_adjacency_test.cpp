#include "knitforge/core/stitch_adjacency.h"

#include <gtest/gtest.h>

#include "knitforge/util/errors.h"

using namespace knitforge;

namespace {

// Two courses of two stitches: row 0 left to right, row 1 right to left.
//  6--7--8
//  |s3|s2|
//  3--4--5
//  |s0|s1|
//  0--1--2
StitchMesh two_by_two() {
  StitchMesh m;
  for (int y = 0; y < 3; ++y)
    for (int x = 0; x < 3; ++x) m.vertices.emplace_back(x, y, 0);
  auto quad = [&](int x, int y, int8_t dir) {
    Stitch s;
    s.direction = dir;
    s.v = {3 * y + x, 3 * y + x + 1, 3 * (y + 1) + x + 1, 3 * (y + 1) + x};
    m.stitches.push_back(s);
  };
  quad(0, 0, 1);
  quad(1, 0, 1);
  quad(1, 1, -1);
  quad(0, 1, -1);
  return m;
}

}  // namespace

TEST(StitchAdjacency, NeighboursBySide) {
  const StitchMesh m = two_by_two();
  const StitchAdjacency a(m);
  EXPECT_EQ(a.neighbor(0, Side::Right), 1);
  EXPECT_EQ(a.neighbor(0, Side::Top), 3);
  EXPECT_EQ(a.neighbor(0, Side::Left), -1);
  EXPECT_EQ(a.neighbor(2, Side::Bottom), 1);
  EXPECT_EQ(a.neighbor_side(0, Side::Right), Side::Left);
}

TEST(StitchAdjacency, KnittingOrderIsOneStroke) {
  const StitchMesh m = two_by_two();
  const StitchAdjacency a(m);
  EXPECT_EQ(a.next_stitch(0), 1);
  EXPECT_EQ(a.next_stitch(1), 2);  // turns up at the right end
  EXPECT_EQ(a.next_stitch(2), 3);
  EXPECT_EQ(a.next_stitch(3), -1);
  EXPECT_EQ(a.previous_stitch(3), 2);
  EXPECT_EQ(a.previous_stitch(2), 1);
  EXPECT_EQ(a.previous_stitch(0), -1);
}

TEST(StitchAdjacency, ShortRowTurnAtApex) {
  // Row 0: two quads left to right. Row 1: a short row going left that ends
  // in a ShortRowLeft triangle whose apex is vertex 3 (left boundary would be
  // a violation, but adjacency does not judge).
  StitchMesh m = two_by_two();
  m.stitches[3].type = StitchType::ShortRowLeft;
  m.stitches[3].v = {3, 4, 7, -1};
  const StitchAdjacency a(m);
  EXPECT_EQ(a.next_stitch(2), 3);
  EXPECT_EQ(a.neighbor(3, Side::Left), -1);
  EXPECT_EQ(apex_vertex(m.stitches[3]), 3);
}

TEST(StitchAdjacency, RejectsInconsistentOrientation) {
  StitchMesh m = two_by_two();
  std::swap(m.stitches[1].v[1], m.stitches[1].v[3]);  // flip stitch 1
  EXPECT_THROW(StitchAdjacency{m}, TopologyError);
}
