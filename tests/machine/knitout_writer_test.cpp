#include "knitforge/machine/knitout_writer.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <sstream>

#include "knitforge/convert/random_knitting_map.h"
#include "knitforge/machine/needle_layout.h"
#include "knitforge/util/errors.h"
#include "machine/knitout_test_check.h"
#include "machine/machine_test_maps.h"

namespace knitforge {
namespace {

using test::check_knitout;

int count_lines_starting(const std::string& text, const std::string& prefix) {
  std::istringstream is(text);
  std::string l;
  int n = 0;
  while (std::getline(is, l)) n += l.rfind(prefix, 0) == 0;
  return n;
}

void expect_valid(const KnittingMap& map, const MachineProfile& prof, const KnitoutOptions& opt,
                  const std::string& what) {
  SCOPED_TRACE(what + " on " + prof.name + "\n" + test::draw_map(map));
  const KnitoutProgram p = write_knitout(map, prof, opt);
  const auto res = check_knitout(p.text, map, prof);
  for (size_t i = 0; i < std::min<size_t>(res.errors.size(), 10); ++i) ADD_FAILURE() << res.errors[i];
  EXPECT_TRUE(res.errors.empty());
  EXPECT_LE(res.max_abs_rack, prof.max_racking);
  EXPECT_LE(res.max_loops, prof.max_loops_per_needle);
  // every map stitch is made exactly once, in its course block
  for (int r = 0; r < map.rows; ++r) {
    int n = 0;
    for (int c = 0; c < map.cols; ++c) n += is_stitch(map.at(r, c));
    EXPECT_EQ(res.course_ops[r], n) << "course " << r;
  }
  EXPECT_EQ(p.stats.map_knits + p.stats.map_tucks, map.num_stitches());
  EXPECT_EQ(p.stats.courses, map.rows);
  // deterministic
  EXPECT_EQ(write_knitout(map, prof, opt).text, p.text);
}

TEST(KnitoutWriter, HeadersComeFirstAndAreExact) {
  const auto& prof = machine_profile("shima-swg091n2");
  const auto p = write_knitout(test::rectangle_map(), prof);
  std::istringstream is(p.text);
  std::string l1, l2, l3, l4, l5;
  std::getline(is, l1);
  std::getline(is, l2);
  std::getline(is, l3);
  std::getline(is, l4);
  std::getline(is, l5);
  EXPECT_EQ(l1, ";!knitout-2");
  EXPECT_EQ(l2, ";;Machine: SWG091N2");
  EXPECT_EQ(l3, ";;Gauge: 15");
  EXPECT_EQ(l4, ";;Carriers: 1 2 3 4 5 6 7 8 9 10");
  EXPECT_EQ(l5, ";;Position: Center");
  EXPECT_EQ(p.text.find('\r'), std::string::npos);
  EXPECT_EQ(p.text.back(), '\n');
  // Kniterate: width header, plain in/out, no hook operations
  const auto& kn = machine_profile("kniterate");
  const auto q = write_knitout(test::rectangle_map(), kn);
  EXPECT_NE(q.text.find(";;Width: 252\n"), std::string::npos);
  EXPECT_NE(q.text.find(";;Carriers: 1 2 3 4 5 6\n"), std::string::npos);
  EXPECT_EQ(q.text.find("hook"), std::string::npos);
  EXPECT_EQ(count_lines_starting(q.text, "in 1"), 1);
  EXPECT_EQ(count_lines_starting(q.text, "out 1"), 1);
}

TEST(KnitoutWriter, RectangleIsPlainCastOnCoursesAndChainBindOff) {
  const auto& prof = machine_profile("shima-swg091n2");
  const auto map = test::rectangle_map();
  KnitoutOptions plain;
  plain.waste_rows = 0;
  const auto p = write_knitout(map, prof, plain);
  // 6 needles: 3 tucks leftwards + 3 rightwards, 1 cast-on course, 4 courses,
  // 5 chain steps (1 knit each), 4 tail knits.
  EXPECT_EQ(p.stats.tucks, 6);
  EXPECT_EQ(p.stats.knits, 6 + 24 + 5 + 4);
  EXPECT_EQ(p.stats.xfers, 10);  // chain bind-off only
  EXPECT_EQ(p.stats.racks, 10);
  EXPECT_EQ(p.stats.increases + p.stats.decreases + p.stats.inside_turns, 0);
  EXPECT_EQ(p.stats.last_needle - p.stats.first_needle, 5);
  // centred on the 540-needle bed
  EXPECT_EQ(p.stats.first_needle, 1 + (540 - 6) / 2);
  EXPECT_EQ(count_lines_starting(p.text, "inhook 1"), 1);
  EXPECT_EQ(count_lines_starting(p.text, "releasehook 1"), 1);
  EXPECT_EQ(count_lines_starting(p.text, "outhook 1"), 1);
  // releasehook comes before the first transfer
  EXPECT_LT(p.text.find("releasehook 1"), p.text.find("xfer"));
  expect_valid(map, prof, plain, "rectangle");
}

TEST(KnitoutWriter, HandMadeMapsAreValidOnEveryTwoBedProfile) {
  for (const char* name : {"shima-swg091n2", "kniterate", "generic"}) {
    const auto& prof = machine_profile(name);
    for (const auto& [what, map] : test::hand_made_maps()) expect_valid(map, prof, {}, what);
  }
}

TEST(KnitoutWriter, ShortRowTurnIsClosedByATuckOnTheHeldNeedle) {
  const auto& prof = machine_profile("shima-swg091n2");
  const auto map = test::short_row_wedge_map();
  const auto p = write_knitout(map, prof);
  // row 1 turns at column 2 going left: wale 1 is held next to it
  EXPECT_EQ(p.stats.inside_turns, 1);
  EXPECT_EQ(p.stats.closed_turns, 1);
  const NeedleLayout L = plan_needle_layout(map);
  const int offset = p.stats.first_needle - L.min_needle;
  const std::string tuck = "tuck - f" + std::to_string(L.needle_at(1, 1) + offset) + " 1";
  const auto at = p.text.find("; turn after course 1");
  ASSERT_NE(at, std::string::npos);
  EXPECT_EQ(p.text.find(tuck, at), p.text.find('\n', at) + 1);
  // without closure the turn is left open and no extra tuck is made
  KnitoutOptions o;
  o.close_turns = false;
  const auto q = write_knitout(map, prof, o);
  EXPECT_EQ(q.stats.open_turns, 1);
  EXPECT_EQ(q.stats.tucks, p.stats.tucks - 1);
  expect_valid(map, prof, o, "wedge without closure");
}

TEST(KnitoutWriter, IncreaseOpensAnEmptyNeedleAndTucksOnIt) {
  const auto& prof = machine_profile("shima-swg091n2");
  const auto map = test::one_increase_map();
  const auto p = write_knitout(map, prof);
  EXPECT_EQ(p.stats.increases, 1);
  EXPECT_EQ(p.stats.map_tucks, 1);
  // course 0 has 4 wales on needles x-2..x+1 (pivot rule: needle 0 is wale 2 ->
  // col 3); the increase at col 2 is right of... the layout moves the wales on
  // one side only: exactly 2 loops move (2 xfers each) plus the bind-off.
  const NeedleLayout L = plan_needle_layout(map);
  ASSERT_EQ(L.transitions[1].starts, std::vector<int>{2});
  int moves = 0;
  for (const auto& s : L.transitions[1].steps) moves += static_cast<int>(s.moves.size());
  EXPECT_EQ(moves, 2);
  EXPECT_EQ(L.needle_at(1, 1) + 1, L.needle_at(1, 2));
  EXPECT_EQ(L.needle_at(1, 2) + 1, L.needle_at(1, 3));
  // the pivot does not move
  const int pc = L.transitions[1].pivot_col;
  EXPECT_EQ(L.needle_at(0, pc), L.needle_at(1, pc));
  EXPECT_EQ(p.stats.xfers, 2 * moves + 2 * 4);
}

TEST(KnitoutWriter, DecreaseStacksTwoLoopsThatKnitTogether) {
  const auto& prof = machine_profile("shima-swg091n2");
  const auto map = test::one_decrease_map();
  const NeedleLayout L = plan_needle_layout(map);
  ASSERT_EQ(L.transitions[3].merges.size(), 1u);
  const auto m = L.transitions[3].merges[0];
  EXPECT_EQ(m.col, 2);
  // merged towards the pivot
  const int pc = L.transitions[3].pivot_col;
  EXPECT_TRUE((m.col < pc && m.onto_col > m.col) || (m.col > pc && m.onto_col < m.col) || m.col == pc);
  EXPECT_EQ(std::abs(m.onto_col - m.col), 1);
  const auto p = write_knitout(map, prof);
  const auto res = check_knitout(p.text, map, prof);
  EXPECT_TRUE(res.errors.empty());
  EXPECT_EQ(res.max_loops, 2);
  EXPECT_EQ(p.stats.decreases, 1);
}

TEST(KnitoutWriter, LargeShiftsAreSplitWithinTheRackingLimit) {
  const auto map = test::many_increases_map();
  const NeedleLayout L4 = plan_needle_layout(map, {4, 3, true, 2});
  EXPECT_EQ(L4.increases, 14);
  EXPECT_GE(L4.transitions[1].steps.size(), 2u);
  for (const auto& s : L4.transitions[1].steps)
    for (const auto& m : s.moves) EXPECT_LE(std::abs(m.to - m.from), 4);
  MachineProfile tight = machine_profile("generic");
  tight.name = "tight";
  tight.max_racking = 1;
  expect_valid(map, tight, {}, "many increases, racking 1");
  const auto p = write_knitout(map, tight);
  EXPECT_EQ(check_knitout(p.text, map, tight).max_abs_rack, 1);
}

TEST(KnitoutWriter, WasteSectionAndWasteBindOff) {
  const auto& prof = machine_profile("shima-swg091n2");
  KnitoutOptions o;
  o.waste_rows = 6;
  o.bind_off = BindOff::Waste;
  o.bind_off_waste_rows = 4;
  const auto map = test::short_column_map();
  expect_valid(map, prof, o, "waste");
  const auto p = write_knitout(map, prof, o);
  for (const char* c : {"inhook 2", "outhook 2", "inhook 3", "outhook 3", "inhook 1", "outhook 1"})
    EXPECT_NE(p.text.find(std::string(c) + "\n"), std::string::npos) << c;
  EXPECT_EQ(count_lines_starting(p.text, "inhook 2"), 2);  // waste at both ends
  // the hook is released before the next carrier comes in with it
  const auto res = check_knitout(p.text, map, prof);
  EXPECT_TRUE(res.errors.empty());
  EXPECT_EQ(res.carriers_used, (std::set<std::string>{"1", "2", "3"}));
}

TEST(KnitoutWriter, StitchAndSpeedSettingsFollowTheMachine) {
  // Shima: no settings unless asked for (its stitch table is the machine's own).
  const auto& prof = machine_profile("shima-swg091n2");
  const auto plain = write_knitout(test::rectangle_map(), prof);
  EXPECT_EQ(plain.text.find("x-"), std::string::npos);
  KnitoutOptions o;
  o.body.stitch_number = "32";
  o.body.speed_number = 10;
  o.gauge = 12;
  const auto p = write_knitout(test::rectangle_map(), prof, o);
  EXPECT_NE(p.text.find("\nx-stitch-number 32\n"), std::string::npos);
  EXPECT_NE(p.text.find("\nx-speed-number 10\n"), std::string::npos);
  EXPECT_NE(p.text.find(";;Gauge: 12\n"), std::string::npos);
  // the SWG translator does not read x-xfer-stitch-number
  KnitoutOptions x;
  x.body.xfer_stitch_number = "20";
  EXPECT_THROW(write_knitout(test::rectangle_map(), prof, x), InvalidInput);
  // Kniterate: settings per section from its translator's defaults; stitch
  // numbers are 0-9 / A-Z there.
  const auto& kn = machine_profile("kniterate");
  const auto k = write_knitout(test::rectangle_map(), kn);
  const auto waste = k.text.find("; waste:");
  const auto cast_on = k.text.find("; cast-on:");
  const auto course0 = k.text.find("; course 0:");
  ASSERT_NE(waste, std::string::npos);
  EXPECT_LT(waste, k.text.find("x-roller-advance 400"));
  EXPECT_LT(k.text.find("x-stitch-number 6"), cast_on);
  EXPECT_LT(cast_on, k.text.find("x-stitch-number 5"));
  EXPECT_LT(k.text.find("x-stitch-number 5"), course0);
  KnitoutOptions big;
  big.body.stitch_number = "12";
  EXPECT_THROW(write_knitout(test::rectangle_map(), kn, big), InvalidInput);
}

TEST(KnitoutWriter, RejectsBadInputWithClearErrors) {
  const auto map = test::rectangle_map();
  EXPECT_THROW(write_knitout(map, machine_profile("brother-kh868")), InvalidInput);
  KnitoutOptions o;
  o.carrier = "11";
  EXPECT_THROW(write_knitout(map, machine_profile("shima-swg091n2"), o), InvalidInput);
  o.carrier = "7";
  EXPECT_THROW(write_knitout(map, machine_profile("kniterate"), o), InvalidInput);
  KnitoutOptions w;
  w.waste_rows = 3;
  w.waste_carrier = "1";
  EXPECT_THROW(write_knitout(map, machine_profile("shima-swg091n2"), w), InvalidInput);
  KnitoutOptions pos;
  pos.position = "Middle";
  EXPECT_THROW(write_knitout(map, machine_profile("shima-swg091n2"), pos), InvalidInput);
  // too wide for the Kniterate bed
  KnittingMap wide(3, 300, CellType::Knit);
  EXPECT_THROW(write_knitout(wide, machine_profile("kniterate")), InvalidInput);
  // an invalid map (a row split by an empty cell)
  KnittingMap bad = test::parse_map({"KK_KK", "KKKKK"});
  EXPECT_THROW(write_knitout(bad, machine_profile("generic")), InvalidInput);
}

TEST(KnitoutWriter, RandomMapsWithShortRowsAndColumnsAreValid) {
  for (uint64_t seed = 1; seed <= 12; ++seed) {
    RandomMapOptions ro;
    ro.seed = seed;
    ro.rows = 30;
    ro.cols = 24;
    ro.short_row_ends = 2 * static_cast<int>(seed % 6);
    ro.short_columns = static_cast<int>(seed % 5);
    ro.boundary_shaping = seed % 3 == 0;
    const KnittingMap map = random_knitting_map(ro);
    const char* prof = seed % 2 ? "shima-swg091n2" : "kniterate";
    KnitoutOptions o;
    if (seed % 4 == 0) {
      o.waste_rows = 3;
      o.bind_off = BindOff::Waste;
    }
    expect_valid(map, machine_profile(prof), o, "random seed " + std::to_string(seed));
  }
}

TEST(KnitoutWriter, WaleLinksFollowTheMapIncludingMerges) {
  RandomMapOptions ro;
  ro.seed = 5;
  ro.rows = 40;
  ro.cols = 30;
  ro.short_row_ends = 12;
  ro.short_columns = 6;
  const KnittingMap map = random_knitting_map(ro);
  const auto& prof = machine_profile("shima-swg091n2");
  const auto res = check_knitout(write_knitout(map, prof).text, map, prof);
  EXPECT_TRUE(res.errors.empty());
  // every stitch with a stitch below in its wale was checked
  int expected = 0;
  for (int c = 0; c < map.cols; ++c) {
    bool prev = false;
    for (int r = 0; r < map.rows; ++r) {
      const CellType t = map.at(r, c);
      if (t == CellType::Empty) prev = false;
      if (!is_stitch(t)) continue;
      if (prev && t != CellType::Increase) ++expected;
      prev = t != CellType::Decrease;
    }
  }
  EXPECT_EQ(res.wale_links_checked, expected);
  EXPECT_GT(expected, 0);
}

}  // namespace
}  // namespace knitforge

