#include "knitforge/convert/map_to_stitch_mesh.h"

#include <gtest/gtest.h>

#include <cmath>
#include <set>

#include "convert/map_test_helpers.h"
#include "knitforge/convert/random_knitting_map.h"
#include "knitforge/convert/stitch_mesh_to_map.h"
#include "knitforge/core/stitch_adjacency.h"

using namespace knitforge;
using namespace knitforge::test;

namespace {

const KnitParams kP{3.5, 2.8};

// The hand-made maps of the round-trip tests (canonical).
KnittingMap plain() { return parse_map({"KKKK", "KKKK", "KKKK"}); }
KnittingMap one_short_row_pair() {
  return parse_map({"KKKKKK",
                    "..LKKK",
                    "..LKKK",
                    "KKKKKK"});
}
KnittingMap nested_short_rows() {
  return parse_map({"KKKKKKK",
                    "...LKKK",
                    "...LKKK",
                    ".LKKKKK",
                    ".LKKKKK",
                    "KKKKKKK"});
}
KnittingMap one_short_column() {
  return parse_map({"KKK.KKK",
                    "KKKDKKK",
                    "KKKKKKK",
                    "KKKIKKK",
                    "KKK.KKK"});
}
// Short rows turning over a short column that has ended: the cells where
// neither the course nor the wale passes are Empty in canonical form.
KnittingMap short_row_over_short_column() {
  return parse_map({"K.KKKKK",
                    "._LKKKK",
                    "._LKKKK",
                    "KDKKKKK",
                    "KKKKKKK",
                    "KKKKKKK"});
}

struct Topo {
  int V, E, F, loops;
};
Topo topology(const StitchMesh& m) {
  const StitchAdjacency adj(m);
  const Halfedges& he = adj.halfedges();
  return {he.num_vertices(), he.num_edges(), he.num_faces(), static_cast<int>(he.boundary_loops().size())};
}

}  // namespace

TEST(MapToStitchMesh, PlainRectangle) {
  const StitchMesh m = map_to_stitch_mesh_topology(plain(), kP);
  EXPECT_EQ(m.num_stitches(), 12);
  EXPECT_EQ(m.num_vertices(), 20);
  const Topo t = topology(m);
  EXPECT_EQ(t.V - t.E + t.F, 1);
  EXPECT_EQ(t.loops, 1);
  // Knitting order: row 0 left to right, row 1 right to left.
  EXPECT_EQ(m.stitches[0].wale, 0);
  EXPECT_EQ(m.stitches[3].wale, 3);
  EXPECT_EQ(m.stitches[4].wale, 3);
  EXPECT_EQ(m.stitches[4].course, 1);
  EXPECT_EQ(m.stitches[4].direction, -1);
  EXPECT_TRUE(one_stroke_in_index_order(m));
  // Initial positions: the grid corners.
  const Stitch& s = m.stitches[5];  // row 1, column 2
  EXPECT_EQ(s.wale, 2);
  EXPECT_NEAR(m.vertices[s.v[0]].x(), 2 * 3.5, 1e-12);
  EXPECT_NEAR(m.vertices[s.v[0]].y(), 1 * 2.8, 1e-12);
  EXPECT_NEAR(m.vertices[s.v[2]].x(), 3 * 3.5, 1e-12);
  EXPECT_NEAR(m.vertices[s.v[2]].y(), 2 * 2.8, 1e-12);
  // Roles: row 0 cast on, row 2 bound off, nothing else.
  for (const Stitch& st : m.stitches) {
    EXPECT_EQ(st.roles, st.course == 0 ? kRoleCastOn : st.course == 2 ? kRoleBindOff : kRoleNone);
  }
}

