// The tube design route (design/tube): annulus -> rounds -> tubular map.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "knitforge/core/stitch.h"
#include "knitforge/design/tube/design_tube.h"
#include "knitforge/geometry/shapes.h"
#include "knitforge/util/errors.h"

namespace knitforge {
namespace {

// Stitch cells of map row r.
int row_stitches(const KnittingMap& m, int r) {
  int n = 0;
  for (int c = 0; c < m.cols; ++c) n += is_stitch(m.at(r, c)) ? 1 : 0;
  return n;
}

int count_cells(const KnittingMap& m, CellType t) {
  int n = 0;
  for (CellType c : m.cells) n += c == t ? 1 : 0;
  return n;
}

TEST(DesignTube, StraightTubeHasRoundsOfCircumferenceOverWidthAndNoShaping) {
  TubeDesignOptions o;
  o.params = {3.5, 2.8};
  const TubeDesign d = design_tube(open_tube(40.0, 100.0, 2.5), o);
  EXPECT_TRUE(d.mesh_check.ok()) << d.mesh_check.text();
  EXPECT_TRUE(d.map_check.ok()) << d.map_check.text();
  ASSERT_TRUE(d.map.tubular());
  const int expected = static_cast<int>(std::lround(2.0 * std::numbers::pi * 40.0 / 3.5));  // 72
  EXPECT_EQ(d.map.rows, static_cast<int>(std::lround(100.0 / 2.8)));                         // 36 rounds
  for (int r = 0; r < d.map.rows; ++r) {
    EXPECT_TRUE(d.map.closed(r)) << "row " << r;
    EXPECT_NEAR(row_stitches(d.map, r), expected, 1) << "row " << r;
  }
  EXPECT_EQ(d.increases + d.decreases, 0);
  EXPECT_EQ(count_cells(d.map, CellType::Increase) + count_cells(d.map, CellType::Decrease), 0);
  EXPECT_EQ(d.field.interior_extrema, 0);
  // Every stitch corner lies on the cylinder (rounds are isocurves on it).
  for (const Vec3& p : d.stitch_mesh.vertices) EXPECT_NEAR(std::hypot(p.x(), p.y()), 40.0, 0.05);
}

TEST(DesignTube, SleeveIsKnittableAndItsRoundsFollowTheCircumference) {
  TubeDesignOptions o;
  o.params = {3.5, 2.8};
  o.short_rows = false;  // plain rounds, one stitch height apart on average
  const SleeveShape s;
  const TubeDesign d = design_tube(sleeve(s, 4.0), o);
  EXPECT_TRUE(d.mesh_check.ok()) << d.mesh_check.text();
  EXPECT_TRUE(d.map_check.ok()) << d.map_check.text();
  ASSERT_TRUE(d.map.tubular());
  // Rounds one stitch height apart along the axis's 262 mm.
  const double axis = s.bend_radius * s.bend_deg * std::numbers::pi / 180.0;
  EXPECT_NEAR(d.map.rows, axis / 2.8, 1.0);
  // Round r's stitches: its circumference (radius linear along the axis) over the width, +-1; the
  // rim rows take their inner round's count.
  for (int r = 1; r + 1 < d.map.rows; ++r) {
    const double t = (r + 0.5) / d.map.rows;
    const double circ = 2.0 * std::numbers::pi * (s.start_radius + (s.end_radius - s.start_radius) * t);
    EXPECT_NEAR(row_stitches(d.map, r), circ / 3.5, 1.6) << "row " << r;
  }
  EXPECT_GT(row_stitches(d.map, 0), row_stitches(d.map, d.map.rows - 1) + 30);  // 89 -> 54
  EXPECT_EQ(d.increases, 0);
  EXPECT_EQ(d.decreases, row_stitches(d.map, 0) - row_stitches(d.map, d.map.rows - 1));
  EXPECT_EQ(count_cells(d.map, CellType::Decrease), d.decreases);
}

TEST(DesignTube, BentSleeveGetsShortRowsByDefaultAndStaysKnittable) {
  TubeDesignOptions o;
  o.params = {3.5, 2.8};
  const TriMesh m = sleeve(SleeveShape{}, 5.0);
  const TubeDesign d = design_tube(m, o);
  EXPECT_TRUE(d.mesh_check.ok()) << d.mesh_check.text();
  EXPECT_TRUE(d.map_check.ok()) << d.map_check.text();
  EXPECT_GT(d.wedges, 10);
  EXPECT_EQ(d.map.rows, static_cast<int>(d.rounds.size()) - 1 + d.short_rows);
  EXPECT_GT(count_cells(d.map, CellType::ShortRowLeft), 0);
  EXPECT_LT(d.course_spacing.outside.max, 1.1);
  EXPECT_GT(d.course_spacing.inside.min, 0.9);
  o.short_rows = false;
  const TubeDesign plain = design_tube(m, o);
  EXPECT_EQ(plain.short_rows, 0);
  EXPECT_GT(plain.course_spacing.outside.min, 1.05);  // what the short rows fix
  EXPECT_LT(plain.course_spacing.inside.max, 0.92);
}

TEST(DesignTube, StraightTubeIsTheSameWithOrWithoutShortRows) {
  TubeDesignOptions o;
  o.params = {3.5, 2.8};
  const TriMesh m = open_tube(40.0, 100.0, 2.5);
  const TubeDesign a = design_tube(m, o);
  o.short_rows = false;
  const TubeDesign b = design_tube(m, o);
  EXPECT_EQ(a.short_rows, 0);
  EXPECT_EQ(a.map.cells, b.map.cells);
  EXPECT_EQ(a.map.seam, b.map.seam);
  EXPECT_EQ(a.stitch_mesh.vertices, b.stitch_mesh.vertices);
}

TEST(DesignTube, RefusesASurfaceWithoutOneOrTwoBoundaryLoops) {
  // A disk is a closed tube (closed_tube_test.cpp); a rectangle with a hole
  // cut twice (three loops) is refused.
  TubeDesignOptions o;
  o.surface_name = "flat disk";
  const TubeDesign d = design_tube(hemisphere(75.0, 5.0), o);
  EXPECT_TRUE(d.map.closed_end);
  TriMesh two = open_tube(40.0, 60.0, 5.0);
  TriMesh three = two;
  for (Vec3& p : three.vertices) p.x() += 200.0;
  const int n = two.num_vertices();
  for (const auto& f : three.faces) two.faces.push_back({f[0] + n, f[1] + n, f[2] + n});
  two.vertices.insert(two.vertices.end(), three.vertices.begin(), three.vertices.end());
  try {
    design_tube(two, o);
    FAIL() << "two pieces were accepted";
  } catch (const InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find("2 pieces"), std::string::npos) << e.what();
  }
}

TEST(DesignTube, NarrowingTubeStartsAtTheLongerRimWhicheverLoopComesFirst) {
  // The sleeve turned upside down (z -> -z, faces reversed to keep normals outward): still cast on
  // at the wide rim, shaped by decreases only.
  TriMesh m = sleeve(SleeveShape{}, 5.0);
  for (Vec3& p : m.vertices) p.z() = -p.z();
  for (auto& f : m.faces) std::swap(f[1], f[2]);
  TubeDesignOptions o;
  o.short_rows = false;
  const TubeDesign d = design_tube(m, o);
  EXPECT_TRUE(d.map_check.ok()) << d.map_check.text();
  EXPECT_GT(d.field.start_length, d.field.end_length);
  EXPECT_EQ(d.increases, 0);
  EXPECT_GT(d.decreases, 30);
}

// The divergence of the normalised gradient (seed §3.3.8) estimates the
// shaping: on a frustum from r 50 to 30 mm the round loses 2π 20 / sw
// stitches, and the estimate says so within 10 %; on a straight tube it is
// near 0 (no shaping). The sheet routes' direction J g^ (along the
// isocurves, circles here) is divergence-free on the frustum: it cannot
// see the taper.
TEST(DesignTube, DivergenceOfTheNormalisedGradientEstimatesTheDecreases) {
  TriMesh frustum = open_tube(40.0, 120.0, 3.0);
  for (Vec3& p : frustum.vertices) {
    const double r = 50.0 - 20.0 * p.z() / 120.0, s = r / std::hypot(p.x(), p.y());
    p.x() *= s;
    p.y() *= s;
  }
  TubeDesignOptions o;
  o.params = {3.5, 2.8};
  const TubeDesign d = design_tube(frustum, o);
  const double expected = 2.0 * std::numbers::pi * 20.0 / 3.5;  // 35.9 stitches
  EXPECT_NEAR(d.divergence.transfer_estimate(3.5), expected, 0.1 * expected);
  EXPECT_NEAR(d.increases + d.decreases, expected, 0.1 * expected);
  EXPECT_EQ(d.divergence.flat_faces, 0);
  DivergenceOptions across;  // the isocurve direction: circles do not spread
  EXPECT_LT(divergence_metric(frustum, d.field.value, across).transfer_estimate(3.5), 0.1 * expected);
  const TubeDesign straight = design_tube(open_tube(40.0, 120.0, 3.0), o);
  EXPECT_LT(straight.divergence.transfer_estimate(3.5), 0.05 * expected);
}

}  // namespace
}  // namespace knitforge
