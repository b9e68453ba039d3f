// Programs written in the style of the published test programs of the open
// knitout tools (swatches that end with drops, tubes that stop with loops
// left, all-needle racked knitting, splits, quarter-pitch racking,
// colourwork with two carriers, CR LF files, knitout 3 headers; our own
// programs in tests/machine/data/published_style/): each gets the verdict
// the machine's software gives (the translators accept them all), with the
// warnings of what the fabric will suffer (issue 18).
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "knitforge/machine/knit_graph_to_map.h"
#include "knitforge/machine/knitout_parse.h"
#include "knitforge/machine/knitout_simulate.h"
#include "knitforge/machine/machine_profile.h"

namespace knitforge {
namespace {

const std::filesystem::path kDir = std::filesystem::path(KNITFORGE_TESTS_DIR) / "machine" / "data" / "published_style";

struct Expect {
  const char* file;
  const char* machine;
  // warnings by category; every other category must be silent
  std::vector<std::pair<KnitoutRule, int>> warnings;
  const char* fabric;  // "sheet", "tube" or "" (not drawn)
};

int warnings_of(const KnitoutSimulation& s, KnitoutRule r) { return s.warning_counts[static_cast<size_t>(r)]; }

TEST(PublishedStylePrograms, GetTheVerdictOfTheMachinesSoftware) {
  const std::vector<Expect> cases = {
      {"swatch_drop.k", "kniterate", {{KnitoutRule::Drop, 10}}, "sheet"},
      {"swatch_crlf.k", "kniterate", {{KnitoutRule::Drop, 10}, {KnitoutRule::Syntax, 1}}, "sheet"},
      {"swatch_knitout3.k", "kniterate", {{KnitoutRule::Drop, 10}, {KnitoutRule::Syntax, 1}}, "sheet"},
      {"tube_loops_left.k", "shima-swg091n2", {{KnitoutRule::LoopsLeft, 1}}, "tube"},
      {"all_needle_racked.k", "shima-swg091n2", {{KnitoutRule::Drop, 12}}, "sheet"},
      {"split_increase.k", "generic", {{KnitoutRule::Drop, 7}}, ""},
      {"kniterate_quarter_pitch.k", "kniterate", {{KnitoutRule::Racking, 2}, {KnitoutRule::Drop, 16}}, "tube"},
      {"colourwork_stripes.k", "kniterate", {{KnitoutRule::Drop, 8}}, "sheet"},
  };
  for (const Expect& c : cases) {
    SCOPED_TRACE(std::string(c.file) + " on " + c.machine);
    const KnitoutSimulation s = simulate_knitout(read_knitout((kDir / c.file).string()), machine_profile(c.machine));
    EXPECT_TRUE(s.ok()) << s.text();
    int expected = 0;
    for (const auto& [rule, n] : c.warnings) {
      EXPECT_EQ(warnings_of(s, rule), n) << name(rule) << "\n" << s.text();
      expected += n;
    }
    EXPECT_EQ(s.warnings, expected) << s.text();
    // The same programs with every warning category strict: what knitforge
    // demands of its own programs, which these are not.
    SimulateOptions strict;
    strict.strict = all_rules_strict();
    EXPECT_FALSE(simulate_knitout(read_knitout((kDir / c.file).string()), machine_profile(c.machine), strict).ok());
    const KnitGraphFabric f = knit_graph_fabric(s);
    EXPECT_EQ(f.kind, c.fabric) << f.reason;
    if (f.kind.empty()) {
      EXPECT_FALSE(f.reason.empty());
    }
  }
}

TEST(PublishedStylePrograms, TheTubeIsTwentyStitchesRoundAndTheSwatchTenWide) {
  const KnitoutSimulation tube =
      simulate_knitout(read_knitout((kDir / "tube_loops_left.k").string()), machine_profile("shima-swg091n2"));
  const KnitGraphFabric t = knit_graph_fabric(tube);
  ASSERT_EQ(t.kind, "tube");
  EXPECT_EQ(t.rounds, 8);
  EXPECT_EQ(t.ring, 20);
  // each stitch above the first round is knitted through the one below it
  for (int r = 1; r < t.rounds; ++r)
    for (int j = 0; j < t.ring; ++j) {
      const auto p = tube.graph.parents_of(t.loop_of_round_stitch[static_cast<size_t>(r * t.ring + j)]);
      ASSERT_EQ(p.size(), 1u);
      EXPECT_EQ(p[0], t.loop_of_round_stitch[static_cast<size_t>((r - 1) * t.ring + j)]);
    }
  const KnitoutSimulation sw =
      simulate_knitout(read_knitout((kDir / "swatch_drop.k").string()), machine_profile("kniterate"));
  const KnitGraphFabric s = knit_graph_fabric(sw);
  ASSERT_EQ(s.kind, "sheet");
  EXPECT_EQ(s.map.rows, 8);
  EXPECT_EQ(s.map.cols, 10);
  EXPECT_EQ(s.map.num_stitches(), 80);
  // the double knit of the all-needle program: front and back interleaved
  const KnitoutSimulation an =
      simulate_knitout(read_knitout((kDir / "all_needle_racked.k").string()), machine_profile("shima-swg091n2"));
  const KnitGraphFabric a = knit_graph_fabric(an);
  ASSERT_EQ(a.kind, "sheet") << a.reason;
  EXPECT_EQ(a.map.cols, 12);
  EXPECT_EQ(a.map.rows, 6);
  // the stripes keep their carriers as yarns
  const KnitGraphFabric st = knit_graph_fabric(
      simulate_knitout(read_knitout((kDir / "colourwork_stripes.k").string()), machine_profile("kniterate")));
  ASSERT_EQ(st.kind, "sheet");
  EXPECT_EQ(st.map.yarn_at(0, 0), 0);
  EXPECT_EQ(st.map.yarn_at(2, 0), 1);
  EXPECT_EQ(st.map.yarn_at(4, 3), 0);
}

}  // namespace
}  // namespace knitforge
