// End-to-end tests of the knitforge program: exit codes, messages, outputs.
#include <gtest/gtest.h>

#include <sys/wait.h>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "knitforge/convert/stitch_mesh_to_map.h"
#include "knitforge/core/knittability.h"
#include "knitforge/io/knitting_map_csv.h"
#include "knitforge/io/mesh_io.h"
#include "knitforge/io/stitch_mesh_ply.h"

#include "e2e/cli_fixture.h"

namespace fs = std::filesystem;
using namespace knitforge;
using namespace knitforge_e2e;

TEST_F(Cli, HelpAndVersion) {
  CliRun r = run("--help");
  EXPECT_EQ(r.code, 0);
  for (const char* c : {"shape", "sample-map", "check", "relax", "map", "yarn"}) {
    EXPECT_NE(r.out.find(c), std::string::npos) << c;
  }
  EXPECT_EQ(run("relax --help").code, 0);
  EXPECT_EQ(run("--version").code, 0);
}

TEST_F(Cli, UsageErrorsExitTwo) {
  EXPECT_EQ(run("").code, 2);
  EXPECT_EQ(run("no-such-command").code, 2);
  EXPECT_EQ(run("relax").code, 2);  // missing required arguments
  CliRun r = run("relax map.csv -o x.ply --iterations minus");
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("usage error"), std::string::npos);
}

TEST_F(Cli, InputErrorsExitOneWithOneLine) {
  CliRun r = run("relax " + path("missing.csv") + " -o " + path("out.ply"));
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.err.find("missing.csv"), std::string::npos);
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  EXPECT_FALSE(fs::exists(path("out.ply")));

  r = run("relax " + path("missing.csv") + " -o " + path("out.ply") + " --stitch 3x");
  EXPECT_EQ(r.code, 2);  // a malformed option value is a usage error
  EXPECT_NE(r.err.find("--stitch"), std::string::npos);

  std::ofstream(path("bad.csv")) << "course,dir,0,1\n1,<,K,Q\n0,>,K,K\n";
  r = run("relax " + path("bad.csv") + " -o " + path("out.ply"));
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.err.find("bad.csv:2"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(path("out.ply")));
}

TEST_F(Cli, ShapeWritesARealMesh) {
  CliRun r = run("shape hemisphere --edge 6 -o " + path("h.obj"));
  ASSERT_EQ(r.code, 0) << r.err;
  const TriMesh m = read_mesh(path("h.obj"));
  EXPECT_GT(m.num_faces(), 500);
  // Radius 75 mm: every vertex on the sphere.
  for (const auto& v : m.vertices) EXPECT_NEAR(v.norm(), 75.0, 1e-6);
  EXPECT_EQ(run("shape --list").code, 0);
  EXPECT_EQ(run("shape nosuchshape -o " + path("x.obj")).code, 1);
}

TEST_F(Cli, MapRelaxMapRoundTripAndCheck) {
  ASSERT_EQ(
      run("sample-map cup -o " + path("cup.csv") + " -o " + path("cup.png") + " -o " + path("cup.svg")).code,
      0);
  EXPECT_GT(fs::file_size(path("cup.png")), 100u);
  EXPECT_NE(slurp(path("cup.svg")).find("<svg"), std::string::npos);
  CliRun c = run("check " + path("cup.csv"));
  EXPECT_EQ(c.code, 0) << c.out;

  CliRun r = run("relax " + path("cup.csv") + " --stitch 3.5x2.8 -o " + path("cup.ply"));
  ASSERT_EQ(r.code, 0) << r.err;
  const StitchMesh mesh = read_stitch_mesh_ply(path("cup.ply"));
  EXPECT_TRUE(check_knittability(mesh).ok());
  // The cup is 3D: short rows lift it out of the plane.
  double zmin = 1e9, zmax = -1e9;
  for (const auto& v : mesh.vertices) zmin = std::min(zmin, v.z()), zmax = std::max(zmax, v.z());
  EXPECT_GT(zmax - zmin, 5.0);

  ASSERT_EQ(run("map " + path("cup.ply") + " -o " + path("back.csv")).code, 0);
  EXPECT_EQ(read_knitting_map_csv(path("back.csv")), read_knitting_map_csv(path("cup.csv")));
  EXPECT_EQ(slurp(path("back.csv")), slurp(path("cup.csv")));

  CliRun j = run("check " + path("cup.ply") + " --json");
  EXPECT_EQ(j.code, 0);
  EXPECT_NE(j.out.find("\"knittable\": true"), std::string::npos) << j.out;

  CliRun y = run("yarn " + path("cup.ply") + " --stitch 3.5x2.8 -o " + path("yarn.obj"));
  ASSERT_EQ(y.code, 0) << y.err;
  const std::string obj = slurp(path("yarn.obj"));
  EXPECT_NE(obj.find("o yarn_0"), std::string::npos);
}

TEST_F(Cli, CheckFailsOnUnknittableMap) {
  // A short-row end on the boundary: the apex lies on the fabric edge.
  std::ofstream(path("edge.csv")) << "course,dir,0,1,2\n2,>,K,K,K\n1,<,L,K,K\n0,>,K,K,K\n";
  CliRun r = run("check " + path("edge.csv"));
  EXPECT_EQ(r.code, 1);
  EXPECT_FALSE(r.out.empty());
}

TEST_F(Cli, CheckSurface) {
  ASSERT_EQ(run("shape disk --edge 8 -o " + path("d.ply")).code, 0);
  CliRun r = run("check " + path("d.ply"));
  EXPECT_EQ(r.code, 0) << r.out << r.err;
  // Non-manifold: three triangles on one edge.
  std::ofstream(path("nm.obj"))
      << "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 -1 0\nv 0 0 1\nf 1 2 3\nf 2 1 4\nf 1 2 5\n";
  r = run("check " + path("nm.obj"));
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.err.find("nm.obj:"), std::string::npos) << r.err;
}
