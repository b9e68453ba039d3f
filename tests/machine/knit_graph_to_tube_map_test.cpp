// Shaped tubes read back from their programs (knit_graph_to_map.h, "Tubes"):
// map -> tube knitout -> virtual machine -> knit_graph_fabric() -> the map.
#include <fmt/core.h>
#include <gtest/gtest.h>

#include <string>
#include <utility>
#include <vector>

#include "convert/map_test_helpers.h"
#include "knitforge/convert/map_knittability.h"
#include "knitforge/convert/map_to_stitch_mesh.h"
#include "knitforge/convert/pack_tube_columns.h"
#include "knitforge/convert/sample_knitting_map.h"
#include "knitforge/design/tube/design_tube.h"
#include "knitforge/geometry/shapes.h"
#include "knitforge/machine/knit_graph_compare.h"
#include "knitforge/machine/knit_graph_to_map.h"
#include "knitforge/machine/knitout_parse.h"
#include "knitforge/machine/knitout_writer.h"

namespace knitforge {
namespace {

// A tube drawn top row first (test::parse_map), every row a round going
// `dir` from seam line `seam` unless listed in `open` (short rows).
KnittingMap tube_map(const std::vector<std::string>& top_first, int dir, int seam,
                     const std::vector<int>& open = {}) {
  KnittingMap m = test::parse_map(top_first);
  m.direction.assign(static_cast<size_t>(m.rows), static_cast<int8_t>(dir));
  m.seam.assign(static_cast<size_t>(m.rows), seam);
  for (int r : open) m.seam[static_cast<size_t>(r)] = -1;
  return m;
}

// Increases on both halves in round 2, decreases in round 5.
KnittingMap increases_and_decreases() {
  return tube_map({"KKK.KKKKKKKK.KKK",  //
                   "KKK.KKKKKKKK.KKK",  //
                   "KKKDKKKKKKKKDKKK",  //
                   "KKKKKKKKKKKKKKKK",  //
                   "KKKKKKKKKKKKKKKK",  //
                   "KKIKKIKKKKIKKIKK",  //
                   "KK.KK.KKKK.KK.KK",  //
                   "KK.KK.KKKK.KK.KK"},
                  1, 0);
}

// Increases, then a heel of four short rows on the back half (turning in
// and out at the seam where the rounds end), then decreases.
KnittingMap shaped_heel() {
  KnittingMap m = tube_map({"KKKKK.KKK.KKKKKK",  //
                            "KKKKKDKKKDKKKKKK",  //
                            "...........LKKKR",  //
                            "...........LKKR.",  //
                            "..........LKKKR.",  //
                            "..........LKKKKR",  //
                            "KKKKKKKKKKKKKKKK",  //
                            "KKIKKKKKKKKKKIKK",  //
                            "KK.KKKKKKKKKK.KK",  //
                            "KK.KKKKKKKKKK.KK"},
                           1, 0, {4, 5, 6, 7});
  m.direction[4] = m.direction[6] = -1;
  return m;
}

KnittingMap small_tapered(int dir = 1, bool closed = false) {
  KnittingMap m = test::small_tapered_tube();
  if (dir < 0) {
    m.direction.assign(static_cast<size_t>(m.rows), -1);
    for (size_t r = 0; r < m.seam.size(); ++r) m.seam[r] = 4 + static_cast<int>(r) / 2;  // s, s or s+1, ...
    m = canonical_cells(m);
  }
  m.closed_end = closed;
  return m;
}

// As the tube route's elbow wedges: short rows across the right fold, the
// seam moving from line 8 to line 9 (knitout_tube_writer_test.cpp).
KnittingMap wedge_across_the_fold() {
  return test::tube_with_short_rows(8, 9, {0, 0, 4, 4, 5, 5, 0, 0}, {11, 11, 7, 6, 6, 8, 11, 11});
}

int count(const KnittingMap& m, CellType t) {
  int n = 0;
  for (CellType c : m.cells) n += c == t;
  return n;
}

// Writes `map` for both profiles, reads the fabric back and expects the
// packed map (pack_tube_columns.h), every cell naming its loop.
void expect_round_trip(const std::string& what, const KnittingMap& map) {
  const KnittingMap want = pack_tube_columns(map);
  for (const char* prof : {"kniterate", "shima-swg091n2"}) {
    SCOPED_TRACE(what + " on " + prof);
    const KnitoutProgram p = write_knitout(map, machine_profile(prof));
    ASSERT_TRUE(p.simulation->ok()) << p.simulation->text();
    ASSERT_TRUE(p.comparison->ok()) << p.comparison->text();
    const KnitGraphFabric f = knit_graph_fabric(*p.simulation);
    ASSERT_EQ(f.kind, "tube") << f.reason;
    EXPECT_TRUE(f.reason.empty()) << f.reason;
    ASSERT_TRUE(f.map.tubular());
    EXPECT_EQ(f.map.rows, want.rows);
    EXPECT_EQ(f.map.cols, want.cols);
    EXPECT_EQ(f.map.direction, want.direction);
    EXPECT_EQ(f.map.seam, want.seam);
    EXPECT_EQ(f.map.closed_end, want.closed_end);
    EXPECT_TRUE(f.map == want) << "got\n" << test::draw_map(f.map) << "want\n" << test::draw_map(want);
    int cells = 0;
    for (size_t i = 0; i < f.loop_of_cell.size(); ++i) {
      if (f.loop_of_cell[i] < 0) continue;
      ++cells;
      EXPECT_TRUE(is_stitch(f.map.cells[i]));
      EXPECT_EQ(f.cell_of_loop[static_cast<size_t>(f.loop_of_cell[i])], static_cast<int>(i));
    }
    EXPECT_EQ(cells, map.num_stitches());
    // Shaped: no rounds x ring description (that is for plain tubes).
    bool plain = true;
    for (int r = 0; r < map.rows; ++r) plain = plain && map.closed(r);
    plain = plain && count(map, CellType::Increase) + count(map, CellType::Decrease) == 0;
    EXPECT_EQ(f.ring > 0, plain);
  }
}

TEST(KnitGraphToTubeMap, CraftedShapedTubesComeBackCellByCell) {
  const std::vector<std::pair<std::string, KnittingMap>> maps = {
      {"increases and decreases", increases_and_decreases()},
      {"heel with increases and decreases", shaped_heel()},
      {"tapered", small_tapered()},
      {"tapered, rounds going left from moving seams", small_tapered(-1)},
      {"tapered, closed at the end", small_tapered(1, true)},
      {"heel", test::heel_tube()},
      {"wedge across the right fold", wedge_across_the_fold()},
  };
  for (const auto& [what, map] : maps) {
    SCOPED_TRACE(what);
    const KnittabilityReport rep = check_knittability(map);
    ASSERT_TRUE(rep.ok()) << rep.text() << test::draw_map(map);
    // drawn with packed columns: the round trip gives them back exactly
    ASSERT_TRUE(pack_tube_columns(map) == canonical_cells(map)) << test::draw_map(pack_tube_columns(map));
    expect_round_trip(what, map);
  }
  const KnittingMap heel = shaped_heel();
  EXPECT_EQ(count(heel, CellType::Increase), 2);
  EXPECT_EQ(count(heel, CellType::Decrease), 2);
  EXPECT_EQ(count(heel, CellType::ShortRowLeft), 4);
}

TEST(KnitGraphToTubeMap, BuiltInTubesComeBackAsTheirMaps) {
  for (const std::string& n : sample_map_names())
    if (sample_knitting_map(n).tubular()) expect_round_trip("sample " + n, sample_knitting_map(n));
  TubeDesignOptions o;
  o.params = {7.0, 5.6};
  const std::vector<std::pair<std::string, TriMesh>> shapes = {{"sleeve", sleeve(SleeveShape{}, 6.0)},
                                                               {"sock", sock(SockShape{}, 6.0)},
                                                               {"beanie", beanie(BeanieShape{}, 6.0)}};
  for (const auto& [name, surface] : shapes) {
    SCOPED_TRACE(name);
    const TubeDesign d = design_tube(surface, o);
    ASSERT_TRUE(d.map_check.ok()) << d.map_check.text();
    EXPECT_GT(d.decreases, 10);
    EXPECT_GT(d.short_rows, 0);
    expect_round_trip(name, d.map);
    if (name != "sleeve") {
      EXPECT_TRUE(d.map.closed_end);
    }
    if (name == "sock") {
      EXPECT_GT(d.increases, 0);
    }
  }
}

// Two-bed programs that are no tube: the reason says what is wrong.
TEST(KnitGraphToTubeMap, TwoBedProgramsThatAreNoTubeSayWhy) {
  auto fabric_of = [](const std::string& text, const char* prof) {
    return knit_graph_fabric(simulate_knitout(parse_knitout(text), machine_profile(prof)));
  };
  // Two layers: each bed knitted left to right, one course after the other
  // (the yarn floats back across): the first "round" holds the front only.
  std::string layers = ";!knitout-2\n;;Carriers: 1 2 3\nin 1\n";
  for (int row = 0; row < 4; ++row)
    for (char bed : {'f', 'b'})
      for (int n = 1; n <= 4; ++n) layers += fmt::format("knit + {}{} 1\n", bed, 2 * n + (bed == 'b'));
  layers += "out 1\n";
  const KnitGraphFabric two = fabric_of(layers, "generic");
  EXPECT_EQ(two.kind, "");
  EXPECT_NE(two.reason.find("neither a tube"), std::string::npos) << two.reason;
  EXPECT_NE(two.reason.find("0 on the back half"), std::string::npos) << two.reason;

  // A tube whose first round knits its back half on the front bed's free
  // needles: those wales change beds.
  const KnittingMap map = small_tapered();
  const auto& prof = machine_profile("kniterate");
  std::string t = write_knitout(map, prof).text;
  const size_t i = t.find("; course 0");
  const size_t j = t.find("; course 1", i);
  std::string block = t.substr(i, j - i);
  for (size_t k = 0; (k = block.find("knit - b", k)) != std::string::npos; k += 8)
    block.replace(k, 8, "knit - f");
  const KnitGraphFabric moved = fabric_of(t.substr(0, i) + block + t.substr(j), "kniterate");
  EXPECT_EQ(moved.kind, "");
  EXPECT_NE(moved.reason.find("moves to the other bed"), std::string::npos) << moved.reason;
}

}  // namespace
}  // namespace knitforge
