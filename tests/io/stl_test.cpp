#include "knitforge/io/stl.h"

#include <gtest/gtest.h>

#include <cstring>
#include <limits>

#include <fmt/core.h>

#include "io/io_test_util.h"

namespace knitforge {
namespace {

using test::TempDir;

// STL loses the vertex order; compare the corner positions face by face.
void expect_same_geometry(const TriMesh& read, const TriMesh& orig) {
  ASSERT_EQ(read.num_faces(), orig.num_faces());
  EXPECT_EQ(read.num_vertices(), orig.num_vertices());  // welded back to shared vertices
  for (int f = 0; f < orig.num_faces(); ++f) {
    for (int k = 0; k < 3; ++k) {
      EXPECT_EQ(read.vertices[read.faces[f][k]], orig.vertices[orig.faces[f][k]]) << "face " << f;
    }
  }
}

TEST(Stl, BinaryAndAsciiRoundTripWeldVertices) {
  TempDir dir;
  const TriMesh mesh = test::float_grid_mesh(4, 3);
  MeshWriteOptions opt;
  write_stl(dir.path("b.stl"), mesh, opt);
  EXPECT_EQ(dir.read("b.stl").size(), 84u + 50u * mesh.faces.size());
  expect_same_geometry(read_stl(dir.path("b.stl")), mesh);
  opt.ascii = true;
  write_stl(dir.path("a.stl"), mesh, opt);
  EXPECT_EQ(dir.read("a.stl").substr(0, 16), "solid knitforge\n");
  expect_same_geometry(read_stl(dir.path("a.stl")), mesh);
}

TEST(Stl, BinaryHeaderStartingWithSolidIsStillBinary) {
  TempDir dir;
  const TriMesh mesh = test::float_grid_mesh(2, 2);
  write_stl(dir.path("b.stl"), mesh);
  std::string bytes = dir.read("b.stl");
  bytes.replace(0, 11, "solid cube ");
  expect_same_geometry(read_stl(dir.write("solid.stl", bytes)), mesh);
}

TEST(Stl, TrianglesCollapsedByWeldingAreDroppedAndColoursRejected) {
  TempDir dir;
  const std::string p = dir.write("d.stl",
                                  "solid t\n"
                                  "facet normal 0 0 1\n outer loop\n  vertex 0 0 0\n  vertex 1 0 0\n  vertex 0 1 0\n"
                                  " endloop\nendfacet\n"
                                  "FACET NORMAL 0 0 0\n OUTER LOOP\n  VERTEX 1 0 0\n  VERTEX 1 0 0\n  VERTEX 0 1 0\n"
                                  " ENDLOOP\nENDFACET\n"
                                  "facet normal 0 0 1\n outer loop\n  vertex 1 0 0\n  vertex 1 1 0\n  vertex -0 1 0\n"
                                  " endloop\nendfacet\n"
                                  "endsolid t\n");
  const TriMesh m = read_stl(p);
  ASSERT_EQ(m.num_faces(), 2);
  EXPECT_EQ(m.num_vertices(), 4);  // -0 welded with 0
  EXPECT_EQ(m.faces[1][2], 2);
  MeshWriteOptions opt;
  opt.face_colours.assign(2, {});
  EXPECT_CONTAINS(test::invalid_input([&] { write_stl(dir.path("c.stl"), m, opt); }), "STL cannot store");
}

TEST(Stl, MalformedFilesNameFileAndLineOrByte) {
  TempDir dir;
  const TriMesh mesh = test::float_grid_mesh(2, 1);  // 4 triangles
  write_stl(dir.path("good.stl"), mesh);
  const std::string good = dir.read("good.stl");
  // Truncated binary: ends inside triangle 2 (starts at byte 84 + 100).
  {
    const std::string p = dir.write("cut.stl", good.substr(0, good.size() - 70));
    const std::string msg = test::io_error([&] { read_stl(p); });
    EXPECT_CONTAINS(msg, p + ": byte 184: the header declares 4 triangles");
  }
  // NaN coordinate in triangle 1, second corner, y.
  {
    std::string bad = good;
    const float nan = std::numeric_limits<float>::quiet_NaN();
    std::memcpy(&bad[84 + 50 + 12 + 12 + 4], &nan, 4);
    const std::string p = dir.write("nan.stl", bad);
    EXPECT_CONTAINS(test::io_error([&] { read_stl(p); }), fmt::format("{}: byte {}: triangle 1", p, 84 + 50 + 28));
  }
  // Non-manifold binary: three copies of a triangle on one edge.
  {
    TriMesh nm;
    nm.vertices = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, -1, 0), Vec3(0, 0, 1)};
    nm.faces = {{0, 1, 2}, {1, 0, 3}, {0, 1, 4}};
    write_stl(dir.path("nm.stl"), nm);
    const std::string p = dir.path("nm.stl");
    EXPECT_CONTAINS(test::io_error([&] { read_stl(p); }), p + ": byte 184: edge (0, 1) is shared by 3 faces");
  }
  const std::string facet = "facet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\nendloop\nendfacet\n";
  struct Case {
    std::string name, content, where, what;
  };
  const std::vector<Case> cases = {
      {"empty.stl", "", ": file is empty", "empty"},
      {"tiny.stl", "abc", ": byte 3:", "too short"},
      {"noend.stl", "solid x\n" + facet, ":8:", "'endsolid' is missing"},
      {"infacet.stl", "solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\n", ":4:", "inside a facet"},
      {"keyword.stl", "solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\nendfacet\n",
       ":7:", "expected 'vertex' or 'endloop'"},
      {"nan.stl", "solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 inf 0\n", ":5:", "not finite"},
      {"twov.stl", "solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nendloop\n", ":6:",
       "it needs at least 3"},
      {"nofaces.stl", "solid x\nendsolid x\n", ": the file holds 0 vertices", "no faces"},
      {"orient.stl", "solid x\n" + facet + facet + "endsolid\n", ":9:", "orientation"},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.name);
    const std::string p = dir.write(c.name, c.content);
    const std::string msg = test::io_error([&] { read_stl(p); });
    EXPECT_CONTAINS(msg, p + c.where);
    EXPECT_CONTAINS(msg, c.what);
  }
}

}  // namespace
}  // namespace knitforge
