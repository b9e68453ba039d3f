#include "knitforge/convert/pack_tube_columns.h"

#include <gtest/gtest.h>

#include "convert/map_test_helpers.h"
#include "knitforge/convert/map_knittability.h"
#include "knitforge/convert/map_to_stitch_mesh.h"
#include "knitforge/convert/sample_knitting_map.h"
#include "knitforge/core/stitch_adjacency.h"
#include "knitforge/util/errors.h"

namespace knitforge {
namespace {

const KnitParams kP{3.5, 2.8};

KnittingMap tube(const std::vector<std::string>& top_first, int seam = 0) {
  KnittingMap m = test::parse_map(top_first);
  m.direction.assign(static_cast<size_t>(m.rows), 1);
  m.seam.assign(static_cast<size_t>(m.rows), seam);
  return m;
}

// The same stitches in the same knitting order with the same neighbours.
void expect_same_fabric(const KnittingMap& a, const KnittingMap& b) {
  const StitchMesh ma = map_to_stitch_mesh_topology(a, kP), mb = map_to_stitch_mesh_topology(b, kP);
  ASSERT_EQ(ma.num_stitches(), mb.num_stitches());
  const StitchAdjacency A(ma), B(mb);
  for (int s = 0; s < ma.num_stitches(); ++s) {
    EXPECT_EQ(ma.stitches[static_cast<size_t>(s)].type, mb.stitches[static_cast<size_t>(s)].type) << s;
    EXPECT_EQ(ma.stitches[static_cast<size_t>(s)].course, mb.stitches[static_cast<size_t>(s)].course) << s;
    for (Side side : {Side::Bottom, Side::Right, Side::Top, Side::Left})
      EXPECT_EQ(A.neighbor(s, side), B.neighbor(s, side)) << s << " side " << static_cast<int>(side);
  }
}

TEST(PackTubeColumns, ColumnsWithoutStitchesMoveToTheEndOfTheirHalf) {
  // The back half holds 5 wales in 6 columns: column 6 (at the right fold)
  // never has a stitch, column 9 only from the increase in round 2 on.
  const KnittingMap m = tube({"KKKKKK.KKKKK",  //
                              "KKKKKK.KKIKK",  //
                              "KKKKKK.KK.KK",  //
                              "KKKKKK.KK.KK"});
  ASSERT_TRUE(check_knittability(m).ok()) << check_knittability(m).text();
  const KnittingMap p = pack_tube_columns(m);
  const KnittingMap want = tube({"KKKKKKKKKKK.",  //
                                 "KKKKKKKKIKK.",  //
                                 "KKKKKKKK.KK.",  //
                                 "KKKKKKKK.KK."});
  EXPECT_TRUE(p == canonical_cells(want)) << test::draw_map(p);
  expect_same_fabric(m, p);
  EXPECT_TRUE(pack_tube_columns(p) == p);
}

TEST(PackTubeColumns, AWaleEndedByADecreaseLeavesItsColumnToALaterIncrease) {
  // Column 2 ends in a decrease in round 1; a new wale starts between the
  // same neighbours in round 4 in column 3. Packed they share column 2;
  // the decrease keeps its column in the row above it, so a new wale
  // starting there in that row would not share it.
  const KnittingMap m = tube({"KK.KKKKKKKKK",  //
                              "KK.IKKKKKKKK",  //
                              "KK..KKKKKKKK",  //
                              "KK..KKKKKKKK",  //
                              "KKD.KKKKKKKK",  //
                              "KKK.KKKKKKKK"});
  ASSERT_TRUE(check_knittability(m).ok()) << check_knittability(m).text();
  const KnittingMap p = pack_tube_columns(m);
  EXPECT_EQ(p.cols, 12);
  EXPECT_EQ(p.at(1, 2), CellType::Decrease);
  EXPECT_EQ(p.at(4, 2), CellType::Increase);
  EXPECT_EQ(p.at(0, 3), CellType::Knit);  // the wale right of them moved left
  expect_same_fabric(m, p);
}

TEST(PackTubeColumns, PackedMapsAndSheetsAreLeftOrRefused) {
  for (const auto& n : sample_map_names()) {
    const KnittingMap m = sample_knitting_map(n);
    if (m.tubular()) {
      EXPECT_TRUE(pack_tube_columns(m) == m) << n;
    } else {
      EXPECT_THROW(pack_tube_columns(m), InvalidInput) << n;
    }
  }
  // the heel's short rows, seams and held wales stay as they are
  EXPECT_TRUE(pack_tube_columns(test::heel_tube()) == canonical_cells(test::heel_tube()));
}

}  // namespace
}  // namespace knitforge
