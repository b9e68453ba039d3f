// The machine end on the command line (issue 12): design commands write the
// program, check --machine agrees with knitout, simulate judges third-party
// style programs as the machines' software does (issue 18).
#include <nlohmann/json.hpp>

#include "e2e/cli_fixture.h"

namespace knitforge_e2e {

TEST_F(Cli, ShortRowWritesAVerifiedProgramAndTheKnittersSummary) {
  const CliRun r = run("shortrow disk --stitch 5x4 --no-evaluate --no-report -o " + path("d"));
  ASSERT_EQ(r.code, 0) << r.err;
  ASSERT_TRUE(fs::exists(path("d/knitout.k")));
  const auto rep = nlohmann::json::parse(slurp(path("d/report.json")));
  const auto& m = rep["machine"];
  EXPECT_EQ(m["profile"], "shima-swg091n2");
  EXPECT_EQ(m["verdict"], "VALID");
  EXPECT_EQ(m["matches_map"], true);
  EXPECT_EQ(m["stitches"], rep["counts"]["stitches"]);
  EXPECT_GT(m["knit_time_s"].get<double>(), 0.0);
  EXPECT_EQ(m["yarn_m"][0]["role"], "main");
  EXPECT_EQ(m["shaping"]["transfer_stitches"], 0);  // short rows only: no short columns
  // The program on disk is the one judged: the simulator agrees.
  const CliRun s = run("simulate " + path("d/knitout.k") + " --against " + path("d/knitting_map.csv"));
  EXPECT_EQ(s.code, 0) << s.out;
  EXPECT_NE(s.out.find("VALID on machine 'shima-swg091n2': 0 error(s), 0 warning(s)"), std::string::npos) << s.out;
  EXPECT_NE(s.out.find("MATCHES"), std::string::npos) << s.out;
}

TEST_F(Cli, DesignCommandsTakeTheMachine) {
  ASSERT_EQ(run("shortrow disk --stitch 5x4 --no-evaluate --no-report --machine kniterate -o " + path("k")).code, 0);
  const std::string k = slurp(path("k/knitout.k"));
  EXPECT_NE(k.find(";;Machine: Kniterate\n"), std::string::npos);
  EXPECT_NE(k.find("x-roller-advance"), std::string::npos);  // the waste section's settings
  // the first pass of every carrier runs right (the Kniterate parks them left)
  const CliRun s = run("simulate " + path("k/knitout.k") + " --machine kniterate --strict all");
  EXPECT_EQ(s.code, 0) << s.out;
  ASSERT_EQ(run("flatten disk --stitch 5x4 --no-evaluate --machine brother-kh868 -o " + path("b")).code, 0);
  EXPECT_TRUE(fs::exists(path("b/instructions.html")));
  EXPECT_FALSE(fs::exists(path("b/knitout.k")));
  ASSERT_EQ(run("shortrow disk --stitch 5x4 --no-evaluate --no-report --no-knitout -o " + path("n")).code, 0);
  EXPECT_FALSE(fs::exists(path("n/knitout.k")));
  EXPECT_EQ(nlohmann::json::parse(slurp(path("n/report.json")))["machine"]["verdict"], "NOT WRITTEN");
  EXPECT_EQ(run("shortrow disk --no-report --machine knitpro9000 -o " + path("x")).code, 1);
}

TEST_F(Cli, CheckAndKnitoutAgreePerMachine) {
  // A map with three edge wales ending in one course at the start of a row,
  // knitted by an edge bind-off chain, and a map the seed's rules reject.
  {
    std::ofstream f(path("edge.csv"));
    f << "course,dir,0,1,2,3,4,5,6,7\n"
         "3,<,K,K,K,K,K,.,.,.\n"
         "2,>,K,K,K,K,K,.,.,.\n"
         "1,<,K,K,K,K,K,K,K,K\n"
         "0,>,K,K,K,K,K,K,K,K\n";
  }
  for (const char* m : {"shima-swg091n2", "kniterate", "generic"}) {
    const CliRun c = run(std::string("check ") + path("edge.csv") + " --machine " + m);
    EXPECT_EQ(c.code, 0) << c.out;
    const CliRun k = run(std::string("knitout ") + path("edge.csv") + " --machine " + m + " -o " + path("edge.k"));
    EXPECT_EQ(k.code, 0) << k.err;
    EXPECT_NE(k.err.find("(2 bound off at the edge)"), std::string::npos) << k.err;
  }
  {
    std::ofstream f(path("broken.csv"));
    f << "course,dir,0,1,2,3\n"
         "1,<,K,K,.,K\n"
         "0,>,K,K,K,K\n";
  }
  EXPECT_EQ(run("check " + path("broken.csv")).code, 1);
  const CliRun k = run("knitout " + path("broken.csv") + " -o " + path("broken.k"));
  EXPECT_EQ(k.code, 1);
  EXPECT_NE(k.err.find("not knittable"), std::string::npos) << k.err;
  EXPECT_FALSE(fs::exists(path("broken.k")));
  // --machine none: the seed's rules only; --json names the machine
  EXPECT_EQ(nlohmann::json::parse(run("check " + path("edge.csv") + " --json").out)["machine"], "shima-swg091n2");
  EXPECT_EQ(nlohmann::json::parse(run("check " + path("edge.csv") + " --machine none --json").out)["machine"], "none");
}

TEST_F(Cli, SimulateExitsZeroWithWarningsAndStrictMakesThemErrors) {
  // A swatch in the style of published test programs: it ends by dropping
  // its last course.
  {
    std::ofstream f(path("swatch.k"));
    f << ";!knitout-2\n;;Carriers: 1 2 3 4 5 6 7 8 9 10\n"
         "inhook 3\ntuck - f4 3\ntuck - f2 3\ntuck + f1 3\ntuck + f3 3\n"
         "knit - f4 3\nknit - f3 3\nknit - f2 3\nknit - f1 3\nreleasehook 3\n"
         "knit + f1 3\nknit + f2 3\nknit + f3 3\nknit + f4 3\n"
         "outhook 3\ndrop f1\ndrop f2\ndrop f3\ndrop f4\n";
  }
  const CliRun s = run("simulate " + path("swatch.k"));
  EXPECT_EQ(s.code, 0) << s.out;
  EXPECT_NE(s.out.find("VALID on machine 'shima-swg091n2': 0 error(s), 4 warning(s)"), std::string::npos) << s.out;
  EXPECT_NE(s.out.find("[drop/run]"), std::string::npos) << s.out;
  EXPECT_EQ(run("simulate " + path("swatch.k") + " --strict drop").code, 1);
  EXPECT_EQ(run("simulate " + path("swatch.k") + " --strict float,loops-left").code, 0);
  const CliRun bad = run("simulate " + path("swatch.k") + " --strict drops");
  EXPECT_EQ(bad.code, 1);
  EXPECT_NE(bad.err.find("unknown category 'drops'"), std::string::npos) << bad.err;
  const auto j = nlohmann::json::parse(run("simulate " + path("swatch.k") + " --json").out);
  EXPECT_EQ(j["valid"], true);
  EXPECT_EQ(j["counts"]["drop"]["warnings"], 4);
  EXPECT_EQ(j["diagnostics"][0]["check"], "run");
  // The rules of a machine, with their sources.
  const CliRun rules = run("simulate --rules --machine kniterate");
  EXPECT_EQ(rules.code, 0);
  EXPECT_NE(rules.out.find("| `first-pass-direction` | carrier-direction | error |"), std::string::npos) << rules.out;
  EXPECT_EQ(run("simulate").code, 2);
}

}  // namespace knitforge_e2e

