#include "knitforge/machine/knitout_tube_writer.h"

#include <gtest/gtest.h>

#include <map>
#include <set>
#include <sstream>

#include "convert/map_test_helpers.h"
#include "knitforge/convert/map_knittability.h"
#include "knitforge/convert/sample_knitting_map.h"
#include "knitforge/machine/hand_instructions.h"
#include "knitforge/machine/knit_graph_to_map.h"
#include "knitforge/machine/knitout_parse.h"
#include "knitforge/machine/knitout_simulate.h"
#include "knitforge/machine/machine_knittability.h"
#include "knitforge/machine/tube_layout.h"
#include "knitforge/util/errors.h"

namespace knitforge {
namespace {

KnittingMap small_tube(int round = 8, int rows = 4) {
  TubeMapOptions o;
  o.round = round;
  o.rows = rows;
  return tube_knitting_map(o);
}

KnittingMap small_tapered() { return test::small_tapered_tube(); }

std::vector<std::string> lines_of(const std::string& text) {
  std::istringstream is(text);
  std::vector<std::string> out;
  std::string l;
  while (std::getline(is, l)) out.push_back(l);
  return out;
}

// Needle numbers of the fabric stitches (knit/tuck between the first
// "; course" comment and "; bind-off"), per bed.
std::map<char, std::set<int>> fabric_needles(const std::string& text) {
  std::map<char, std::set<int>> out;
  bool fabric = false;
  for (const std::string& l : lines_of(text)) {
    if (l.rfind("; course", 0) == 0) fabric = true;
    if (l.rfind("; bind-off", 0) == 0) fabric = false;
    if (!fabric || (l.rfind("knit ", 0) != 0 && l.rfind("tuck ", 0) != 0)) continue;
    std::istringstream is(l);
    std::string op, dir, needle;
    is >> op >> dir >> needle;
    out[needle[0]].insert(std::stoi(needle.substr(1)));
  }
  return out;
}

void expect_verified(const KnitoutProgram& p, const KnittingMap& map, const MachineProfile& prof) {
  ASSERT_TRUE(p.simulation.has_value());
  ASSERT_TRUE(p.comparison.has_value());
  EXPECT_TRUE(p.simulation->ok()) << p.simulation->text();
  EXPECT_EQ(p.simulation->warnings, 0) << p.simulation->text();
  EXPECT_TRUE(p.comparison->ok()) << p.comparison->text();
  EXPECT_EQ(p.comparison->map_stitches, map.num_stitches());
  EXPECT_EQ(p.stats.map_knits + p.stats.map_tucks, map.num_stitches()) << prof.name;
  EXPECT_EQ(p.stats.courses, map.rows);
}

TEST(TubeLayout, HalvesOnTheirBedsEveryOtherNeedle) {
  const KnittingMap map = small_tube(8, 3);
  const TubeLayout L = plan_tube_layout(map);
  ASSERT_TRUE(L.problems.empty());
  for (int r = 0; r < map.rows; ++r) {
    for (int c = 0; c < map.cols; ++c) {
      const int n = L.needle_at(r, c);
      // front wales on even relative needles, back wales on odd ones
      EXPECT_EQ(((n % 2) + 2) % 2, c >= 4 ? 1 : 0) << r << "," << c;
    }
    // front left to right, back from the right fold to the left fold
    for (int c = 1; c < 4; ++c) EXPECT_EQ(L.needle_at(r, c) - L.needle_at(r, c - 1), 2);
    for (int c = 5; c < 8; ++c) EXPECT_EQ(L.needle_at(r, c) - L.needle_at(r, c - 1), -2);
    // the folds face each other
    EXPECT_EQ(L.needle_at(r, 4) - L.needle_at(r, 3), 1);
    EXPECT_EQ(L.needle_at(r, 7) - L.needle_at(r, 0), 1);
  }
}

TEST(TubeLayout, DecreasesMergeOnTheirOwnBed) {
  const KnittingMap map = small_tapered();
  const TubeLayout L = plan_tube_layout(map);
  ASSERT_TRUE(L.problems.empty()) << L.problems.front().message;
  EXPECT_EQ(L.decreases, 8);
  for (const auto& T : L.transitions)
    for (const auto& m : T.merges) EXPECT_EQ(m.col >= 8, m.onto_col >= 8) << m.col << " -> " << m.onto_col;
  // racking 4 allows two slots per step
  for (const auto& T : L.transitions)
    for (const auto& s : T.steps)
      for (const auto& m : s) EXPECT_LE(std::abs(m.to - m.from), 4);
}

TEST(TubeLayout, RacklessMachinesAndSheetsAreRefused) {
  TubeLayoutOptions o;
  o.max_racking = 1;
  EXPECT_THROW(plan_tube_layout(small_tube(), o), InvalidInput);
  KnittingMap sheet = small_tube();
  sheet.seam.clear();
  EXPECT_THROW(plan_tube_layout(sheet), InvalidInput);
  EXPECT_THROW(plan_needle_layout(small_tube()), InvalidInput);
}

TEST(TubeWriter, StraightTubeIsValidAndMatchesOnEveryTwoBedMachine) {
  const KnittingMap map = small_tube(8, 4);
  for (const char* name : {"shima-swg091n2", "kniterate", "generic"}) {
    SCOPED_TRACE(name);
    const auto& prof = machine_profile(name);
    const KnitoutProgram p = write_knitout(map, prof);
    expect_verified(p, map, prof);
    const auto needles = fabric_needles(p.text);
    ASSERT_EQ(needles.count('f'), 1u);
    ASSERT_EQ(needles.count('b'), 1u);
    // every other needle on each bed, the beds on opposite parity
    std::set<int> fpar, bpar;
    for (int n : needles.at('f')) fpar.insert(n % 2);
    for (int n : needles.at('b')) bpar.insert(n % 2);
    EXPECT_EQ(fpar.size(), 1u);
    EXPECT_EQ(bpar.size(), 1u);
    EXPECT_NE(*fpar.begin(), *bpar.begin());
    EXPECT_EQ(needles.at('f').size(), 4u);
    EXPECT_EQ(needles.at('b').size(), 4u);
    // deterministic
    EXPECT_EQ(write_knitout(map, prof).text, p.text);
  }
}

TEST(TubeWriter, KniterateAndShimaStartTheirCarriersAwayFromTheParkingSide) {
  const KnittingMap map = small_tube(8, 2);
  for (const char* name : {"shima-swg091n2", "kniterate"}) {
    const auto& prof = machine_profile(name);
    KnitoutOptions o;
    o.waste_rows = 0;
    const auto p = write_knitout(map, prof, o);
    const auto ls = lines_of(p.text);
    std::string first;
    for (const auto& l : ls)
      if (l.rfind("tuck ", 0) == 0) {
        first = l;
        break;
      }
    const bool left_park = prof.carrier_park_side == BedSide::Left;
    // Kniterate parks at the left: first pass +, on the front; Shima: -, on the back
    EXPECT_EQ(first.substr(0, 8), left_park ? "tuck + f" : "tuck - b") << name << ": " << first;
    EXPECT_EQ(p.text.find("inhook") != std::string::npos, prof.has_yarn_inserting_hook);
  }
}

TEST(TubeWriter, TaperedTubeDecreasesByTransfersWithRacking) {
  const KnittingMap map = small_tapered();
  for (const char* name : {"shima-swg091n2", "kniterate"}) {
    SCOPED_TRACE(name);
    const auto& prof = machine_profile(name);
    const KnitoutProgram p = write_knitout(map, prof);
    expect_verified(p, map, prof);
    EXPECT_EQ(p.stats.decreases, 8);
    EXPECT_GT(p.stats.shaping_xfers, 0);
    EXPECT_GT(p.stats.racks, 0);
    // loops moved on both beds: front loops parked on the back and back loops on the front
    EXPECT_NE(p.text.find("xfer f"), std::string::npos);
    EXPECT_NE(p.text.find("xfer b"), std::string::npos);
  }
}

TEST(TubeWriter, WasteSectionsAndWasteBindOff) {
  const KnittingMap map = small_tube(8, 3);
  const auto& prof = machine_profile("shima-swg091n2");
  KnitoutOptions o;
  o.waste_rows = 4;
  o.bind_off = BindOff::Waste;
  o.bind_off_waste_rows = 3;
  const KnitoutProgram p = write_knitout(map, prof, o);
  expect_verified(p, map, prof);
  EXPECT_EQ(p.stats.waste_rows, 4);
  EXPECT_FALSE(p.waste_carrier.empty());
  EXPECT_FALSE(p.draw_carrier.empty());
  int drops = 0;
  for (const auto& l : lines_of(p.text)) drops += l.rfind("drop ", 0) == 0;
  EXPECT_EQ(drops, 8);  // every loop of the last round, both beds
}

TEST(TubeWriter, RoundsGoingTheOtherWayAndAnotherSeam) {
  KnittingMap map = small_tube(8, 4);
  map.direction.assign(4, -1);
  map.seam = {4, 4, 5, 6};  // a round going -1 from seam s ends at column s
  const auto& prof = machine_profile("kniterate");
  const KnitoutProgram p = write_knitout(map, prof);
  expect_verified(p, map, prof);
}

TEST(TubeWriter, ShortRowsOnPartOfTheRoundTurnWithClosureTucks) {
  const KnittingMap map = test::heel_tube();
  const KnittabilityReport rep = check_knittability(map);
  ASSERT_TRUE(rep.ok()) << rep.text();
  for (const char* name : {"shima-swg091n2", "kniterate"}) {
    SCOPED_TRACE(name);
    const auto& prof = machine_profile(name);
    const KnitoutProgram p = write_knitout(map, prof);
    expect_verified(p, map, prof);
    EXPECT_EQ(p.stats.inside_turns, 3);
    EXPECT_EQ(p.stats.closed_turns, 3);
  }
}

TEST(TubeWriter, AWedgeAcrossTheRightFoldMovesTheSeam) {
  // As the tube route's elbow wedges: rounds of 12 from seam 8, short rows on columns 4..8
  // across the right fold (line 6), the last one ending at column 8, the next rounds from seam 9.
  const KnittingMap map =
      test::tube_with_short_rows(8, 9, {0, 0, 4, 4, 5, 5, 0, 0}, {11, 11, 7, 6, 6, 8, 11, 11});
  const KnittabilityReport rep = check_knittability(map);
  ASSERT_TRUE(rep.ok()) << rep.text();
  for (const char* name : {"shima-swg091n2", "kniterate"}) {
    SCOPED_TRACE(name);
    const auto& prof = machine_profile(name);
    expect_verified(write_knitout(map, prof), map, prof);
  }
}

TEST(TubeWriter, HandMachineRefusesATubeSayingSo) {
  const auto& prof = machine_profile("brother-kh868");
  try {
    hand_instructions(small_tube(), prof);
    FAIL() << "no exception";
  } catch (const InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find("tube"), std::string::npos) << e.what();
  }
  const KnittabilityReport rep = check_machine_knittability(small_tube(), prof);
  EXPECT_FALSE(rep.ok());
  EXPECT_GT(rep.counts[static_cast<size_t>(KnitRule::MachineLimit)], 0);
}

TEST(TubeSimulator, KnitGraphOfATubeProgramIsTheTubularMap) {
  const KnittingMap map = small_tube(8, 4);
  const auto& prof = machine_profile("kniterate");
  const KnitoutProgram p = write_knitout(map, prof);
  const KnitGraphFabric f = knit_graph_fabric(*p.simulation);
  EXPECT_EQ(f.kind, "tube") << f.reason;
  EXPECT_EQ(f.rounds, 4);
  EXPECT_EQ(f.ring, 8);
  EXPECT_TRUE(f.map == map) << f.map.rows << "x" << f.map.cols;
}

// One rule broken per program: the simulator refuses it and names the check.
struct Broken {
  const char* machine;
  const char* check;
  std::string (*edit)(const std::string&);
};

std::string replace_first(const std::string& text, const std::string& from, const std::string& to) {
  std::string s = text;
  const size_t i = s.find(from);
  if (i == std::string::npos) return s;
  return s.replace(i, from.size(), to);
}

std::vector<std::string> check_ids(const KnitoutSimulation& sim) {
  std::vector<std::string> ids;
  for (const auto& d : sim.diagnostics)
    if (d.severity == Severity::Error) ids.emplace_back(knitout_check_id(d.check));
  return ids;
}

TEST(TubeSimulator, CraftedProgramsWithOneRuleBrokenAreRefused) {
  const KnittingMap map = small_tapered();
  std::map<std::string, std::string> programs;
  for (const char* name : {"shima-swg091n2", "kniterate"})
    programs[name] = write_knitout(map, machine_profile(name)).text;
  const std::vector<Broken> cases = {
      // racking beyond the machine during a transfer step
      {"kniterate", "racking-range", [](const std::string& t) { return replace_first(t, "rack 2\n", "rack 6\n"); }},
      // a transfer to a needle that does not face the loop
      {"kniterate", "misaligned",
       [](const std::string& t) {
         const size_t i = t.find("rack 2\n");
         const size_t j = t.find("xfer b", i);
         const size_t e = t.find('\n', j);
         std::string line = t.substr(j, e - j);  // xfer bN fM
         const size_t sp = line.rfind('f');
         const int m = std::stoi(line.substr(sp + 1));
         line = line.substr(0, sp + 1) + std::to_string(m + 1);
         return t.substr(0, j) + line + t.substr(e);
       }},
      // the hook still holds the yarn at the first transfer
      {"shima-swg091n2", "hook-transfer", [](const std::string& t) {
         std::string s = replace_first(t, "releasehook 1\n", "");
         const size_t i = s.find("xfer ");
         return s.substr(0, i) + s.substr(i, s.find("; bind-off") - i) + "releasehook 1\n" +
                s.substr(s.find("; bind-off"));
       }},
      // the main carrier never goes out
      {"kniterate", "carrier-left-in", [](const std::string& t) { return replace_first(t, "\nout 1\n", "\n"); }},
      // a back-bed stitch on a needle that holds nothing
      {"kniterate", "empty-needle-knit",
       [](const std::string& t) {
         const size_t i = t.find("; course 1");
         const size_t j = t.find("knit - b", i);
         const size_t sp = t.find(' ', j + 7);
         const int n = std::stoi(t.substr(j + 8, sp - j - 8));
         return t.substr(0, j) + "knit - b" + std::to_string(n - 1) + t.substr(sp);
       }},
  };
  for (const Broken& b : cases) {
    SCOPED_TRACE(std::string(b.machine) + " " + b.check);
    const std::string text = b.edit(programs.at(b.machine));
    ASSERT_NE(text, programs.at(b.machine)) << "the edit found nothing to break";
    // judged as knitforge judges programs (simulate --strict all): the
    // profile's warnings are refusals too
    SimulateOptions so;
    so.strict = all_rules_strict();
    const KnitoutSimulation sim = simulate_knitout(parse_knitout(text), machine_profile(b.machine), so);
    const auto ids = check_ids(sim);
    EXPECT_FALSE(sim.ok());
    EXPECT_NE(std::find(ids.begin(), ids.end(), b.check), ids.end()) << sim.text();
  }
}

TEST(TubeSimulator, BackHalfKnittedOnTheFrontDiffersFromTheMap) {
  // The same stitches, but course 0's back half knitted on the front bed's
  // free needles: the simulator accepts it, the comparison names the bed.
  const KnittingMap map = small_tube(8, 3);
  const auto& prof = machine_profile("kniterate");
  std::string t = write_knitout(map, prof).text;
  const size_t i = t.find("; course 0");
  const size_t j = t.find("; course 1", i);
  std::string block = t.substr(i, j - i);
  size_t k = 0;
  while ((k = block.find("knit - b", k)) != std::string::npos) block.replace(k, 8, "knit - f"), k += 8;
  t = t.substr(0, i) + block + t.substr(j);
  const KnitoutSimulation sim = simulate_knitout(parse_knitout(t), prof);
  const GraphComparison cmp = compare_knit_graph(sim.graph, map);
  EXPECT_FALSE(cmp.ok());
  bool bed = false;
  for (const auto& m : cmp.issues) bed = bed || m.kind == "bed";
  EXPECT_TRUE(bed) << cmp.text();
}

}  // namespace
}  // namespace knitforge
