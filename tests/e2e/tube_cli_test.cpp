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

  const std::string k = path("sleeve.k");
  r = run("knitout " + out + "/knitting_map.csv --machine kniterate -o " + k);
  ASSERT_EQ(r.code, 0) << r.err;
  r = run("simulate " + k + " --machine kniterate --against " + out + "/knitting_map.csv");
  EXPECT_EQ(r.code, 0) << r.err << r.out;
  EXPECT_NE((r.out + r.err).find("MATCHES the map"), std::string::npos) << r.err << r.out;
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
