// The short-column route end to end on the built-in hemisphere
// (design_short_columns.h): knittable with few transfers, deterministic.
#include "knitforge/design/shortcolumn/design_short_columns.h"

#include <cmath>
#include <numbers>

#include <gtest/gtest.h>

#include "design/shortcolumn/test_meshes.h"

#include "knitforge/design/shortcolumn/harmonic_field.h"
#include "knitforge/geometry/shapes.h"

namespace knitforge {
namespace {

ShortColumnOptions options() {
  ShortColumnOptions o;
  o.params = KnitParams{3.5, 2.8};
  o.evaluate = false;
  return o;
}

TEST(DesignShortColumns, HemisphereFromPointToPointIsKnittableWithFewTransfers) {
  const TriMesh surface = hemisphere();
  // R_s and R_e points roughly opposite on the rim (the optimum the
  // optimiser finds on this surface is of this kind).
  const HarmonicField h = harmonic_field(surface, {0.84, 0.84, 1.34, 1.34});
  const ShortColumnDesign d = design_short_columns(surface, h.value, options());
  EXPECT_TRUE(d.mesh_check.ok()) << d.mesh_check.text();
  EXPECT_TRUE(d.map_check.ok()) << d.map_check.text();
  EXPECT_LT(d.counts.transfers(), 40) << "few transfers: short rows take most of the shaping";
  EXPECT_EQ(d.counts.transfers(), d.counts.increases + d.counts.decreases);
  // Stitches match the area within 5 %.
  const double expected = d.surface_area / (3.5 * 2.8);
  EXPECT_NEAR(d.counts.stitches / expected, 1.0, 0.05);
  EXPECT_EQ(d.map.rows, d.courses.num_courses);
  // Same input, same design.
  const ShortColumnDesign again = design_short_columns(surface, h.value, options());
  EXPECT_EQ(again.counts.stitches, d.counts.stitches);
  EXPECT_EQ(again.counts.increases, d.counts.increases);
  EXPECT_EQ(again.map.cells.size(), d.map.cells.size());
}

TEST(DesignShortColumns, FrontsAlongTheRimAndTinyIsocurvePiecesStayKnittable) {
  // Four random b of the Fig. 3.16 experiment (example_06) whose designs
  // were not knittable: fronts reach the rim, the isocurve d = sw leaves the
  // surface and comes back; joined along the rim they are knittable, not
  // joined the knitting order misses stitches.
  const TriMesh surface = hemisphere();
  {
    const HarmonicField h = harmonic_field(surface, {0.329, 0.520, 0.654, 1.251});
    const ShortColumnDesign d = design_short_columns(surface, h.value, options());
    EXPECT_GT(d.wales.joined_arcs, 0);
    EXPECT_TRUE(d.mesh_check.ok()) << d.mesh_check.text();
    EXPECT_TRUE(d.map_check.ok()) << d.map_check.text();
    ShortColumnOptions apart = options();
    apart.wales.join_along_boundary = false;
    const ShortColumnDesign a = design_short_columns(surface, h.value, apart);
    EXPECT_FALSE(a.mesh_check.ok() && a.map_check.ok()) << "not joined: stitches the knitting order never reaches";
  }
  {
    // Here an isocurve piece of 0.06 mm around one front vertex took front
    // samples from the short wale beside it, which left them without stitches.
    const HarmonicField h = harmonic_field(surface, {0.650, 0.945, 1.281, 1.394});
    const ShortColumnDesign d = design_short_columns(surface, h.value, options());
    EXPECT_GT(d.wales.tiny_arcs, 0);
    EXPECT_TRUE(d.mesh_check.ok()) << d.mesh_check.text();
    EXPECT_TRUE(d.map_check.ok()) << d.map_check.text();
  }
  {
    // Here a front piece whose samples mostly lie on its region's front (a
    // few off it, beside a fork) was dropped by a mean-distance rule: the
    // region advanced with no samples, its strips unreachable (or, left
    // uncovered, a hole of 540 mm^2).
    const HarmonicField h = harmonic_field(surface, {0.562, 0.848, 0.855, 0.923});
    const ShortColumnDesign d = design_short_columns(surface, h.value, options());
    EXPECT_TRUE(d.mesh_check.ok()) << d.mesh_check.text();
    EXPECT_TRUE(d.map_check.ok()) << d.map_check.text();
    EXPECT_EQ(d.wales.sampleless_regions, 0);
    EXPECT_LT(d.wales.uncovered_area, 50.0);
  }
  {
    // Here an isocurve piece of 3.3 mm that could get no strip owned the
    // front samples beside it: the wale next to it (from a fork to the rim)
    // took only part of the front it faces, and 534 stitches were never
    // reached.
    const HarmonicField h = harmonic_field(surface, {0.411629, 0.581824, 0.609492, 0.836326});
    const ShortColumnDesign d = design_short_columns(surface, h.value, options());
    EXPECT_TRUE(d.mesh_check.ok()) << d.mesh_check.text();
    EXPECT_TRUE(d.map_check.ok()) << d.map_check.text();
  }
}

TEST(DesignShortColumns, SpreadingFieldIsKnitWithShortColumns) {
  // f = angle on a quarter annulus: the wales fan out, short columns start
  // (increases) and the design stays knittable.
  const TriMesh surface = test::polar_grid(20.0, 80.0, 0.0, std::numbers::pi / 2, 40, 60);
  std::vector<double> f;
  for (const Vec3& p : surface.vertices) f.push_back(std::atan2(p.y(), p.x()));
  const ShortColumnDesign d = design_short_columns(surface, f, options());
  EXPECT_TRUE(d.mesh_check.ok()) << d.mesh_check.text();
  EXPECT_TRUE(d.map_check.ok()) << d.map_check.text();
  EXPECT_GT(d.counts.increases, 5);
  EXPECT_GT(d.wales.fill_steps, 0);
}

TEST(DesignShortColumns, ParallelFieldNeedsNoTransfersInside) {
  // f = x on a rectangle: wales straight, only the last (narrow) strip may
  // carry shaping, and that becomes edge stitches.
  const TriMesh surface = rectangle(60.0, 40.0, 2.0);
  std::vector<double> f;
  for (const Vec3& p : surface.vertices) f.push_back(p.x());
  const ShortColumnDesign d = design_short_columns(surface, f, options());
  EXPECT_TRUE(d.knittable()) << d.mesh_check.text() << d.map_check.text();
  EXPECT_EQ(d.counts.transfers(), 0);
  EXPECT_EQ(d.counts.short_row_ends, 0);
}

}  // namespace
}  // namespace knitforge
