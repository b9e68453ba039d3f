// Closed tubes (design/tube/tube_crown.h): a disk knitted in the round from
// its rim to its crown, the last round joined across the beds.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "knitforge/convert/map_knittability.h"
#include "knitforge/convert/map_to_stitch_mesh.h"
#include "knitforge/convert/stitch_mesh_to_map.h"
#include "knitforge/core/stitch.h"
#include "knitforge/design/tube/design_tube.h"
#include "knitforge/geometry/shapes.h"
#include "knitforge/io/knitting_map_csv.h"
#include "knitforge/util/errors.h"

namespace knitforge {
namespace {

int row_stitches(const KnittingMap& m, int r, int lo, int hi) {
  int n = 0;
  for (int c = lo; c < hi; ++c) n += is_stitch(m.at(r, c)) ? 1 : 0;
  return n;
}

TubeDesign beanie_design() {
  TubeDesignOptions o;
  o.params = {7.0, 5.6};
  o.crown_stitches = 12;
  return design_tube(beanie(BeanieShape{}, 6.0), o);
}

TEST(BeanieTube, KnittedFromTheRimToASmallClosedCrown) {
  const TubeDesign d = beanie_design();
  EXPECT_TRUE(d.mesh_check.ok()) << d.mesh_check.text();
  EXPECT_TRUE(d.map_check.ok()) << d.map_check.text();
  ASSERT_TRUE(d.map.tubular());
  EXPECT_TRUE(d.map.closed_end);
  for (int r = 0; r < d.map.rows; ++r) EXPECT_TRUE(d.map.closed(r)) << r;
  const int h = d.map.tube_half(), last = d.map.rows - 1;
  // The rim: 560 mm round at sw 7 -> 80 stitches; the crown small, halves equal.
  EXPECT_NEAR(row_stitches(d.map, 0, 0, d.map.cols), 80, 2);
  const int front = row_stitches(d.map, last, 0, h), back = row_stitches(d.map, last, h, d.map.cols);
  EXPECT_EQ(front, back);
  EXPECT_GE(front + back, 8);
  EXPECT_LE(front + back, 20);
  EXPECT_EQ(static_cast<int>(closing_pairs(d.map).size()), front);
  EXPECT_GT(d.decreases, 50);
  EXPECT_EQ(d.increases, 0);
  EXPECT_GT(d.rim_to_crown, 180.0);
  EXPECT_NEAR(d.crown_radius, 12 * 7.0 / (2.0 * std::numbers::pi), 1e-9);
  // Decreases spread: no row holds more than a quarter of its stitches as
  // decreases, and no two decreases side by side (map check above).
  for (int r = 0; r < d.map.rows; ++r) {
    int dec = 0;
    for (int c = 0; c < d.map.cols; ++c) dec += d.map.at(r, c) == CellType::Decrease ? 1 : 0;
    EXPECT_LE(4 * dec, row_stitches(d.map, r, 0, d.map.cols) + 4) << r;
  }
  // The last round's stitches carry the closing-seam role.
  for (const Stitch& s : d.stitch_mesh.stitches)
    EXPECT_EQ((s.roles & kRoleClosingSeam) != 0, s.course == last) << s.course;
}

TEST(BeanieTube, RoundTripsThroughMeshAndCsvExactly) {
  const TubeDesign d = beanie_design();
  const StitchMesh mesh = map_to_stitch_mesh_topology(d.map, KnitParams{7.0, 5.6});
  EXPECT_TRUE(stitch_mesh_to_map(mesh) == d.map);
  EXPECT_TRUE(stitch_mesh_to_map(d.stitch_mesh) == d.map);
  const KnittingMap back = knitting_map_from_csv(knitting_map_to_csv(d.map), "beanie.csv");
  EXPECT_TRUE(back == d.map);
  EXPECT_TRUE(back.closed_end);
  KnittingMap open = d.map;
  open.closed_end = false;
  EXPECT_FALSE(open == d.map);
  EXPECT_EQ(knitting_map_to_csv(open).find(":close"), std::string::npos);
}

TEST(BeanieTube, ClosingRuleAndRefusals) {
  // A closed end whose last round's halves differ is refused (tube-layout).
  KnittingMap m(3, 8, CellType::Knit);
  m.seam.assign(3, 0);
  for (int r = 0; r < 3; ++r) m.direction[static_cast<size_t>(r)] = 1;
  m.closed_end = true;
  EXPECT_TRUE(check_knittability(m, KnitParams{}).ok()) << check_knittability(m, KnitParams{}).text();
  EXPECT_EQ(closing_pairs(m), (std::vector<std::pair<int, int>>{{0, 7}, {1, 6}, {2, 5}, {3, 4}}));
  m.at(2, 5) = CellType::Collapsed;
  m.at(1, 5) = CellType::Decrease;
  const KnittabilityReport rep = check_knittability(m, KnitParams{});
  EXPECT_FALSE(rep.ok());
  EXPECT_NE(rep.text().find("closing seam"), std::string::npos) << rep.text();
  // A ':close' below the top line, and a closed sheet, are refused.
  EXPECT_THROW(knitting_map_from_csv("course,dir,seam,0,1,2,3\n1,>,0,K,K,K,K\n0,>,0:close,K,K,K,K\n", "t.csv"),
               IOError);
  KnittingMap sheet(2, 4, CellType::Knit);
  sheet.closed_end = true;
  EXPECT_THROW(check_map_arrays(sheet), InvalidInput);
  // Too small for its crown: a 10 mm disk with a 64-stitch crown.
  TubeDesignOptions o;
  o.params = {3.5, 2.8};
  o.crown_stitches = 64;
  EXPECT_THROW(design_tube(hemisphere(20.0, 2.5), o), InvalidInput);
  o.crown_stitches = 4;
  EXPECT_THROW(design_tube(hemisphere(40.0, 2.5), o), InvalidInput);
}

// The sock: a closed tube that bends (the heel), so it gets short-row
// wedges as an open bent tube does, and still closes at the toe with equal
// halves; the map round-trips.
TEST(SockTube, HeelWedgesAndAClosedToe) {
  TubeDesignOptions o;
  o.params = {7.0, 5.6};
  const TubeDesign d = design_tube(sock(SockShape{}, 6.0), o);
  EXPECT_TRUE(d.mesh_check.ok()) << d.mesh_check.text();
  EXPECT_TRUE(d.map_check.ok()) << d.map_check.text();
  ASSERT_TRUE(d.map.tubular());
  EXPECT_TRUE(d.map.closed_end);
  EXPECT_GT(d.wedges, 5);  // the heel bends by (70 + 38) / (70 - 38)
  EXPECT_GT(d.short_rows, 2 * d.wedges - 1);
  int open_rows = 0;
  for (int r = 0; r < d.map.rows; ++r) open_rows += d.map.closed(r) ? 0 : 1;
  EXPECT_EQ(open_rows, d.short_rows);
  const int last = d.map.rows - 1, h = d.map.tube_half();
  EXPECT_TRUE(d.map.closed(last));
  EXPECT_EQ(row_stitches(d.map, last, 0, h), row_stitches(d.map, last, h, d.map.cols));
  EXPECT_FALSE(closing_pairs(d.map).empty());
  // 239 mm round at sw 7: 34 stitches in the leg
  EXPECT_NEAR(row_stitches(d.map, 0, 0, d.map.cols), 34, 1);
  EXPECT_TRUE(stitch_mesh_to_map(map_to_stitch_mesh_topology(d.map, o.params)) == d.map);
  EXPECT_TRUE(knitting_map_from_csv(knitting_map_to_csv(d.map), "sock.csv") == d.map);
  // Without short rows the same sock is knitted in plain rounds.
  o.short_rows = false;
  const TubeDesign plain = design_tube(sock(SockShape{}, 6.0), o);
  EXPECT_EQ(plain.wedges, 0);
  EXPECT_TRUE(plain.map.closed_end);
  EXPECT_TRUE(plain.map_check.ok()) << plain.map_check.text();
}

}  // namespace
}  // namespace knitforge
