#include "knitforge/geometry/split_nonmanifold_vertices.h"

#include <vector>

#include <gtest/gtest.h>

#include "knitforge/geometry/halfedges.h"
#include "knitforge/util/errors.h"

namespace knitforge {
namespace {

// Two triangles touching at vertex 0 only (a bow tie) and a quad sharing an
// edge with the first: vertex 0 gets one copy, for the second triangle.
TEST(SplitNonmanifoldVertices, BowTieGetsOneCopyPerFan) {
  // faces: (0 1 2), (0 3 4), quad (1 0 5 6) sharing edge 0-1 with the first
  const std::vector<int> start{0, 3, 6, 10};
  const std::vector<int> corners{0, 1, 2, 0, 3, 4, 1, 0, 5, 6};
  EXPECT_THROW(build_halfedges(7, start, corners), TopologyError);
  const VertexFanSplit r = split_nonmanifold_vertices(7, start, corners);
  EXPECT_EQ(r.num_split, 1);
  ASSERT_EQ(r.vertex_origin.size(), 8u);
  EXPECT_EQ(r.vertex_origin[7], 0);
  // The first fan (faces 0 and 2) keeps vertex 0, the second face gets 7.
  EXPECT_EQ(r.face_vertices, (std::vector<int>{0, 1, 2, 7, 3, 4, 1, 0, 5, 6}));
  EXPECT_NO_THROW(build_halfedges(8, start, r.face_vertices));
}

// Three fans around one vertex: two copies, in order of their first corner;
// a manifold mesh comes back unchanged.
TEST(SplitNonmanifoldVertices, ThreeFansAndManifoldInput) {
  const std::vector<int> start{0, 3, 6, 9};
  const std::vector<int> corners{0, 1, 2, 3, 0, 4, 5, 6, 0};
  const VertexFanSplit r = split_nonmanifold_vertices(7, start, corners);
  EXPECT_EQ(r.num_split, 1);
  EXPECT_EQ(r.face_vertices, (std::vector<int>{0, 1, 2, 3, 7, 4, 5, 6, 8}));
  EXPECT_EQ(r.vertex_origin, (std::vector<int>{0, 1, 2, 3, 4, 5, 6, 0, 0}));
  const std::vector<int> fan_start{0, 3, 6};
  const std::vector<int> fan{0, 1, 2, 0, 2, 3};
  const VertexFanSplit same = split_nonmanifold_vertices(4, fan_start, fan);
  EXPECT_EQ(same.num_split, 0);
  EXPECT_EQ(same.face_vertices, fan);
  EXPECT_EQ(same.vertex_origin.size(), 4u);
}

TEST(SplitNonmanifoldVertices, RejectsBadLayouts) {
  EXPECT_THROW(split_nonmanifold_vertices(3, std::vector<int>{0, 4}, std::vector<int>{0, 1, 2}),
               InvalidInput);
  EXPECT_THROW(split_nonmanifold_vertices(3, std::vector<int>{0, 3}, std::vector<int>{0, 1, 5}),
               InvalidInput);
  EXPECT_THROW(split_nonmanifold_vertices(3, std::vector<int>{}, std::vector<int>{}), InvalidInput);
}

}  // namespace
}  // namespace knitforge