namespace knitforge_e2e {

TEST_F(Cli, SimulateReportDrawsAProgramsFabric) {
  const std::string prog =
      (fs::path(KNITFORGE_TESTS_DIR) / "machine" / "data" / "published_style" / "swatch_drop.k").string();
  const CliRun r = run("simulate " + prog + " --machine kniterate --report " + path("view"));
  EXPECT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.err.find("sheet, 8 courses x 10 wales; 10 of 10 findings placed on the fabric"), std::string::npos)
      << r.err;
  for (const char* f : {"report.html", "report.json", "stitch_mesh.ply", "yarn.obj", "knitting_map.csv", "knitout.k"})
    EXPECT_TRUE(fs::exists(path(std::string("view/") + f))) << f;
  const std::string html = slurp(path("view/report.html"));
  EXPECT_NE(html.find("knitforge-data"), std::string::npos);
  // an invalid program still gets its view, and the exit code says invalid
  {
    std::ofstream f(path("bad.k"));
    f << ";!knitout-2\n;;Carriers: 1 2 3 4 5 6\nin 1\ntuck - f2 1\nknit - f2 1\nrack 9\nout 1\n";
  }
  const CliRun b = run("simulate " + path("bad.k") + " --machine kniterate --report " + path("bad"));
  EXPECT_EQ(b.code, 1);
  EXPECT_TRUE(fs::exists(path("bad/report.json")));
}

}  // namespace knitforge_e2e
