// Distance between the levels of a tube field per place round the tube (design/tube/tube_spacing.h).
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "knitforge/design/tube/tessellate_rounds.h"
#include "knitforge/design/tube/tube_spacing.h"
#include "knitforge/geometry/shapes.h"

namespace knitforge {
namespace {

TEST(TubeSpacing, StraightTubeIsEvenlySpacedRoundIt) {
  const TriMesh m = open_tube(40.0, 100.0, 2.5);
  const TubeSpacing s = tube_spacing(m, tube_field(m, "tube"), 64, 32);
  EXPECT_NEAR(s.ratio, 1.0, 0.01);
  for (const auto& a : s.along) EXPECT_NEAR(a.back(), 100.0, 0.5);
}

TEST(TubeSpacing, SleeveIsFurtherApartOnTheOutsideOfTheBend) {
  const SleeveShape shape;
  const TriMesh m = sleeve(shape, 5.0);
  const TubeSpacing s = tube_spacing(m, tube_field(m, "sleeve"), 128, 64);
  // Along the axis 262 mm; inside (R - r) theta, outside (R + r) theta with r from 50 to 30.
  const double theta = shape.bend_deg * std::numbers::pi / 180.0;
  EXPECT_NEAR(s.along[static_cast<size_t>(s.inside_fraction)].back(), (shape.bend_radius - 40.0) * theta, 4.0);
  EXPECT_NEAR(s.along[static_cast<size_t>(s.outside_fraction)].back(), (shape.bend_radius + 40.0) * theta, 4.0);
  EXPECT_NEAR(s.ratio, 340.0 / 260.0, 0.03);
  // The two lines lie on the mirror plane y = 0, on opposite sides (x larger inside the bend).
  const Vec3 in = s.line(s.inside_fraction)[0], out = s.line(s.outside_fraction)[0];
  EXPECT_NEAR(in.y(), 0.0, 2.0);
  EXPECT_NEAR(out.y(), 0.0, 2.0);
  EXPECT_GT(in.x(), out.x() + 90.0);
}

TEST(TubeSpacing, PlainRoundsOfABentTubeMeasureShortInsideAndTallOutside) {
  const TriMesh m = sleeve(SleeveShape{}, 5.0);
  const TubeField f = tube_field(m, "sleeve");
  const TubeSpacing s = tube_spacing(m, f, 128, 64);
  const RoundsTessellation t = tessellate_rounds(tube_round_curves(m, f, round_levels(m, f, 2.8).levels), {3.5, 2.8});
  const CourseSpacing c = measure_course_spacing(t.mesh, s, 3.5, 2.8);
  EXPECT_LT(c.inside.max, 0.92);
  EXPECT_GT(c.outside.min, 1.05);
}

}  // namespace
}  // namespace knitforge