TEST(MapToStitchMesh, ShortRowPairMergesTheApexes) {
  const StitchMesh m = map_to_stitch_mesh_topology(one_short_row_pair(), kP);
  EXPECT_EQ(m.num_stitches(), 20);
  // 5 x 7 grid corners; V(1,0)=V(2,0)=V(3,0), V(1,1)=V(2,1)=V(3,1) and the
  // apex V(1,2)=V(2,2)=V(3,2) each remove two.
  EXPECT_EQ(m.num_vertices(), 35 - 6);
  const Topo t = topology(m);
  EXPECT_EQ(t.V - t.E + t.F, 1);
  EXPECT_EQ(t.loops, 1);
  EXPECT_EQ(count_boundary_apexes(m), 0);
  EXPECT_TRUE(one_stroke_in_index_order(m));
  // The two turning stitches share their apex and are stacked.
  std::vector<int> turning;
  for (int s = 0; s < m.num_stitches(); ++s) {
    if (m.stitches[s].type == StitchType::ShortRowLeft) turning.push_back(s);
  }
  ASSERT_EQ(turning.size(), 2u);
  EXPECT_EQ(apex_vertex(m.stitches[turning[0]]), apex_vertex(m.stitches[turning[1]]));
  const StitchAdjacency adj(m);
  EXPECT_EQ(adj.neighbor(turning[0], Side::Top), turning[1]);
  // The wale at column 0 passes the short rows: row 0 and row 3 are neighbours.
  int s00 = -1, s30 = -1;
  for (int s = 0; s < m.num_stitches(); ++s) {
    if (m.stitches[s].wale == 0 && m.stitches[s].course == 0) s00 = s;
    if (m.stitches[s].wale == 0 && m.stitches[s].course == 3) s30 = s;
  }
  EXPECT_EQ(adj.neighbor(s00, Side::Top), s30);
  // The merged vertex lies at the mean of its grid corners.
  const Vec3 apex = m.vertices[apex_vertex(m.stitches[turning[0]])];
  EXPECT_NEAR(apex.x(), 2 * 3.5, 1e-12);
  EXPECT_NEAR(apex.y(), 2 * 2.8, 1e-12);
}

TEST(MapToStitchMesh, ShortColumnApexes) {
  const StitchMesh m = map_to_stitch_mesh_topology(one_short_column(), kP);
  EXPECT_EQ(m.num_stitches(), 33);
  // 6 x 8 corners; the collapsed cells at rows 0 and 4 merge V(0,3)=V(0,4),
  // V(1,3)=V(1,4) (also the increase apex), V(4,3)=V(4,4) (the decrease
  // apex), V(5,3)=V(5,4).
  EXPECT_EQ(m.num_vertices(), 48 - 4);
  const Topo t = topology(m);
  EXPECT_EQ(t.V - t.E + t.F, 1);
  EXPECT_EQ(t.loops, 1);
  EXPECT_EQ(count_boundary_apexes(m), 0);
  const auto counts = count_stitch_types(m);
  EXPECT_EQ(counts[static_cast<int>(StitchType::Increase)], 1);
  EXPECT_EQ(counts[static_cast<int>(StitchType::Decrease)], 1);
  // Row 0: stitches at columns 2 and 4 are neighbours across the missing wale.
  const StitchAdjacency adj(m);
  EXPECT_EQ(m.stitches[adj.neighbor(2, Side::Right)].wale, 4);
}

TEST(MapToStitchMesh, NeitherCollapsedCellsAreEmpty) {
  KnittingMap m = short_row_over_short_column();
  // Writing Collapsed where neither course nor wale passes changes nothing.
  KnittingMap with_collapsed = m;
  with_collapsed.at(3, 1) = with_collapsed.at(4, 1) = CellType::Collapsed;
  EXPECT_TRUE(canonical_cells(with_collapsed) == m);
  const StitchMesh a = map_to_stitch_mesh_topology(m, kP), b = map_to_stitch_mesh_topology(with_collapsed, kP);
  EXPECT_EQ(a.num_vertices(), b.num_vertices());
  ASSERT_EQ(a.num_stitches(), b.num_stitches());
  for (int s = 0; s < a.num_stitches(); ++s) EXPECT_EQ(a.stitches[s].v, b.stitches[s].v);
  EXPECT_EQ(count_boundary_apexes(a), 0);
  const Topo t = topology(a);
  EXPECT_EQ(t.V - t.E + t.F, 1);
  EXPECT_EQ(t.loops, 1);
}

TEST(MapToStitchMesh, RoundTripOnHandMadeMaps) {
  for (const KnittingMap& m : {plain(), one_short_row_pair(), nested_short_rows(), one_short_column(),
                               short_row_over_short_column()}) {
    const KnittingMap back = stitch_mesh_to_map(map_to_stitch_mesh_topology(m, kP));
    EXPECT_TRUE(back == m) << "in:\n" << draw_map(m) << "out:\n" << draw_map(back);
  }
}

