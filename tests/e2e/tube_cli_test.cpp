// Tubes on the command line (issue 15): a built-in tube map goes to a program
// knitted in the round on both beds that the simulator calls VALID and that
// MATCHES the map, on the Shima and the Kniterate.
#include <nlohmann/json.hpp>

#include "e2e/cli_fixture.h"

namespace knitforge_e2e {

TEST_F(Cli, TubeMapsAreKnittedInTheRoundAndMatch) {
  for (const char* name : {"tube", "tapered-tube"}) {
    SCOPED_TRACE(name);
    const std::string csv = path(std::string(name) + ".csv");
    // small tubes keep the test fast
    const std::string size = std::string(name) == "tube" ? " --round 12 --rows 6" : " --round 16 --rows 8 "
                                                                                     "--decrease-rounds 2 --every 3";
    const CliRun m = run("sample-map " + std::string(name) + size + " -o " + csv + " -o " + path("m.svg"));
    ASSERT_EQ(m.code, 0) << m.err;
    EXPECT_NE(m.err.find("tubular map"), std::string::npos) << m.err;
    EXPECT_EQ(slurp(csv).rfind("course,dir,seam,0,", 0), 0u);
    EXPECT_NE(slurp(path("m.svg")).find("class=\"fold\""), std::string::npos);
    const CliRun c = run("check " + csv);
    EXPECT_EQ(c.code, 0) << c.out << c.err;
    for (const char* machine : {"shima-swg091n2", "kniterate"}) {
      SCOPED_TRACE(machine);
      const std::string k = path(std::string(name) + "_" + machine + ".k");
      const CliRun w = run("knitout " + csv + " --machine " + machine + " -o " + k);
      ASSERT_EQ(w.code, 0) << w.err;
      const std::string text = slurp(k);
      EXPECT_NE(text.find("knit - b"), std::string::npos);  // the back half on the back bed
      const CliRun s = run("simulate " + k + " --machine " + machine + " --against " + csv + " --strict all");
      EXPECT_EQ(s.code, 0) << s.out << s.err;
      EXPECT_NE(s.out.find(std::string("VALID on machine '") + machine + "': 0 error(s), 0 warning(s)"),
                std::string::npos)
          << s.out;
      EXPECT_NE(s.out.find("MATCHES"), std::string::npos) << s.out;
      const auto j = nlohmann::json::parse(run("check " + csv + " --machine " + machine + " --json").out);
      EXPECT_EQ(j["knittable"], true) << j.dump();
    }
  }
}

TEST_F(Cli, AHandMachineSaysItCannotKnitATube) {
  ASSERT_EQ(run("sample-map tube --round 8 --rows 4 -o " + path("t.csv")).code, 0);
  const CliRun i = run("instructions " + path("t.csv") + " --machine brother-kh868 -o " + path("t.html"));
  EXPECT_NE(i.code, 0);
  EXPECT_NE(i.err.find("tube"), std::string::npos) << i.err;
  EXPECT_FALSE(fs::exists(path("t.html")));
  EXPECT_NE(run("check " + path("t.csv") + " --machine brother-kh868").code, 0);
}

}  // namespace knitforge_e2e
