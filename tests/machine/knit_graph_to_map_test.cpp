#include "knitforge/machine/knit_graph_to_map.h"

#include <gtest/gtest.h>

#include "knitforge/convert/map_to_stitch_mesh.h"
#include "knitforge/convert/random_knitting_map.h"
#include "knitforge/convert/sample_knitting_map.h"
#include "knitforge/machine/knit_graph_compare.h"
#include "knitforge/machine/knitout_writer.h"
#include "machine/machine_test_maps.h"

namespace knitforge {
namespace {

// The writer's programs come back as their own maps: the reconstruction is
// the writer's inverse on canonical maps (short rows, short columns, edge
// shaping, bind-off chains, waste sections).
TEST(KnitGraphToMap, TheWritersProgramsGiveTheirMapsBack) {
  std::vector<std::pair<std::string, KnittingMap>> maps = test::hand_made_maps();
  for (const auto& n : sample_map_names())
    if (!sample_knitting_map(n).tubular())  // tubes: knitout_tube_writer_test.cpp
      maps.push_back({"sample " + n, sample_knitting_map(n)});
  for (uint64_t seed = 1; seed <= 24; ++seed) {
    RandomMapOptions ro;
    ro.seed = seed;
    ro.rows = 26;
    ro.cols = 22;
    ro.short_row_ends = 2 * static_cast<int>(seed % 6);
    ro.short_columns = static_cast<int>(seed % 5);
    ro.boundary_shaping = seed % 3 == 0;
    maps.push_back({"random " + std::to_string(seed), random_knitting_map(ro)});
  }
  int identical = 0;
  for (const char* prof : {"shima-swg091n2", "kniterate"}) {
    for (const auto& [what, map] : maps) {
      SCOPED_TRACE(what + " on " + prof);
      const KnitoutProgram p = write_knitout(map, machine_profile(prof));
      const KnitGraphFabric f = knit_graph_fabric(*p.simulation);
      ASSERT_EQ(f.kind, "sheet") << f.reason;
      const KnittingMap want = canonical_cells(map);
      EXPECT_EQ(f.map.rows, want.rows);
      EXPECT_EQ(f.map.direction, want.direction);
      EXPECT_EQ(f.map.num_stitches(), want.num_stitches());
      // Short columns that never share a course may sit in either order
      // (the map does not fix it); without them the map is the same.
      bool short_columns = false;
      for (CellType t : want.cells) short_columns |= t == CellType::Increase || t == CellType::Decrease;
      if (!short_columns) {
        EXPECT_EQ(f.map, want);
      }
      identical += f.map == want;
      // every stitch cell names its loop and back
      int cells = 0;
      for (size_t i = 0; i < f.loop_of_cell.size(); ++i) {
        if (f.loop_of_cell[i] < 0) continue;
        ++cells;
        EXPECT_EQ(f.cell_of_loop[static_cast<size_t>(f.loop_of_cell[i])], static_cast<int>(i));
      }
      EXPECT_EQ(cells, map.num_stitches());
    }
  }
  EXPECT_GE(identical, 2 * static_cast<int>(maps.size()) - 4);
}

TEST(KnitGraphToMap, CablesAndEmptyProgramsAreNotSheets) {
  // Two wales crossing (a 1x1 cable): their order differs between courses.
  const std::string cable =
      ";!knitout-2\n;;Carriers: 1 2 3\nin 1\n"
      "knit + f1 1\nknit + f2 1\nknit + f3 1\nknit + f4 1\n"
      "knit - f4 1\nknit - f3 1\nknit - f2 1\nknit - f1 1\n"
      "xfer f2 b2\nxfer f3 b3\nrack 1\nxfer b2 f3\nrack 0\nrack -1\nxfer b3 f2\nrack 0\n"
      "knit + f1 1\nknit + f2 1\nknit + f3 1\nknit + f4 1\nout 1\n; leave-loops\n";
  const KnitGraphFabric c =
      knit_graph_fabric(simulate_knitout(parse_knitout(cable), machine_profile("generic")));
  EXPECT_EQ(c.kind, "");
  EXPECT_NE(c.reason.find("cross"), std::string::npos) << c.reason;
  const KnitGraphFabric e = knit_graph_fabric(
      simulate_knitout(parse_knitout(";!knitout-2\n;;Carriers: 1\nin 1\ntuck + f1 1\nout 1\n"), machine_profile("generic")));
  EXPECT_EQ(e.kind, "");
  EXPECT_FALSE(e.reason.empty());
}

}  // namespace
}  // namespace knitforge
