// shortrow --tube end to end: design, knitout, simulate (docs/tubes.md "Design").
#include "cli_fixture.h"

namespace knitforge_e2e {
namespace {

TEST_F(Cli, ShortrowTubeDesignsTheSleeveKnitsAndSimulatesIt) {
  const std::string out = path("sleeve");
  CliRun r = run("shortrow sleeve --tube --stitch 7x5.6 --edge 6 --no-report -o " + out);
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.err.find("shima-swg091n2: VALID, knit graph MATCHES the map"), std::string::npos) << r.err;
  const std::string csv = slurp(fs::path(out) / "knitting_map.csv");
  EXPECT_EQ(csv.rfind("course,dir,seam,", 0), 0u) << "not a tubular map";
  EXPECT_NE(csv.find(",D"), std::string::npos) << "the tapered sleeve has decreases";
  const std::string report = slurp(fs::path(out) / "report.json");
  EXPECT_NE(report.find("\"route\": \"tube\""), std::string::npos);
  EXPECT_NE(report.find("\"rounds_off_ideal_by_more_than_1\": 0"), std::string::npos) << report;

  expect_knitted_as_designed(out + "/knitting_map.csv", path("sleeve.k"), "kniterate");
}

TEST_F(Cli, ShortrowTubeKnitsTheSleevesBendWithShortRowsOnBothMachines) {
  const std::string out = path("sleeve_sr");
  CliRun r = run("shortrow sleeve --tube --edge 5 --no-report -o " + out);
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.err.find("shima-swg091n2: VALID, knit graph MATCHES the map"), std::string::npos) << r.err;
  const std::string csv = slurp(fs::path(out) / "knitting_map.csv");
  EXPECT_NE(csv.find(",-,"), std::string::npos) << "no open row (short row)";
  EXPECT_NE(csv.find(",L"), std::string::npos) << "no short-row end";
  const std::string report = slurp(fs::path(out) / "report.json");
  EXPECT_EQ(report.find("\"short_rows\": 0,"), std::string::npos) << report;
  expect_knitted_as_designed(out + "/knitting_map.csv", path("sleeve_sr.k"), "kniterate");

  const std::string plain = path("sleeve_plain");
  r = run("shortrow sleeve --tube --edge 5 --no-tube-short-rows --no-report -o " + plain);
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(slurp(fs::path(plain) / "knitting_map.csv").find(",-,"), std::string::npos) << "a short row without them";
  r = run("shortrow sleeve --no-tube-short-rows --edge 8 -o " + path("sheet"));
  EXPECT_NE(r.code, 0);
  EXPECT_NE(r.err.find("--no-tube-short-rows applies to --tube only"), std::string::npos) << r.err;
}

TEST_F(Cli, ShortrowTubeKnitsAStraightTubeWithoutShortRows) {
  const std::string out = path("tube");
  CliRun r = run("shortrow tube --tube --stitch 7x5.6 --edge 5 --no-report -o " + out);
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.err.find("0 short rows (0 turns) in 0 wedges,"), std::string::npos) << r.err;
  EXPECT_EQ(slurp(fs::path(out) / "knitting_map.csv").find(",-,"), std::string::npos);
}

TEST_F(Cli, ShortrowTubeRefusesASurfaceWithoutTwoLoopsAndWritesNothing) {
  const std::string out = path("hemi");
  CliRun r = run("shortrow hemisphere --tube --edge 5 -o " + out);
  EXPECT_NE(r.code, 0);
  EXPECT_NE(r.err.find("exactly two boundary loops"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(fs::path(out) / "knitting_map.csv"));
  r = run("shortrow tube --tube --source plane:0,0,1,50 -o " + out);
  EXPECT_NE(r.code, 0);
  EXPECT_NE(r.err.find("--tube takes no --source"), std::string::npos) << r.err;
}

}  // namespace
}  // namespace knitforge_e2e
