#include "knitforge/machine/knit_graph_compare.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "knitforge/convert/random_knitting_map.h"
#include "knitforge/machine/knitout_parse.h"
#include "knitforge/machine/knitout_simulate.h"
#include "knitforge/machine/knitout_writer.h"
#include "knitforge/machine/machine_profile.h"
#include "convert/map_test_helpers.h"

using namespace knitforge;
using knitforge::test::make_map;

namespace {

const std::filesystem::path kData = std::filesystem::path(KNITFORGE_TESTS_DIR) / "machine" / "data";

std::string read_text(const std::string& name) {
  std::ifstream in(kData / name);
  std::ostringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

std::vector<std::string> split_lines(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  for (std::string l; std::getline(in, l);) lines.push_back(l);
  return lines;
}

std::string join_lines(const std::vector<std::string>& lines) {
  std::string s;
  for (const auto& l : lines) s += l + "\n";
  return s;
}


// The maps of the hand-written programs in tests/machine/data.
KnittingMap wedge_map() { return make_map({"KKKKKK", "KKK>..", "KKK>..", "KKKKKK", "KKKKKK"}); }
KnittingMap decrease_map() { return make_map({"KK.KK", "KK.KK", "KKDKK", "KKKKK"}); }
KnittingMap jersey_map() { return KnittingMap(6, 10, CellType::Knit); }

KnitoutSimulation simulate_text(const std::string& text) {
  return simulate_knitout(parse_knitout(text), machine_profile("shima-swg091n2"));
}

bool has_kind(const GraphComparison& c, const std::string& kind) {
  for (const auto& m : c.issues) {
    if (m.kind == kind) return true;
  }
  return false;
}

}  // namespace

TEST(KnitGraphCompare, HandWrittenProgramsKnitTheirMaps) {
  const struct {
    const char* file;
    KnittingMap map;
  } cases[] = {{"short_row_wedge.k", wedge_map()}, {"decrease.k", decrease_map()}, {"jersey_alt_tuck.k", jersey_map()}};
  for (const auto& c : cases) {
    const KnitoutSimulation sim = simulate_text(read_text(c.file));
    ASSERT_TRUE(sim.ok()) << c.file << "\n" << sim.text();
    const GraphComparison cmp = compare_knit_graph(sim.graph, c.map);
    EXPECT_TRUE(cmp.ok()) << c.file << "\n" << cmp.text();
    EXPECT_EQ(cmp.map_stitches, c.map.num_stitches());
    EXPECT_EQ(cmp.fabric_loops, c.map.num_stitches());
  }
}

TEST(KnitGraphCompare, FabricLoopsSkipCastOnTurnTucksAndBindOff) {
  const KnitoutSimulation sim = simulate_text(read_text("short_row_wedge.k"));
  const std::vector<int> fab = fabric_loops(sim.graph);
  ASSERT_EQ(static_cast<int>(fab.size()), wedge_map().num_stitches());
  // 6 cast-on tucks + 6 cast-on knits come first; the first fabric loop is course 0 on f1.
  EXPECT_EQ(fab.front(), 12);
  EXPECT_EQ(sim.graph.loops[static_cast<size_t>(fab.front())].needle, (Needle{Bed::Front, 1}));
  for (int l : fab) {
    const KnitLoop& loop = sim.graph.loops[static_cast<size_t>(l)];
    EXPECT_EQ(loop.section, LoopSection::Fabric);
    EXPECT_EQ(loop.kind, LoopKind::Knit);
  }
  // The turn tuck on f5 is pulled through by course 4 together with course 1's loop.
  int turn_tuck = -1;
  for (int i = 0; i < sim.graph.num_loops(); ++i) {
    const KnitLoop& l = sim.graph.loops[static_cast<size_t>(i)];
    if (l.kind == LoopKind::Tuck && l.section == LoopSection::Fabric) turn_tuck = i;
  }
  ASSERT_GE(turn_tuck, 0);
  const int child = sim.graph.loops[static_cast<size_t>(turn_tuck)].child;
  ASSERT_GE(child, 0);
  EXPECT_EQ(sim.graph.parents_of(child).size(), 2u);
}

TEST(KnitGraphCompare, SkippedStitchFails) {
  std::vector<std::string> lines = split_lines(read_text("short_row_wedge.k"));
  const auto it = std::find(lines.begin(), lines.end(), "; course 1");
  ASSERT_NE(it, lines.end());
  const int course1 = static_cast<int>(it - lines.begin());
  ASSERT_EQ(lines[static_cast<size_t>(course1 + 3)], "knit - f4 1");
  lines.erase(lines.begin() + course1 + 3);  // course 1 misses f4
  const KnitoutSimulation sim = simulate_text(join_lines(lines));
  ASSERT_TRUE(sim.ok()) << sim.text();  // a valid program, but not the design
  const GraphComparison cmp = compare_knit_graph(sim.graph, wedge_map());
  EXPECT_FALSE(cmp.ok());
  EXPECT_EQ(cmp.fabric_loops, wedge_map().num_stitches() - 1);
  EXPECT_TRUE(has_kind(cmp, "count")) << cmp.text();
  EXPECT_TRUE(has_kind(cmp, "wale")) << cmp.text();
  // The first wale mismatch is in map row 1 or 2 and names a knitout line.
  for (const auto& m : cmp.issues) {
    if (m.kind == "wale") {
      EXPECT_GE(m.row, 1);
      EXPECT_LE(m.row, 2);
      EXPECT_GT(m.line, course1);
      break;
    }
  }
}

TEST(KnitGraphCompare, CourseInWrongDirectionFails) {
  std::vector<std::string> lines = split_lines(read_text("short_row_wedge.k"));
  const auto it = std::find(lines.begin(), lines.end(), "; course 1");
  ASSERT_NE(it, lines.end());
  const size_t c1 = static_cast<size_t>(it - lines.begin());
  for (int k = 0; k < 6; ++k) lines[c1 + 1 + static_cast<size_t>(k)] = "knit + f" + std::to_string(k + 1) + " 1";
  const KnitoutSimulation sim = simulate_text(join_lines(lines));
  ASSERT_TRUE(sim.ok()) << sim.text();
  const GraphComparison cmp = compare_knit_graph(sim.graph, wedge_map());
  EXPECT_FALSE(cmp.ok());
  ASSERT_FALSE(cmp.issues.empty());
  EXPECT_EQ(cmp.issues[0].kind, "direction");
  EXPECT_EQ(cmp.issues[0].row, 1);
  // Map row 1 starts at column 5; its first loop is the first knit of the block.
  EXPECT_EQ(cmp.issues[0].col, 5);
  EXPECT_EQ(cmp.issues[0].line, static_cast<int>(c1) + 2);
}

TEST(KnitGraphCompare, DecreaseNotMergedFails) {
  // The same program without the transfers: the decrease's loop stays on f3
  // and course 2 knits it as a wale of its own.
  std::vector<std::string> lines = split_lines(read_text("decrease.k"));
  std::vector<std::string> out;
  bool skip = false;
  for (const auto& l : lines) {
    if (l.rfind("; transfers", 0) == 0) skip = true;
    if (l == "; course 2") skip = false;
    if (!skip) out.push_back(l);
  }
  // Course 2 and 3 then knit f2..f5 over loops that did not move.
  const KnitoutSimulation sim = simulate_text(join_lines(out));
  const GraphComparison cmp = compare_knit_graph(sim.graph, decrease_map());
  EXPECT_FALSE(cmp.ok());
  EXPECT_TRUE(has_kind(cmp, "wale") || has_kind(cmp, "decrease")) << cmp.text();
}

TEST(KnitGraphCompare, WriterProgramsSimulateCleanlyAndMatch) {
  const MachineProfile& shima = machine_profile("shima-swg091n2");
  for (uint64_t seed = 1; seed <= 6; ++seed) {
    RandomMapOptions o;
    o.seed = seed;
    o.rows = 14 + static_cast<int>(seed % 5);
    o.cols = 14 + static_cast<int>(seed % 4);
    o.short_row_ends = seed % 2 == 0 ? 4 : 2;
    o.short_columns = seed % 3 == 0 ? 1 : 2;
    o.boundary_shaping = seed % 2 == 1 && o.rows >= 12;
    const KnittingMap map = random_knitting_map(o);
    for (BindOff b : {BindOff::Chain, BindOff::Waste}) {
      KnitoutOptions ko;
      ko.bind_off = b;
      ko.waste_rows = seed % 2 == 0 ? 3 : 0;
      const auto prog = write_knitout(map, shima, ko);
      const KnitoutSimulation sim = simulate_text(prog.text);
      EXPECT_TRUE(sim.ok()) << "seed " << seed << "\n" << sim.text();
      const GraphComparison cmp = compare_knit_graph(sim.graph, map);
      EXPECT_TRUE(cmp.ok()) << "seed " << seed << "\n" << cmp.text();
    }
  }
}
