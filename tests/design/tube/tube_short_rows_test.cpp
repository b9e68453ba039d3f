// Short-row wedges inside a bent tube (design/tube/tube_short_rows.h).
#include <gtest/gtest.h>

#include "knitforge/convert/map_knittability.h"
#include "knitforge/convert/map_to_stitch_mesh.h"
#include "knitforge/convert/stitch_mesh_to_map.h"
#include "knitforge/core/knittability.h"
#include "knitforge/design/tube/tube_short_rows.h"
#include "knitforge/geometry/shapes.h"

namespace knitforge {
namespace {

bool same_map(const KnittingMap& a, const KnittingMap& b) {
  return a.rows == b.rows && a.cols == b.cols && a.cells == b.cells && a.direction == b.direction && a.seam == b.seam;
}

TEST(TubeShortRows, AStraightTubeNeedsNoWedge) {
  const TriMesh m = open_tube(40.0, 100.0, 2.5);
  TubeShortRowOptions o;
  o.params = {3.5, 2.8};
  const TubeShortRows sr = tube_short_rows(m, tube_field(m, "tube"), o);
  EXPECT_EQ(sr.wedges, 0);
  EXPECT_EQ(sr.short_rows, 0);
  EXPECT_NEAR(sr.spacing.ratio, 1.0, 0.02);
}

class TubeShortRowsSleeve : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    surface = new TriMesh(sleeve(SleeveShape{}, 5.0));
    TubeShortRowOptions o;
    o.params = {3.5, 2.8};
    result = new TubeShortRows(tube_short_rows(*surface, tube_field(*surface, "sleeve"), o));
  }
  static void TearDownTestSuite() {
    delete result;
    delete surface;
  }
  static TriMesh* surface;
  static TubeShortRows* result;
};
TriMesh* TubeShortRowsSleeve::surface = nullptr;
TubeShortRows* TubeShortRowsSleeve::result = nullptr;

TEST_F(TubeShortRowsSleeve, TheOutsideOfTheBendGetsWedgesTheInsideNone) {
  const TubeShortRows& sr = *result;
  EXPECT_GT(sr.wedges, 10);
  EXPECT_EQ(sr.short_rows, 2 * sr.wedges + 2 * (sr.turns - sr.wedges));
  // The rows at the inside line (left fold, column 0) are the full rounds only; at the outside
  // (the right fold, column N/2) about (ratio - 1) more.
  const KnittingMap& m = sr.plan;
  const int K = static_cast<int>(sr.rounds.size()) - 1;
  int at_fold = 0, at_outside = 0;
  for (int r = 0; r < m.rows; ++r) {
    at_fold += is_stitch(m.at(r, 0)) ? 1 : 0;
    at_outside += is_stitch(m.at(r, m.cols / 2)) ? 1 : 0;
  }
  EXPECT_EQ(at_fold, K);
  EXPECT_NEAR(at_outside, K * sr.spacing.ratio, 0.15 * K);
  for (int r = 0; r < m.rows; ++r) {
    if (m.closed(r)) continue;
    for (int c : {0, m.cols - 1}) EXPECT_FALSE(is_stitch(m.at(r, c))) << "short row " << r << " crosses the left fold";
  }
}

TEST_F(TubeShortRowsSleeve, MapAndStitchMeshRoundTripExactlyAndAreKnittable) {
  const TubeShortRows& sr = *result;
  const KnittingMap canon = canonical_cells(sr.plan);
  EXPECT_TRUE(same_map(stitch_mesh_to_map(sr.mesh), canon));
  EXPECT_TRUE(same_map(stitch_mesh_to_map(map_to_stitch_mesh_topology(canon, {3.5, 2.8})), canon));
  KnittabilityOptions closed;
  closed.closed_courses = true;
  const KnittabilityReport mesh_check = check_knittability(sr.mesh, closed);
  EXPECT_TRUE(mesh_check.ok()) << mesh_check.text();
  const KnittabilityReport map_check = check_knittability(canon, KnitParams{3.5, 2.8});
  EXPECT_TRUE(map_check.ok()) << map_check.text();
}

TEST_F(TubeShortRowsSleeve, CoursesLieAboutOneStitchHeightApartOnBothSides) {
  const CourseSpacing c = measure_course_spacing(result->mesh, result->spacing, 3.5, 2.8);
  ASSERT_GT(c.inside.stitches, 20);
  ASSERT_GT(c.outside.stitches, 20);
  EXPECT_GT(c.inside.min, 0.9);
  EXPECT_LT(c.inside.max, 1.1);
  EXPECT_GT(c.outside.min, 0.9);
  EXPECT_LT(c.outside.max, 1.1);
}

}  // namespace
}  // namespace knitforge
