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
  // Plain rounds but for a few short rows where the rounds lie further
  // apart towards the crown segment's sides than its ends.
  int open_rows = 0;
  for (int r = 0; r < d.map.rows; ++r) open_rows += d.map.closed(r) ? 0 : 1;
  EXPECT_EQ(open_rows, d.short_rows);
  EXPECT_LE(d.wedges, 4);
  const int h = d.map.tube_half(), last = d.map.rows - 1;
  // The rim: 560 mm round at sw 7 -> 80 stitches; the crown small, halves equal.
  EXPECT_NEAR(row_stitches(d.map, 0, 0, d.map.cols), 80, 2);
  const int front = row_stitches(d.map, last, 0, h), back = row_stitches(d.map, last, h, d.map.cols);
  EXPECT_EQ(front, back);
  EXPECT_NEAR(front + back, 12, 1);  // the asked crown (crown segment, tube_crown.h)
  EXPECT_EQ(static_cast<int>(closing_pairs(d.map).size()), front);
  EXPECT_GT(d.decreases, 50);
  EXPECT_EQ(d.increases, 0);
  EXPECT_GT(d.rim_to_crown, 180.0);
  // The crown segment: its ring (2 s + 2 pi w) is the asked 12 x 7 mm.
  EXPECT_NEAR(2.0 * d.crown_segment + 2.0 * std::numbers::pi * d.crown_radius, 12 * 7.0, 3.0);
  EXPECT_NEAR(d.crown_ring, 12 * 7.0, 0.1 * 12 * 7.0);
  EXPECT_GT(d.crown_segment, 2.0 * 7.0);
  EXPECT_EQ(d.crown_direction_scores.size(), 6u);
  // Decreases spread: no row holds more than half of its stitches as
  // decreases (every other wale, at the crown), a quarter below the last
  // few rounds, and no two decreases side by side (map check above).
  for (int r = 0; r < d.map.rows; ++r) {
    int dec = 0;
    for (int c = 0; c < d.map.cols; ++c) dec += d.map.at(r, c) == CellType::Decrease ? 1 : 0;
    EXPECT_LE(2 * dec, row_stitches(d.map, r, 0, d.map.cols) + 2) << r;
    if (r + 4 < d.map.rows) {
      EXPECT_LE(4 * dec, row_stitches(d.map, r, 0, d.map.cols) + 4) << r;
    }
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

// The crown segment's closing round has the asked count within one stitch
// (the last row may not shape, so the round below it takes that count,
// decreasing every other wale where the crown narrows fast).
TEST(CrownSegment, TheClosingRoundHasTheAskedCount) {
  for (const bool is_sock : {false, true}) {
    for (const int asked : {10, 12, 16}) {
      TubeDesignOptions o;
      o.params = {7.0, 5.6};
      o.crown_stitches = asked;
      const TubeDesign d = design_tube(is_sock ? sock(SockShape{}, 6.0) : beanie(BeanieShape{}, 6.0), o);
      EXPECT_TRUE(d.map_check.ok()) << d.map_check.text();
      EXPECT_TRUE(d.mesh_check.ok()) << d.mesh_check.text();
      const int last = d.map.rows - 1;
      EXPECT_NEAR(row_stitches(d.map, last, 0, d.map.cols), asked, 1)
          << (is_sock ? "sock " : "beanie ") << asked;
      EXPECT_NEAR(d.round_stitches.back(), asked, 1);
      EXPECT_EQ(static_cast<int>(closing_pairs(d.map).size()) * 2, row_stitches(d.map, last, 0, d.map.cols));
    }
  }
  // A long segment on the sock's toe (32 stitches of 3.5 mm: s = 48 mm on a
  // 38 mm toe), whose tangent ends the projection pulls in by 10 %.
  TubeDesignOptions o;
  o.crown_stitches = 32;
  const TubeDesign d = design_tube(sock(SockShape{}, 4.0), o);
  EXPECT_NEAR(d.round_stitches.back(), 32, 1);
  EXPECT_NEAR(d.crown_ring, 32 * 3.5, 0.05 * 32 * 3.5);
}

// The sock's toe is closed side to side, as socks are grafted: the last
// round's two halves (the beds, joined in pairs) lie one above the other
// (instep and sole, along z: the foot runs along x, the sole at z = -38),
// each spanning the toe from side to side (along y).
TEST(CrownSegment, TheSocksToeSeamRunsSideToSide) {
  TubeDesignOptions o;
  o.params = {7.0, 5.6};
  const TubeDesign d = design_tube(sock(SockShape{}, 6.0), o);
  int last = 0;
  for (const Stitch& s : d.stitch_mesh.stitches) last = std::max(last, s.course);
  const int h = d.map.tube_half();
  Vec3 mean[2] = {Vec3::Zero(), Vec3::Zero()};
  double lo[2] = {1e9, 1e9}, hi[2] = {-1e9, -1e9};
  int count[2] = {0, 0};
  for (const Stitch& s : d.stitch_mesh.stitches) {
    if (s.course != last) continue;
    Vec3 c = Vec3::Zero();
    for (int q = 0; q < s.corners(); ++q)
      c += d.stitch_mesh.vertices[static_cast<size_t>(s.v[static_cast<size_t>(q)])];
    c /= s.corners();
    const int side = s.wale < h ? 0 : 1;
    mean[side] += c;
    ++count[side];
    lo[side] = std::min(lo[side], c.y());
    hi[side] = std::max(hi[side], c.y());
  }
  ASSERT_GT(count[0], 0);
  ASSERT_EQ(count[0], count[1]);
  for (int i = 0; i < 2; ++i) mean[i] /= count[i];
  // one half above the other; the crown ring's sides run along y
  EXPECT_GT(std::abs(mean[0].z() - mean[1].z()), 3.0) << mean[0].transpose() << " / " << mean[1].transpose();
  for (int i = 0; i < 2; ++i) EXPECT_GT(hi[i] - lo[i], d.crown_segment) << i;
}

}  // namespace
}  // namespace knitforge