TEST(MapToStitchMesh, RoundTripOnRandomMaps) {
  int n = 0;
  for (uint64_t seed = 100; seed < 300; ++seed) {
    RandomMapOptions o;
    o.seed = seed;
    o.rows = 5 + static_cast<int>((seed * 13) % 30);
    o.cols = 6 + static_cast<int>((seed * 7) % 30);
    const int max_ends = 2 * (o.rows - 3);
    o.short_row_ends = 2 * static_cast<int>(seed % (max_ends / 2 + 1));
    o.short_columns = static_cast<int>(seed % std::max(1, (o.cols - 2) / 2));
    o.boundary_shaping = seed % 3 == 0;
    if (o.boundary_shaping) {
      o.short_row_ends = std::min(o.short_row_ends, 2 * std::max(0, o.rows * 3 / 5 - 4));
      o.short_columns = std::min(o.short_columns, std::max(0, o.cols / 2 - 4));
    }
    KnittingMap m;
    try {
      m = random_knitting_map(o);
    } catch (const InvalidInput&) {
      continue;  // an over-full request for this size
    }
    ++n;
    const StitchMesh mesh = map_to_stitch_mesh_topology(m, kP);
    const KnittingMap back = stitch_mesh_to_map(mesh);
    ASSERT_TRUE(back == m) << "seed " << seed << "\n" << draw_map(m) << "out:\n" << draw_map(back);
    // Courses and wales of the mesh are the map rows and columns.
    for (const Stitch& s : mesh.stitches) {
      ASSERT_EQ(to_cell_type(s.type), m.at(s.course, s.wale));
      ASSERT_EQ(s.direction, m.direction[s.course]);
    }
  }
  EXPECT_GE(n, 150);
}

TEST(MapToStitchMesh, YarnIsCarried) {
  KnittingMap m = one_short_row_pair();
  m.set_yarn(1, 4, 2);
  m.set_yarn(3, 0, 1);
  const StitchMesh mesh = map_to_stitch_mesh_topology(m, kP);
  for (const Stitch& s : mesh.stitches) EXPECT_EQ(s.yarn, m.yarn_at(s.course, s.wale));
  EXPECT_TRUE(stitch_mesh_to_map(mesh) == m);
}

TEST(MapToStitchMesh, OutsideIncreaseAndDecreaseRoles) {
  // Row 1 (right to left) widens on the left, row 3 narrows on the left.
  const KnittingMap m = parse_map({"_KKKK",
                                   "KKKKK",
                                   "KKKKK",
                                   "_KKKK"});
  const StitchMesh mesh = map_to_stitch_mesh_topology(m, kP);
  for (const Stitch& s : mesh.stitches) {
    const bool inc = s.course == 1 && s.wale == 0, dec = s.course == 3 && s.wale == 1;
    EXPECT_EQ((s.roles & kRoleOutsideIncrease) != 0, inc) << s.course << "," << s.wale;
    EXPECT_EQ((s.roles & kRoleOutsideDecrease) != 0, dec) << s.course << "," << s.wale;
    // The widened stitch has nothing below it: it is cast on as well.
    if (inc) {
      EXPECT_TRUE(s.roles & kRoleCastOn);
    }
  }
  EXPECT_TRUE(stitch_mesh_to_map(mesh) == m);
}

namespace {
std::string error_of(const KnittingMap& m) {
  try {
    map_to_stitch_mesh_topology(m, kP);
  } catch (const InvalidInput& e) {
    return e.what();
  }
  return "";
}
}  // namespace

TEST(MapToStitchMesh, InvalidMapsNameTheCell) {
  // Collapsed inside both its row and its column.
  std::string e = error_of(parse_map({"KKK", "K.K", "KKK"}));
  EXPECT_NE(e.find("(row 1, column 1)"), std::string::npos) << e;
  EXPECT_NE(e.find("both"), std::string::npos) << e;
  // Two runs in a row (split by an Empty cell, or by a short-row end in the middle).
  e = error_of(parse_map({"KKKK", "K_KK", "KKKK"}));
  EXPECT_NE(e.find("(row 1, column 1)"), std::string::npos) << e;
  EXPECT_NE(e.find("two separate runs"), std::string::npos) << e;
  e = error_of(parse_map({"KKKK", "KRKK", "KKKK"}));
  EXPECT_NE(e.find("(row 1, column 1)"), std::string::npos) << e;
  // Direction not +-1.
  KnittingMap d = plain();
  d.direction[2] = 0;
  e = error_of(d);
  EXPECT_NE(e.find("row 2"), std::string::npos) << e;
  EXPECT_NE(e.find("direction"), std::string::npos) << e;
  // Degenerate stitch: a knit above a decrease loses its bottom side.
  e = error_of(parse_map({"KKK", "KDK"}));
  EXPECT_NE(e.find("(row 1, column 1)"), std::string::npos) << e;
  EXPECT_NE(e.find("degenerates"), std::string::npos) << e;
  // A row without stitches.
  e = error_of(parse_map({"KKK", "___", "KKK"}));
  EXPECT_NE(e.find("row 1 holds no stitch"), std::string::npos) << e;
  // Wrong array sizes.
  KnittingMap bad = plain();
  bad.cells.pop_back();
  EXPECT_THROW(map_to_stitch_mesh_topology(bad, kP), InvalidInput);
  EXPECT_THROW(map_to_stitch_mesh_topology(plain(), KnitParams{0, 2.8}), InvalidInput);
}

