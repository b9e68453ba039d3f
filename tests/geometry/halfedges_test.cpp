#include "knitforge/geometry/halfedges.h"

#include <algorithm>
#include <set>

#include <gtest/gtest.h>

#include "geometry/test_meshes.h"
#include "knitforge/util/errors.h"

namespace knitforge {
namespace {

Halfedges build(const TriMesh& m) { return build_halfedges(m.num_vertices(), m.faces); }

template <class F>
std::string topology_message(F&& f) {
  try {
    f();
  } catch (const TopologyError& e) {
    return e.what();
  }
  ADD_FAILURE() << "no TopologyError thrown";
  return "";
}

TEST(Halfedges, CountsOfASquareGrid) {
  const int n = 4;
  const Halfedges h = build(test::square_grid(n));
  EXPECT_EQ(h.num_vertices(), 25);
  EXPECT_EQ(h.num_faces(), 32);
  EXPECT_EQ(h.num_halfedges(), 96);
  EXPECT_EQ(h.num_edges(), 2 * n * (n + 1) + n * n);  // horizontal + vertical + diagonals
  int boundary = 0;
  for (int e = 0; e < h.num_halfedges(); ++e) {
    if (h.is_boundary_halfedge(e)) {
      ++boundary;
    } else {
      EXPECT_EQ(h.opposite(h.opposite(e)), e);
      EXPECT_EQ(h.from(h.opposite(e)), h.to(e));
      EXPECT_EQ(h.edge(h.opposite(e)), h.edge(e));
    }
    EXPECT_EQ(h.from(h.next(e)), h.to(e));
    EXPECT_EQ(h.next(h.prev(e)), e);
  }
  EXPECT_EQ(boundary, 4 * n);
}

TEST(Halfedges, BoundaryLoopOfASquareGridRunsCounterClockwise) {
  const int n = 3;
  const TriMesh m = test::square_grid(n);
  const auto loops = build(m).boundary_loops();
  ASSERT_EQ(loops.size(), 1u);
  const auto& loop = loops[0];
  ASSERT_EQ(loop.size(), static_cast<size_t>(4 * n));
  EXPECT_EQ(loop[0], 0);
  // The mesh lies to the left: from the origin the loop goes along +x first.
  const std::vector<int> expected = {0, 1, 2, 3, 7, 11, 15, 14, 13, 12, 8, 4};
  EXPECT_EQ(loop, expected);
}

TEST(Halfedges, AnnulusHasTwoBoundaryLoopsAndTorusNone) {
  EXPECT_EQ(build(test::ring_grid(2, 8, false)).boundary_loops().size(), 2u);
  const Halfedges torus = build(test::ring_grid(4, 8, true));
  EXPECT_TRUE(torus.boundary_loops().empty());
  for (int v = 0; v < torus.num_vertices(); ++v) EXPECT_FALSE(torus.is_boundary_vertex(v));
}

TEST(Halfedges, VertexFansOfInteriorAndBoundaryVertices) {
  const TriMesh m = test::square_grid(2);
  const Halfedges h = build(m);
  // Interior vertex 4 = (1, 1): six faces, six neighbours, in one fan.
  const auto faces = h.vertex_faces(4);
  const auto nbrs = h.vertex_neighbors(4);
  EXPECT_EQ(faces.size(), 6u);
  EXPECT_EQ(std::set<int>(nbrs.begin(), nbrs.end()), (std::set<int>{0, 1, 3, 5, 7, 8}));
  EXPECT_EQ(nbrs.size(), 6u);
  for (size_t i = 0; i < faces.size(); ++i) {
    const auto& t = m.faces[faces[i]];
    EXPECT_NE(std::find(t.begin(), t.end(), 4), t.end());
    // Consecutive faces of the fan share an edge (two vertices).
    const auto& u = m.faces[faces[(i + 1) % faces.size()]];
    int shared = 0;
    for (int a : t) shared += std::count(u.begin(), u.end(), a);
    EXPECT_EQ(shared, 2);
  }
  // Corner vertex 2 = (2, 0): one face, two neighbours.
  EXPECT_EQ(h.vertex_faces(2).size(), 1u);
  EXPECT_EQ(h.vertex_neighbors(2).size(), 2u);
  EXPECT_TRUE(h.is_boundary_vertex(2));
  EXPECT_FALSE(h.is_boundary_vertex(4));
  // Boundary vertex 1 = (1, 0): faces + 1 neighbours.
  EXPECT_EQ(h.vertex_neighbors(1).size(), h.vertex_faces(1).size() + 1);
}

TEST(Halfedges, IsolatedVerticesAndComponents) {
  TriMesh m;
  m.vertices = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {5, 0, 0}, {6, 0, 0}, {5, 1, 0}, {9, 9, 9}};
  m.faces = {{0, 1, 2}, {3, 4, 5}};
  const Halfedges h = build(m);
  EXPECT_TRUE(h.is_isolated_vertex(6));
  EXPECT_FALSE(h.is_isolated_vertex(0));
  EXPECT_TRUE(h.vertex_faces(6).empty());
  int count = 0;
  const auto comp = h.face_components(&count);
  EXPECT_EQ(count, 2);
  EXPECT_NE(comp[0], comp[1]);
}

TEST(Halfedges, EdgeWithThreeFacesThrows) {
  TriMesh m;
  m.vertices = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}};
  m.faces = {{0, 1, 2}, {1, 0, 3}, {0, 1, 4}};
  const std::string msg = topology_message([&] { build(m); });
  EXPECT_NE(msg.find("shared by 3 faces"), std::string::npos) << msg;
  EXPECT_NE(msg.find("(0, 1, 2)"), std::string::npos) << msg;  // faces listed
}

TEST(Halfedges, FlippedFaceThrows) {
  TriMesh m = test::square_grid(1);
  std::swap(m.faces[1][1], m.faces[1][2]);
  const std::string msg = topology_message([&] { build(m); });
  EXPECT_NE(msg.find("same direction"), std::string::npos) << msg;
  EXPECT_NE(msg.find("faces 0 and 1"), std::string::npos) << msg;
}

TEST(Halfedges, BowTieVertexThrows) {
  TriMesh m;
  m.vertices = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {-1, 0, 0}, {-1, -1, 0}};
  m.faces = {{0, 1, 2}, {0, 3, 4}};
  const std::string msg = topology_message([&] { build(m); });
  EXPECT_NE(msg.find("vertex 0 is non-manifold"), std::string::npos) << msg;
}

TEST(Halfedges, RepeatedVertexAndOutOfRangeIndexThrow) {
  TriMesh m = test::square_grid(1);
  m.faces[1] = {0, 2, 2};
  const std::string msg = topology_message([&] { build(m); });
  EXPECT_NE(msg.find("face 1 uses vertex 2 twice"), std::string::npos) << msg;
  TriMesh o = test::square_grid(1);
  o.faces[0][2] = 7;
  const std::string msg2 = topology_message([&] { build(o); });
  EXPECT_NE(msg2.find("face 0 uses vertex 7"), std::string::npos) << msg2;
}

TEST(Halfedges, MalformedFaceStartIsInvalidInput) {
  const std::vector<int> start = {0, 3};
  const std::vector<int> verts = {0, 1};
  EXPECT_THROW(build_halfedges(3, start, verts), InvalidInput);
  // A decreasing face_start would index past face_vertices.
  const std::vector<int> start2 = {0, 9, 6};
  const std::vector<int> verts2 = {0, 1, 2, 0, 2, 3};
  EXPECT_THROW(build_halfedges(4, start2, verts2), InvalidInput);
}

}  // namespace
}  // namespace knitforge
