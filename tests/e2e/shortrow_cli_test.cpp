// End-to-end runs of `knitforge shortrow` (issue: short-row design route).
#include <cmath>

#include <nlohmann/json.hpp>

#include "e2e/cli_fixture.h"
#include "knitforge/convert/map_knittability.h"
#include "knitforge/core/knittability.h"
#include "knitforge/io/knitting_map_csv.h"
#include "knitforge/io/mesh_io.h"
#include "knitforge/io/polyline_obj.h"
#include "knitforge/io/stitch_mesh_ply.h"

using namespace knitforge;
using namespace knitforge_e2e;

TEST_F(Cli, ShortRowHemisphereWritesEveryOutput) {
  const std::string out = path("hemi");
  const CliRun r = run("shortrow hemisphere --edge 4 --stitch 3.2x2.2 -o " + out + " --json");
  ASSERT_EQ(r.code, 0) << r.err;
  for (const char* f : {"stitch_mesh.ply", "knitting_map.csv", "knitting_map.png", "knitting_map.svg",
                        "wales.obj", "field.ply", "target.ply", "relaxed.ply", "shape_error.ply",
                        "distortion.ply", "yarn.obj", "report.json"}) {
    EXPECT_TRUE(fs::exists(out + "/" + f)) << f;
  }
  // A progress line per stage on stderr.
  for (const char* stage : {"geodesic field", "wale curves", "tessellation", "post-processing", "courses",
                            "knitting map", "evaluation"}) {
    EXPECT_NE(r.err.find(stage), std::string::npos) << stage;
  }
  const nlohmann::json report = nlohmann::json::parse(slurp(out + "/report.json"));
  EXPECT_EQ(report, nlohmann::json::parse(r.out)) << "--json prints report.json";
  EXPECT_TRUE(report["knittable"].get<bool>());
  const KnittingMap map = read_knitting_map_csv(out + "/knitting_map.csv");
  EXPECT_TRUE(check_knittability(map, KnitParams{3.2, 2.2}).ok());
  const StitchMesh mesh = read_stitch_mesh_ply(out + "/stitch_mesh.ply");
  EXPECT_EQ(mesh.num_stitches(), report["counts"]["stitches"].get<int>());
  EXPECT_EQ(map.rows, report["counts"]["courses"].get<int>());
  EXPECT_EQ(static_cast<int>(read_polylines_obj(out + "/wales.obj").size()),
            report["counts"]["wales"].get<int>());
  EXPECT_LT(std::abs(report["counts"]["stitches_vs_area"].get<double>()), 0.05);
  EXPECT_GT(report["evaluation"]["shape_error_mm"]["rms"].get<double>(), 0.0);
  EXPECT_EQ(read_mesh(out + "/field.ply").num_faces(), read_mesh(out + "/target.ply").num_faces());
}

TEST_F(Cli, ShortRowBadInputsExitOneAndWriteNothing) {
  const std::string out = path("bad");
  CliRun r = run("shortrow hemisphere --stitch 3.2x2.2 --source plane:1,0,0,500 -o " + out);
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.err.find("misses the surface"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(out + "/report.json"));
  r = run("shortrow hemisphere --source banana:1 -o " + out);
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.err.find("unknown kind 'banana'"), std::string::npos) << r.err;
  r = run("shortrow no_such_file.obj -o " + out);
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.err.find("no_such_file.obj"), std::string::npos) << r.err;
  // A closed surface cannot be knitted as one piece: the message says to open it.
  TriMesh tet;
  tet.vertices = {Vec3(0, 0, 0), Vec3(10, 0, 0), Vec3(0, 10, 0), Vec3(0, 0, 10)};
  tet.faces = {{0, 2, 1}, {0, 1, 3}, {1, 2, 3}, {0, 3, 2}};
  write_mesh(path("tet.obj"), tet);
  r = run("shortrow " + path("tet.obj") + " -o " + out);
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.err.find("is a closed surface"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("open it"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(out + "/report.json"));
}

TEST_F(Cli, ShortRowCutsANonDiskOpenItselfOrAlongTheUsersCut) {
  // A flat annulus (radii 20 and 40 mm) is cut into a disk by the route
  // itself: the plane y = 0 crosses it twice from rim to rim, so the seam
  // follows one of those pieces; with a radial cut from the inner to the
  // outer rim (drawn a little beyond both) that cut is the seam instead.
  TriMesh ring;
  const int n = 48, m = 6;
  for (int j = 0; j <= m; ++j) {
    for (int i = 0; i < n; ++i) {
      const double a = 2 * 3.14159265358979 * (i + 0.5) / n, r = 20.0 + 20.0 * j / m;
      ring.vertices.emplace_back(r * std::cos(a), r * std::sin(a), 0.0);
    }
  }
  for (int j = 0; j < m; ++j) {
    for (int i = 0; i < n; ++i) {
      const int a = j * n + i, b = j * n + (i + 1) % n, c = a + n, d = b + n;
      ring.faces.push_back({a, b, d});
      ring.faces.push_back({a, d, c});
    }
  }
  write_mesh(path("ring.obj"), ring);
  const std::string out = path("ring");
  CliRun r = run("shortrow " + path("ring.obj") + " --no-evaluate --source plane:0,1,0,0 -o " + out);
  EXPECT_EQ(r.code, 0) << r.err;
  EXPECT_TRUE(fs::exists(out + "/seams.obj"));
  nlohmann::json report = nlohmann::json::parse(slurp(out + "/report.json"));
  EXPECT_EQ(report["input"]["boundary_loops"].get<int>(), 2);
  ASSERT_EQ(report["seams"]["count"].get<int>(), 1);
  EXPECT_EQ(report["seams"]["seams"][0]["kind"], "loops");
  EXPECT_TRUE(report["seams"]["seams"][0]["on_source"].get<bool>());
  EXPECT_NEAR(report["seams"]["length_mm"].get<double>(), 20.0, 0.1);  // the rims are 48-gons
  EXPECT_TRUE(report["knittable"].get<bool>());
  write_polylines_obj(path("cut.obj"), {{Vec3(0.0, 19.0, 0.0), Vec3(0.0, 30.0, 0.0), Vec3(0.0, 41.0, 0.0)}});
  r = run("shortrow " + path("ring.obj") + " --no-evaluate --source plane:0,1,0,0 --cut " + path("cut.obj") +
          " -o " + out);
  EXPECT_NE(r.err.find("geodesic field"), std::string::npos) << r.err;  // got past the seams
  report = nlohmann::json::parse(slurp(out + "/report.json"));
  ASSERT_EQ(report["seams"]["count"].get<int>(), 1);
  EXPECT_EQ(report["seams"]["seams"][0]["kind"], "user");
  EXPECT_NEAR(report["seams"]["length_mm"].get<double>(), 20.0, 0.05);
  EXPECT_GT(report["counts"]["stitches"].get<int>(), 0);
}
