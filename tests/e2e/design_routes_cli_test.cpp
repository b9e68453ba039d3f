// End-to-end runs of `knitforge flatten`, `render` and `report` on small
// built-in designs: exit codes, the files each promises, and their content.
#include <nlohmann/json.hpp>

#include "e2e/cli_fixture.h"
#include "knitforge/convert/map_knittability.h"
#include "knitforge/io/knitting_map_csv.h"
#include "knitforge/io/png_image.h"

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
