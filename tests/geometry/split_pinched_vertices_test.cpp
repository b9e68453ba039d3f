#include "knitforge/geometry/split_pinched_vertices.h"

#include <gtest/gtest.h>

#include "knitforge/geometry/halfedges.h"
#include "knitforge/geometry/shapes.h"
#include "knitforge/util/errors.h"

namespace knitforge {
namespace {

TEST(SplitPinchedVertices, TwoTrianglesTouchingAtAVertexGetTwoVertices) {
  TriMesh m;
  m.vertices = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(-1, 0, 0), Vec3(0, -1, 0)};
  m.faces = {{0, 1, 2}, {0, 3, 4}};
  EXPECT_THROW(build_halfedges(m.num_vertices(), m.faces), TopologyError);
  const std::vector<int> origin = split_pinched_vertices(m);
  ASSERT_EQ(m.num_vertices(), 6);
  EXPECT_EQ(origin, (std::vector<int>{0, 1, 2, 3, 4, 0}));
  EXPECT_EQ(m.vertices[5], m.vertices[0]);
  EXPECT_EQ(m.faces[0][0], 0);
  EXPECT_EQ(m.faces[1][0], 5);
  EXPECT_NO_THROW(build_halfedges(m.num_vertices(), m.faces));
}

TEST(SplitPinchedVertices, AManifoldMeshIsUnchanged) {
  TriMesh m = hemisphere(30.0, 5.0);
  const TriMesh before = m;
  const std::vector<int> origin = split_pinched_vertices(m);
  EXPECT_EQ(m.num_vertices(), before.num_vertices());
  EXPECT_EQ(m.faces, before.faces);
  for (int v = 0; v < m.num_vertices(); ++v) EXPECT_EQ(origin[static_cast<size_t>(v)], v);
}

TEST(SplitPinchedVertices, ThreeFansAtOneVertexGiveTwoCopies) {
  // A vertex with three separate wedges (bow-tie of three).
  TriMesh m;
  m.vertices = {Vec3(0, 0, 0)};
  for (int k = 0; k < 6; ++k) m.vertices.emplace_back(std::cos(k * 1.0472), std::sin(k * 1.0472), 0.0);
  m.faces = {{0, 1, 2}, {0, 3, 4}, {0, 5, 6}};
  split_pinched_vertices(m);
  EXPECT_EQ(m.num_vertices(), 9);
  EXPECT_NO_THROW(build_halfedges(m.num_vertices(), m.faces));
  m.faces.push_back({0, 1, 99});
  EXPECT_THROW(split_pinched_vertices(m), InvalidInput);
}

}  // namespace
}  // namespace knitforge