// ---- the programs run on the simulator (knitout_simulate.h) ----------------
#include "knitforge/machine/knit_graph_compare.h"
#include "knitforge/machine/knitout_simulate.h"

namespace knitforge {
namespace {

void expect_simulates(const KnittingMap& map, const MachineProfile& prof, const KnitoutOptions& opt,
                      const std::string& what) {
  SCOPED_TRACE(what + " on " + prof.name);
  const KnitoutProgram p = write_knitout(map, prof, opt);
  const KnitoutSimulation sim = simulate_knitout(parse_knitout(p.text), prof);
  EXPECT_EQ(sim.errors, 0) << sim.text();
  CompareOptions co;
  co.max_issues = 0;
  const GraphComparison cmp = compare_knit_graph(sim.graph, map, co);
  // Outside decreases (a wale stopping at the fabric edge without a Decrease
  // cell) are knitted as fully-fashioned narrowing: the edge loop is merged
  // onto its neighbour. The comparison accepts exactly that merge, so the
  // program must match the map with no mismatch at all.
  EXPECT_TRUE(cmp.issues.empty()) << cmp.text();
  EXPECT_EQ(cmp.mismatches, 0) << cmp.text();
  EXPECT_EQ(cmp.fabric_loops, map.num_stitches());
  EXPECT_EQ(sim.stats.transfers, p.stats.xfers);
  EXPECT_EQ(sim.stats.knits, p.stats.knits);
}

TEST(KnitoutWriterSimulated, HandMadeMapsSimulateCleanAndMatchTheMap) {
  for (const char* name : {"shima-swg091n2", "kniterate", "generic"})
    for (const auto& [what, map] : test::hand_made_maps())
      expect_simulates(map, machine_profile(name), {}, what);
  KnitoutOptions o;
  o.waste_rows = 4;
  o.bind_off = BindOff::Waste;
  for (const auto& [what, map] : test::hand_made_maps())
    expect_simulates(map, machine_profile("shima-swg091n2"), o, what + " (waste)");
}

TEST(KnitoutWriterSimulated, RandomMapsSimulateCleanAndMatchTheMap) {
  for (uint64_t seed = 1; seed <= 10; ++seed) {
    RandomMapOptions ro;
    ro.seed = 100 + seed;
    ro.rows = 36;
    ro.cols = 28;
    ro.short_row_ends = 2 * static_cast<int>(seed % 7);
    ro.short_columns = static_cast<int>(seed % 6);
    ro.boundary_shaping = seed % 3 == 1;
    const KnittingMap map = random_knitting_map(ro);
    KnitoutOptions o;
    if (seed % 2) {
      o.waste_rows = 2;
      o.bind_off = BindOff::Waste;
    }
    expect_simulates(map, machine_profile(seed % 3 ? "shima-swg091n2" : "kniterate"), o,
                     "random " + std::to_string(seed));
  }
}

}  // namespace
}  // namespace knitforge
