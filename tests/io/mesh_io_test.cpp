#include "knitforge/io/mesh_io.h"

#include <gtest/gtest.h>

#include <limits>

#include "io/io_test_util.h"

namespace knitforge {
namespace {

using test::TempDir;

TEST(MeshIo, DispatchesByExtensionAndRoundTrips) {
  TempDir dir;
  const TriMesh mesh = test::float_grid_mesh(3, 3);
  for (const std::string name : {"m.obj", "m.ply", "m.off", "m.stl", "UPPER.OBJ", "ascii.Ply"}) {
    SCOPED_TRACE(name);
    MeshWriteOptions opt;
    opt.ascii = name == "ascii.Ply";
    write_mesh(dir.path(name), mesh, opt);
    const TriMesh back = read_mesh(dir.path(name));
    ASSERT_EQ(back.num_faces(), mesh.num_faces());
    for (int f = 0; f < mesh.num_faces(); ++f) {
      for (int k = 0; k < 3; ++k) EXPECT_EQ(back.vertices[back.faces[f][k]], mesh.vertices[mesh.faces[f][k]]);
    }
  }
  // The content decides the format, not a guess: an OBJ named .ply fails as PLY.
  write_mesh(dir.path("x.obj"), mesh);
  const std::string p = dir.write("x.ply", dir.read("x.obj"));
  EXPECT_CONTAINS(test::io_error([&] { read_mesh(p); }), p + ":1: not a PLY file");
}

TEST(MeshIo, UnknownExtensionsAreRejected) {
  TempDir dir;
  const TriMesh mesh = test::grid_mesh(1, 1);
  const std::string p = dir.write("m.dae", "x");
  EXPECT_CONTAINS(test::io_error([&] { read_mesh(p); }), "unknown mesh format '.dae'");
  EXPECT_CONTAINS(test::invalid_input([&] { write_mesh(dir.path("m.3ds"), mesh); }), "unknown mesh format '.3ds'");
  EXPECT_CONTAINS(test::io_error([&] { read_mesh(dir.path("noext")); }), "unknown mesh format");
}

TEST(MeshIo, FailedWritesLeaveTheOldFileAndNoTemporary) {
  TempDir dir;
  const TriMesh mesh = test::grid_mesh(2, 2);
  write_mesh(dir.path("m.ply"), mesh);
  const std::string before = dir.read("m.ply");
  TriMesh bad = mesh;
  bad.vertices[3].y() = std::numeric_limits<double>::quiet_NaN();
  EXPECT_CONTAINS(test::invalid_input([&] { write_mesh(dir.path("m.ply"), bad); }), "vertex 3 has a non-finite");
  MeshWriteOptions opt;
  opt.vertex_colours.resize(2);
  EXPECT_CONTAINS(test::invalid_input([&] { write_mesh(dir.path("m.ply"), mesh, opt); }), "2 vertex colours");
  EXPECT_EQ(dir.read("m.ply"), before);
  EXPECT_EQ(dir.num_files(), 1u);
  EXPECT_CONTAINS(test::io_error([&] { write_mesh(dir.path("nodir/m.obj"), mesh); }), "cannot create file");
}

TEST(MeshIo, WritingIsDeterministic) {
  TempDir dir;
  const TriMesh mesh = test::grid_mesh(3, 2);
  for (const std::string ext : {"obj", "ply", "off", "stl"}) {
    write_mesh(dir.path("a." + ext), mesh);
    write_mesh(dir.path("b." + ext), mesh);
    EXPECT_EQ(dir.read("a." + ext), dir.read("b." + ext)) << ext;
  }
}

}  // namespace
}  // namespace knitforge

namespace knitforge {
namespace {

// The shared test meshes read with the counts their README gives, and survive
// a binary PLY round trip bit for bit.
TEST(MeshIo, ReadsTheSharedTestMeshes) {
  struct Mesh {
    const char* name;
    int vertices, faces;
  };
  test::TempDir dir;
  for (const Mesh& m : {Mesh{"triple_peak.obj", 5105, 10016}, Mesh{"mannequin_front.obj", 13648, 26593}}) {
    const std::string path = std::string(KNITFORGE_SHARED_DATA) + "/" + m.name;
    if (!std::filesystem::exists(path)) GTEST_SKIP() << path << " not present";
    const TriMesh mesh = read_mesh(path);
    EXPECT_EQ(mesh.num_vertices(), m.vertices) << m.name;
    EXPECT_EQ(mesh.num_faces(), m.faces) << m.name;
    write_mesh(dir.path("copy.ply"), mesh);
    test::expect_same_mesh(read_mesh(dir.path("copy.ply")), mesh);
  }
}

}  // namespace
}  // namespace knitforge
