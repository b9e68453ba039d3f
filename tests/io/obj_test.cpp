#include "knitforge/io/obj.h"

#include <gtest/gtest.h>

#include "io/io_test_util.h"

namespace knitforge {
namespace {

using test::TempDir;

TEST(Obj, RoundTripIsBitExact) {
  TempDir dir;
  const TriMesh mesh = test::grid_mesh(4, 3);
  write_obj(dir.path("m.obj"), mesh);
  test::expect_same_mesh(read_obj(dir.path("m.obj")), mesh);
}

TEST(Obj, VertexColoursAreWrittenAndIgnoredOnReading) {
  TempDir dir;
  const TriMesh mesh = test::grid_mesh(1, 1);
  MeshWriteOptions opt;
  opt.vertex_colours = {{255, 0, 0}, {0, 255, 0}, {0, 0, 255}, {51, 51, 51}};
  write_obj(dir.path("c.obj"), mesh, opt);
  const std::string text = dir.read("c.obj");
  EXPECT_CONTAINS(text, " 1 0 0\n");
  EXPECT_CONTAINS(text, " 0.2 0.2 0.2\n");
  test::expect_same_mesh(read_obj(dir.path("c.obj")), mesh);
}

TEST(Obj, FaceColoursAndBadMeshesAreRejectedOnWriting) {
  TempDir dir;
  TriMesh mesh = test::grid_mesh(1, 1);
  MeshWriteOptions opt;
  opt.face_colours = {{1, 2, 3}, {4, 5, 6}};
  EXPECT_CONTAINS(test::invalid_input([&] { write_obj(dir.path("a.obj"), mesh, opt); }), "face colours");
  mesh.faces[1][2] = 9;
  EXPECT_CONTAINS(test::invalid_input([&] { write_obj(dir.path("a.obj"), mesh); }), "face 1 uses vertex 9");
  EXPECT_EQ(dir.num_files(), 0u);  // nothing left behind
}

TEST(Obj, IndexFormsNegativeIndicesCommentsAndPolygons) {
  TempDir dir;
  const std::string p = dir.write("forms.obj",
                                  "# a comment\r\n"
                                  "mtllib x.mtl\r\n"
                                  "o square\r\n"
                                  "v 0 0 0\r\n"
                                  "v 1 0 0 # trailing comment\r\n"
                                  "v 1 1 0 1.0\r\n"
                                  "v 0 1 0 0.5 0.5 0.5\r\n"
                                  "vt 0 0\r\nvt 1 0\r\nvt 1 1\r\nvn 0 0 1\r\n"
                                  "g part\r\ns 1\r\nusemtl wool\r\n"
                                  "f 1/1/1 2/2/1 3/3/1 4//1\r\n"
                                  "v 2 0 0\r\n"
                                  "v +2 1 0\r\n"
                                  "f -4 -2 -1 -3\r\n"
                                  "l 1 2\r\n");
  const TriMesh m = read_obj(p);
  ASSERT_EQ(m.num_vertices(), 6);
  EXPECT_EQ(m.vertices[5], Vec3(2, 1, 0));
  const std::vector<std::array<int, 3>> expected = {{0, 1, 2}, {0, 2, 3}, {2, 4, 5}, {2, 5, 3}};
  EXPECT_EQ(m.faces, expected);
}

TEST(Obj, ZeroAreaTrianglesAreAllowed) {
  TempDir dir;
  const TriMesh m = read_obj(dir.write("z.obj", "v 0 0 0\nv 1 0 0\nv 2 0 0\nv 0 1 0\nf 1 2 3\nf 1 3 4\n"));
  EXPECT_EQ(m.num_faces(), 2);
}

struct BadCase {
  const char* name;
  const char* content;
  const char* where;  // expected "<file>:<line>" suffix, or ": " for no line
  const char* what;
};

TEST(Obj, MalformedFilesNameFileAndLine) {
  const BadCase cases[] = {
      {"empty.obj", "", "", "file is empty"},
      {"blank.obj", "\n  \n", "", "file is empty"},
      {"nofaces.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\n", "", "no faces"},
      {"range.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\nf 1 3 4\n", ":5:", "out of range"},
      {"zero.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 0 1 2\n", ":4:", "index 0"},
      {"neg.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf -1 -2 -4\n", ":4:", "before the first vertex"},
      {"nan.obj", "v 0 0 0\nv nan 0 0\nv 0 1 0\nf 1 2 3\n", ":2:", "not finite"},
      {"inf.obj", "v 0 0 0\nv 1 0 0\nv 0 -inf 0\nf 1 2 3\n", ":3:", "not finite"},
      {"junk.obj", "v 0 0 0\nv 1 0x 0\nv 0 1 0\nf 1 2 3\n", ":2:", "'0x' is not a number"},
      {"short.obj", "v 0 0\n", ":1:", "three coordinates"},
      {"twoface.obj", "v 0 0 0\nv 1 0 0\nf 1 2\n", ":3:", "at least 3"},
      {"badref.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 a\n", ":4:", "not a vertex index"},
      {"degenerate.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 1\n", ":4:", "twice"},
      // Three faces on edge (1, 2) (0-based 0, 1): the third one, line 7, is reported.
      {"nonmanifold.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 -1 0\nf 1 2 3\nf 2 1 4\nf 1 2 5\nv 0 0 1\n", ":7:",
       "shared by 3 faces"},
      {"orient.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\n# c\nf 1 2 3\nf 2 3 4\n", ":7:", "orientation"},
      {"bowtie.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nv -1 0 0\nv 0 -1 0\nf 1 2 3\nf 1 4 5\n", ":6:", "non-manifold"},
  };
  TempDir dir;
  for (const BadCase& c : cases) {
    SCOPED_TRACE(c.name);
    const std::string p = dir.write(c.name, c.content);
    const std::string msg = test::io_error([&] { read_obj(p); });
    EXPECT_CONTAINS(msg, p + c.where);
    EXPECT_CONTAINS(msg, c.what);
  }
  const std::string missing = dir.path("missing.obj");
  EXPECT_CONTAINS(test::io_error([&] { read_obj(missing); }), missing + ": cannot open");
}

TEST(Obj, NonManifoldMessageListsTheFaceLines) {
  TempDir dir;
  const std::string p =
      dir.write("nm.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 -1 0\nv 0 0 1\nf 1 2 3\nf 2 1 4\nf 1 2 5\n");
  const std::string msg = test::io_error([&] { read_obj(p); });
  EXPECT_CONTAINS(msg, p + ":8: edge (0, 1) is shared by 3 faces");
  EXPECT_CONTAINS(msg, "face 0 at line 6, face 1 at line 7, face 2 at line 8");
}

}  // namespace
}  // namespace knitforge