TEST(MapToStitchMesh, NonManifoldResultIsInvalidInput) {
  // Two courses that touch only at a corner.
  const KnittingMap m = parse_map({"_K", "K_"});
  EXPECT_THROW(map_to_stitch_mesh_topology(m, kP), InvalidInput);
}

namespace {

TEST(MapToStitchMesh, TubeRoundsCloseAcrossTheSeamInKnittingOrder) {
  KnittingMap m(3, 6, CellType::Knit);
  m.direction = {1, 1, -1};
  m.seam = {0, 2, 2};
  const StitchMesh mesh = map_to_stitch_mesh_topology(m, kP);
  ASSERT_EQ(mesh.num_stitches(), 18);
  const StitchAdjacency adj(mesh);
  for (int s = 0; s < mesh.num_stitches(); ++s) {
    for (Side side : {Side::Left, Side::Right, Side::Top, Side::Bottom}) {
      const int t = adj.neighbor(s, side);
      if (side == Side::Left || side == Side::Right) {
        ASSERT_GE(t, 0) << "a round has no Left/Right boundary";
        const int dc = ((mesh.stitches[t].wale - mesh.stitches[s].wale) % 6 + 6) % 6;
        EXPECT_EQ(dc, side == Side::Right ? 1 : 5);
        EXPECT_EQ(mesh.stitches[t].course, mesh.stitches[s].course);
      }
    }
  }
  // knitting order: row 0 from column 0, row 1 from column 2 going right,
  // row 2 from column 1 going left (the first at or left of seam - 1)
  EXPECT_EQ(mesh.stitches[0].wale, 0);
  EXPECT_EQ(mesh.stitches[6].wale, 2);
  EXPECT_EQ(mesh.stitches[11].wale, 1);
  EXPECT_EQ(mesh.stitches[12].wale, 1);
  EXPECT_EQ(mesh.stitches[13].wale, 0);
  EXPECT_EQ(mesh.stitches[14].wale, 5);
  // no boundary roles on the rounds' sides, cast-on below and bind-off above
  for (const Stitch& s : mesh.stitches) {
    EXPECT_EQ((s.roles & (kRoleOutsideIncrease | kRoleOutsideDecrease)), 0);
    EXPECT_EQ((s.roles & kRoleCastOn) != 0, s.course == 0);
    EXPECT_EQ((s.roles & kRoleBindOff) != 0, s.course == 2);
  }
  // the flat positions lie on a cylinder of circumference 6 stitch widths
  const double radius = 6 * kP.stitch_width / (2 * 3.14159265358979323846);
  for (const Vec3& v : mesh.vertices) EXPECT_NEAR(std::hypot(v.x(), v.z()), radius, 1e-9);
  // the same cells as a sheet have open rows
  KnittingMap sheet = m;
  sheet.seam.clear();
  const StitchMesh flat = map_to_stitch_mesh_topology(sheet, kP);
  const StitchAdjacency fadj(flat);
  int open_sides = 0;
  for (int s = 0; s < flat.num_stitches(); ++s) open_sides += fadj.neighbor(s, Side::Right) < 0;
  EXPECT_EQ(open_sides, 3);
}

TEST(MapToStitchMesh, ClosedRowsRefuseShortRowEndsAndEmptyCells) {
  KnittingMap m(2, 4, CellType::Knit);
  m.seam = {0, 0};
  m.direction = {1, 1};
  m.at(1, 3) = CellType::Empty;
  EXPECT_THROW(map_to_stitch_mesh_topology(m, kP), InvalidInput);
  m.at(1, 3) = CellType::ShortRowRight;
  try {
    map_to_stitch_mesh_topology(m, kP);
    FAIL() << "no exception";
  } catch (const InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find("closed row"), std::string::npos) << e.what();
  }
}

}  // namespace
