#include "knitforge/geometry/prepare_surface.h"

#include <gtest/gtest.h>

#include "geometry/test_meshes.h"
#include "knitforge/geometry/cut_to_disk.h"
#include "knitforge/geometry/shapes.h"
#include "knitforge/geometry/surface_checks.h"

namespace knitforge {
namespace {

// Unused vertices are dropped; the others keep their order; the map says
// where each went.
TEST(PrepareSurface, DropsUnusedVertices) {
  TriMesh m = test::square_grid(3);
  const int n = m.num_vertices();
  m.vertices.insert(m.vertices.begin() + 5, Vec3(500, 500, 500));  // vertex 5, used by no face
  for (auto& t : m.faces)
    for (int& v : t)
      if (v >= 5) ++v;
  m.vertices.push_back(Vec3(-7e4, 0, 0));  // and a far one at the end
  const PreparedSurface p = prepare_surface(m);
  EXPECT_EQ(p.unused_vertices, 2);
  EXPECT_EQ(p.welded_vertices, 0);
  ASSERT_EQ(p.mesh.num_vertices(), n);
  EXPECT_EQ(p.vertex_map[5], -1);
  EXPECT_EQ(p.vertex_map[n + 1], -1);
  EXPECT_EQ(p.vertex_map[4], 4);
  EXPECT_EQ(p.vertex_map[6], 5);
  EXPECT_EQ(p.mesh.faces, test::square_grid(3).faces);
  EXPECT_EQ(validate_surface(p.mesh).count(SurfaceIssueKind::IsolatedVertex), 0);
}

// A surface whose vertices are split along a seam (as exports split them
// along texture seams) is welded back: the tube cut open along a seam is a
// tube again, with one vertex per position.
TEST(PrepareSurface, WeldsASplitSeam) {
  const TriMesh tube = open_tube(20.0, 30.0, 3.0);
  const CutToDisk open = cut_to_disk(tube);
  ASSERT_EQ(validate_surface(open.mesh).num_boundary_loops, 1);
  int copies = 0;
  std::vector<char> seen(open.mesh.num_vertices(), 0);
  for (int v = 0; v < open.mesh.num_vertices(); ++v) {
    const int o = open.vertex_origin[v];
    if (o >= 0 && seen[o]++) ++copies;
  }
  ASSERT_GT(copies, 0);
  const PreparedSurface p = prepare_surface(open.mesh);
  EXPECT_GE(p.welded_vertices, copies);  // the copies of input vertices, and of new vertices on the seam
  const SurfaceReport r = validate_surface(p.mesh);
  EXPECT_TRUE(r.ok()) << r.summary();
  EXPECT_EQ(r.num_boundary_loops, 2);
  EXPECT_EQ(r.genus, 0);
  EXPECT_EQ(p.mesh.num_vertices(), open.mesh.num_vertices() - p.welded_vertices);
}

// Vertices at one position that share a face (a zero-length edge) are not a
// split and stay; welding that would make the surface non-manifold (two
// triangles touching at a corner) is not done.
TEST(PrepareSurface, KeepsZeroLengthEdgesAndRefusesBadWelds) {
  TriMesh m;
  m.vertices = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0)};
  m.faces = {{0, 1, 3}, {1, 2, 3}};
  const PreparedSurface keep = prepare_surface(m);
  EXPECT_EQ(keep.welded_vertices, 0);
  EXPECT_EQ(keep.mesh.faces, m.faces);
  TriMesh bow;
  bow.vertices = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 0), Vec3(-1, 0, 0), Vec3(0, -1, 0)};
  bow.faces = {{0, 1, 2}, {3, 4, 5}};
  const PreparedSurface p = prepare_surface(bow);
  EXPECT_EQ(p.welded_vertices, 0);
  EXPECT_EQ(p.mesh.num_vertices(), 6);
  EXPECT_TRUE(validate_surface(p.mesh).ok());
}

}  // namespace
}  // namespace knitforge
