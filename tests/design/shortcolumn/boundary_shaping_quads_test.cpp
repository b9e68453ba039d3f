// Boundary-apex increases and decreases become regular stitches
// (boundary_shaping_quads.h).
#include "knitforge/design/shortcolumn/boundary_shaping_quads.h"

#include <gtest/gtest.h>

#include "knitforge/core/stitch_adjacency.h"

namespace knitforge {
namespace {

Stitch make(StitchType t, std::array<int, 4> v) {
  Stitch s;
  s.type = t;
  s.v = v;
  return s;
}

TEST(BoundaryShapingQuads, ADecreaseBetweenTwoNeighboursUnderTheEdgeSplitsItsApex) {
  // Bottom v0..v3 at y = 0, top v4 (0,1), v5 (1.5,1), v6 (3,1): the Decrease
  // (v1, v2, v5) sits between two quads, its apex on the top edge.
  StitchMesh m;
  m.vertices = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(2, 0, 0), Vec3(3, 0, 0),
                Vec3(0, 1, 0), Vec3(1.5, 1, 0), Vec3(3, 1, 0)};
  m.stitches = {make(StitchType::Knit, {0, 1, 5, 4}), make(StitchType::Decrease, {1, 2, 5, -1}),
                make(StitchType::Knit, {2, 3, 6, 5})};
  const BoundaryShapingQuadStats st = boundary_shaping_quads(m);
  EXPECT_EQ(st.decreases, 1);
  EXPECT_EQ(st.split_apexes, 1);
  ASSERT_EQ(m.num_vertices(), 8);
  EXPECT_EQ(m.stitches[1].type, StitchType::Knit);
  EXPECT_EQ(m.stitches[1].v, (std::array<int, 4>{1, 2, 7, 5}));
  EXPECT_EQ(m.stitches[0].v, (std::array<int, 4>{0, 1, 5, 4})) << "the left neighbour keeps the apex";
  EXPECT_EQ(m.stitches[2].v, (std::array<int, 4>{2, 3, 6, 7})) << "the right neighbour takes the copy";
  // The top edge is half the bottom one, centred on the old apex.
  EXPECT_NEAR(m.vertices[5].x(), 1.25, 1e-12);
  EXPECT_NEAR(m.vertices[7].x(), 1.75, 1e-12);
  // A valid stitch mesh: left and right neighbours across Left / Right sides.
  const StitchAdjacency adj(m);
  EXPECT_EQ(adj.neighbor(1, Side::Left), 0);
  EXPECT_EQ(adj.neighbor(1, Side::Right), 2);
}

TEST(BoundaryShapingQuads, AnIncreaseAtTheEdgeOfItsCourseBecomesAnEdgeStitch) {
  // Increase (v1, v3, v2) right of a quad, nothing on its right.
  StitchMesh m;
  m.vertices = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(1, 1, 0), Vec3(2, 1, 0), Vec3(0, 1, 0)};
  m.stitches = {make(StitchType::Knit, {0, 1, 2, 4}), make(StitchType::Increase, {1, 3, 2, -1})};
  const BoundaryShapingQuadStats st = boundary_shaping_quads(m);
  EXPECT_EQ(st.increases, 1);
  EXPECT_EQ(st.split_apexes, 0);
  EXPECT_EQ(m.stitches[1].type, StitchType::Knit);
  ASSERT_EQ(m.num_vertices(), 6);
  EXPECT_EQ(m.stitches[1].v, (std::array<int, 4>{1, 5, 3, 2}));
  EXPECT_TRUE(m.vertices[5].isApprox(Vec3(2, 0, 0))) << "A + TR - TL";
}

}  // namespace
}  // namespace knitforge
