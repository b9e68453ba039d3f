// End-to-end runs of `knitforge support`, `close` and `thicken` (seed §2.C).
#include "e2e/cli_fixture.h"
#include "knitforge/geometry/alpha_close.h"
#include "knitforge/geometry/halfedges.h"
#include "knitforge/geometry/mesh_measures.h"
#include "knitforge/io/mesh_io.h"

using namespace knitforge;
using namespace knitforge_e2e;

namespace {

// Read back: every edge shared by exactly two faces, consistently oriented.
void expect_watertight_file(const std::string& file) {
  const TriMesh m = read_mesh(file);
  ASSERT_GT(m.num_faces(), 0);
  const Halfedges he = build_halfedges(m.num_vertices(), m.faces);
  EXPECT_TRUE(he.boundary_loops().empty()) << file;
  for (int h = 0; h < he.num_halfedges(); ++h) ASSERT_GE(he.opposite(h), 0) << file;
  EXPECT_GT(enclosed_volume(m), 0.0) << file << " is outward-facing";
}

}  // namespace

TEST_F(Cli, SupportOfBuiltInHemisphereIsAWatertightStl) {
  const std::string out = path("support.stl");
  CliRun r = run("support hemisphere --edge 6 --offset 1.5 --base-height 8 -o " + out);
  ASSERT_EQ(r.code, 0) << r.err;
  expect_watertight_file(out);
  const BoundingBox box = bounding_box(read_mesh(out));
  EXPECT_NEAR(box.max.z(), 75.0 - 1.5, 0.1);
  EXPECT_LT(box.min.z(), -8.0 + 1e-3);
  EXPECT_NE(r.err.find("support of built-in hemisphere"), std::string::npos) << r.err;
  // Rectangle base and a shell.
  r = run("support triple-peak --edge 10 --base rectangle --margin 4 -o " + path("tp.ply"));
  ASSERT_EQ(r.code, 0) << r.err;
  expect_watertight_file(path("tp.ply"));
  EXPECT_NEAR(bounding_box(read_mesh(path("tp.ply"))).size().x(), 150.0 + 8.0, 0.5);
  r = run("support hemisphere --edge 6 --thickness 3 -o " + path("shell.stl"));
  ASSERT_EQ(r.code, 0) << r.err;
  expect_watertight_file(path("shell.stl"));
}

TEST_F(Cli, ThickenAndCloseAMeshFileWithUnits) {
  // A surface in cm: the output is in mm.
  TriMesh grid;
  for (int j = 0; j <= 3; ++j)
    for (int i = 0; i <= 3; ++i) grid.vertices.emplace_back(i, j, 0.1 * i * j);
  for (int j = 0; j < 3; ++j)
    for (int i = 0; i < 3; ++i) {
      const int a = j * 4 + i;
      grid.faces.push_back({a, a + 1, a + 5});
      grid.faces.push_back({a, a + 5, a + 4});
    }
  write_mesh(path("grid.obj"), grid);
  CliRun r = run("thicken " + path("grid.obj") + " --units cm --thickness 2 -o " + path("thick.stl"));
  ASSERT_EQ(r.code, 0) << r.err;
  expect_watertight_file(path("thick.stl"));
  EXPECT_NEAR(bounding_box(read_mesh(path("thick.stl"))).size().x(), 30.0, 1.0);
  r = run("close hemisphere --edge 10 --alpha 10 --offset 2 -o " + path("closed.obj"));
  ASSERT_EQ(r.code, 0) << r.err;
  expect_watertight_file(path("closed.obj"));
  EXPECT_NE(r.err.find("holes capped: 1"), std::string::npos) << r.err;
}

TEST_F(Cli, BadArgumentsExitNonZeroAndWriteNothing) {
  CliRun r = run("thicken hemisphere -o " + path("a.stl"));  // --thickness is required
  EXPECT_EQ(r.code, 2);
  r = run("thicken hemisphere --thickness -1 -o " + path("a.stl"));
  EXPECT_EQ(r.code, 2);
  r = run("close no_such_file.obj -o " + path("a.stl"));
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.err.find("no_such_file.obj"), std::string::npos) << r.err;
  r = run("support hemisphere --edge 6 --base circle -o " + path("a.stl"));
  EXPECT_EQ(r.code, 2);
  r = run("support hemisphere --edge 6 -o " + path("a.xyz"));
  EXPECT_EQ(r.code, 1);
  // A closed surface has no boundary loop for a base.
  TriMesh tet;
  tet.vertices = {Vec3(0, 0, 0), Vec3(10, 0, 0), Vec3(0, 10, 0), Vec3(0, 0, 10)};
  tet.faces = {{0, 2, 1}, {0, 1, 3}, {1, 2, 3}, {0, 3, 2}};
  write_mesh(path("tet.obj"), tet);
  r = run("support " + path("tet.obj") + " -o " + path("a.stl"));
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.err.find("boundary loops"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(path("a.stl")));
  EXPECT_FALSE(fs::exists(path("a.xyz")));
}
