// End-to-end runs of `knitforge flatten`, `render` and `report` on small
// built-in designs: exit codes, the files each promises, and their content.
#include <nlohmann/json.hpp>

#include "e2e/cli_fixture.h"
#include "knitforge/convert/map_knittability.h"
#include "knitforge/io/knitting_map_csv.h"
#include "knitforge/io/png_image.h"
#include "knitforge/io/mesh_io.h"
#include "knitforge/geometry/shapes.h"
#include <cmath>

using namespace knitforge;
using namespace knitforge_e2e;

TEST_F(Cli, FlattenHemisphereWithAutoDartsIsKnittableAndReported) {
  const std::string out = path("flat");
  const CliRun r = run("flatten hemisphere --edge 4 --stitch 3.5x2.8 --auto-darts 4 --no-evaluate -o " + out);
  ASSERT_EQ(r.code, 0) << r.err;
  for (const char* f : {"knitting_map.csv", "pattern.svg", "distortion.ply", "report.json", "report.html"}) {
    EXPECT_TRUE(fs::exists(out + "/" + f)) << f;
  }
  const KnittingMap map = read_knitting_map_csv(out + "/knitting_map.csv");
  EXPECT_TRUE(check_knittability(map, KnitParams{3.5, 2.8}).ok());
  EXPECT_NE(slurp(out + "/report.html").find("knitforge-data"), std::string::npos);
}

TEST_F(Cli, RenderWritesEachFormatAndReportRebuildsThePage) {
  ASSERT_EQ(run("sample-map cup -o " + path("cup.csv")).code, 0);
  ASSERT_EQ(run("relax " + path("cup.csv") + " --stitch 3.5x2.8 -o " + path("cup.ply")).code, 0);
  const CliRun png = run("render " + path("cup.ply") + " --mesh --size 320x240 -o " + path("cup.png"));
  ASSERT_EQ(png.code, 0) << png.err;
  const RgbImage img = read_png(path("cup.png"));
  EXPECT_EQ(img.width, 320);
  EXPECT_EQ(img.height, 240);
  ASSERT_EQ(run("render " + path("cup.ply") + " --ply-vertices 1 -o " + path("cup.glb")).code, 0);
  EXPECT_EQ(slurp(path("cup.glb")).substr(0, 4), "glTF");
  // Full detail (the default for a design this small) vs. preview detail.
  ASSERT_EQ(run("render " + path("cup.ply") + " -o " + path("full.glb")).code, 0);
  ASSERT_EQ(run("render " + path("cup.ply") + " --detail preview -o " + path("preview.glb")).code, 0);
  EXPECT_LT(2 * fs::file_size(path("preview.glb")), fs::file_size(path("full.glb")));
  EXPECT_EQ(run("render " + path("cup.ply") + " --detail coarse -o " + path("x.glb")).code, 2);
  ASSERT_EQ(run("render " + path("cup.ply") + " --mesh -o " + path("cup.svg")).code, 0);
  EXPECT_NE(slurp(path("cup.svg")).find("<svg"), std::string::npos);
  EXPECT_EQ(run("render " + path("cup.ply") + " -o " + path("cup.bmp")).code, 1);

  fs::create_directories(path("design"));
  fs::copy_file(path("cup.ply"), path("design/stitch_mesh.ply"));
  fs::copy_file(path("cup.csv"), path("design/knitting_map.csv"));
  const CliRun rep = run("report " + path("design"));
  ASSERT_EQ(rep.code, 0) << rep.err;
  EXPECT_TRUE(fs::exists(path("design/report.html")));
  fs::create_directories(path("empty"));
  EXPECT_EQ(run("report " + path("empty")).code, 1);
}

// The repro: a bumpy disk (two bumps and a dip, radius 80 mm) at
// 3 x 2 mm with --auto-darts 3 folded the pattern (13 flipped triangles, max
// log sigma 3.6) and reported success. Now: no fold, a bounded maximum, and
// every kept dart lowers both the RMS and the maximum.
TEST_F(Cli, FlattenBumpyDiskWithAutoDartsNeverFolds) {
  TriMesh m = flat_disk(80.0, 4.0);
  for (Vec3& p : m.vertices) {
    auto g = [&](double cx, double cy, double a) {
      return a * std::exp(-((p.x() - cx) * (p.x() - cx) + (p.y() - cy) * (p.y() - cy)) / (2 * 12.0 * 12.0));
    };
    p.z() = g(-35, 15, 30) + g(30, 25, 30) + g(5, -35, -30);
  }
  write_mesh(path("bumpy.obj"), m);
  const std::string out = path("flat");
  const CliRun r = run("flatten " + path("bumpy.obj") + " --stitch 3x2 --auto-darts 3 --no-evaluate -o " + out);
  ASSERT_EQ(r.code, 0) << r.err;
  const auto rep = nlohmann::json::parse(slurp(out + "/report.json"));
  const auto& f = rep["flattening"];
  EXPECT_GT(f["arap_flipped_faces"].get<int>(), 0);  // ARAP alone folds this disk
  EXPECT_TRUE(f["injective_solver"].get<bool>());
  EXPECT_TRUE(f["flipped_faces"].empty());
  EXPECT_EQ(f["distortion"]["flipped_faces"].get<int>(), 0);
  EXPECT_LT(f["distortion"]["max_abs_log_sigma"].get<double>(), 1.5);
  const auto& seq = f["distortion_sequence"];
  for (size_t k = 2; k < seq.size(); ++k) {  // entry 0: no darts; 1..: after each kept dart
    EXPECT_LT(seq[k]["rms_log_sigma"].get<double>(), seq[k - 1]["rms_log_sigma"].get<double>());
    EXPECT_LT(seq[k]["max_abs_log_sigma"].get<double>(), seq[k - 1]["max_abs_log_sigma"].get<double>());
  }
  EXPECT_NE(r.err.find("automatic darts:"), std::string::npos);
}
