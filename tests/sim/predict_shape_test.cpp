// The predicted shape (knitforge predict): a free piece relaxes to its
// stitches' rest size, and a sheet settles on a dome under gravity to a
// converged equilibrium outside it.

#include "knitforge/sim/predict_shape.h"

#include <cmath>

#include <gtest/gtest.h>

#include "knitforge/geometry/shapes.h"
#include "knitforge/util/errors.h"
#include "sim_test_meshes.h"

namespace knitforge {
namespace {

KnitParams stitch(double w, double h) {
  KnitParams p;
  p.stitch_width = w;
  p.stitch_height = h;
  return p;
}

TEST(PredictShape, FreeSheetAtRestStaysAndConvergesAtOnce) {
  const StitchMesh sheet = test::knit_sheet(6, 5, 3.5, 2.8);
  const PredictResult r = predict_shape(sheet, stitch(3.5, 2.8), nullptr);
  EXPECT_TRUE(r.solve.converged);
  EXPECT_EQ(r.solve.iterations, 0);
  for (int v = 0; v < sheet.num_vertices(); ++v) EXPECT_LT((r.predicted.vertices[v] - sheet.vertices[v]).norm(), 1e-12);
}

// Designed 20 % too small in both directions: the free piece grows back to
// the stitches' ideal size (3.5 x 2.8 mm), flat, and converges.
TEST(PredictShape, FreeSheetDesignedSmallGrowsToTheStitchSize) {
  const int cols = 8, rows = 6;
  const StitchMesh sheet = test::knit_sheet(cols, rows, 0.8 * 3.5, 0.8 * 2.8);
  const PredictResult r = predict_shape(sheet, stitch(3.5, 2.8), nullptr);
  ASSERT_TRUE(r.solve.converged) << r.solve.stop_reason << ", force " << r.solve.max_force_mn;
  EXPECT_LE(r.solve.max_force_mn, 1e-5);
  auto id = [&](int i, int j) { return j * (cols + 1) + i; };
  const Vec3 a = r.predicted.vertices[id(0, 0)];
  EXPECT_NEAR((r.predicted.vertices[id(cols, 0)] - a).norm(), cols * 3.5, 1e-4);
  EXPECT_NEAR((r.predicted.vertices[id(0, rows)] - a).norm(), rows * 2.8, 1e-4);
  for (double s : r.stitch_stress_kpa) EXPECT_LT(s, 1e-3);
}

TEST(PredictShape, FreeBodyConstraintsHoldSixCoordinates) {
  const StitchMesh sheet = test::knit_sheet(4, 3, 3.5, 2.8);
  const std::vector<char> held = free_body_constraints(test::flatten(sheet.vertices));
  int count = 0;
  for (char h : held) count += h;
  EXPECT_EQ(count, 6);
}

TEST(PredictShape, LiftPutsPointsOutsideTheBodyAtTheGap) {
  const KinematicBody dome(hemisphere(20.0, 2.0));
  Eigen::VectorXd x(6);
  x << 0, 0, 19.0, 3, 1, 18.5;  // inside the dome
  const double lift = lift_clear_of_body(dome, x, 0.3, 100.0);
  // Signed clearance of the lifted points: all at least the gap, and a lift
  // 1 % of the gap lower would leave one closer (the lift is the least one).
  auto min_clearance = [&](double l) {
    double m = INFINITY;
    for (int v = 0; v < 2; ++v) {
      const Vec3 p = Vec3(x.segment<3>(3 * v)) + Vec3(0, 0, l);
      const auto q = dome.closest_point_within(p, INFINITY);
      const double side = (p - q->where.point).dot(dome.face_normal(q->face));
      m = std::min(m, side > 0 ? std::sqrt(q->distance2) : -std::sqrt(q->distance2));
    }
    return m;
  };
  EXPECT_GE(min_clearance(lift), 0.3);
  EXPECT_LT(min_clearance(lift - 0.003), 0.3);
  EXPECT_GT(lift, 1.0);  // the pole is at z = 20, 1 mm above the first point
  EXPECT_THROW(lift_clear_of_body(dome, x, 0.3, 0.5), InvalidInput);
}

TEST(PredictShape, GravityNeedsASupport) {
  PredictOptions o;
  o.gravity = true;
  EXPECT_THROW(predict_shape(test::knit_sheet(2, 2, 3.5, 2.8), stitch(3.5, 2.8), nullptr, o), InvalidInput);
}

// A 16 x 16 sheet of 3 mm stitches (48 mm) centred on a dome of radius 30 mm
// under gravity: settles, converges, rests in contact and outside the dome.
TEST(PredictShape, SheetSettlesOnADomeAndConverges) {
  const KinematicBody dome(hemisphere(30.0, 3.0));
  const StitchMesh sheet = test::knit_sheet(16, 16, 3.0, 3.0);
  PredictOptions o;
  o.gravity = true;
  const PredictResult r = predict_shape(sheet, stitch(3.0, 3.0), &dome, o);
  EXPECT_TRUE(r.settled);
  ASSERT_TRUE(r.solve.converged) << r.solve.stop_reason << ", force " << r.solve.max_force_mn;
  EXPECT_GT(r.solve.contacts, 20);
  EXPECT_GT(r.solve.min_distance_mm, 0.0);
  double lowest = INFINITY;
  for (const Vec3& p : r.predicted.vertices) {
    const auto q = dome.closest_point_within(p, INFINITY);
    ASSERT_TRUE(q.has_value());
    EXPECT_GT((p - q->where.point).dot(dome.face_normal(q->face)), 0.0);
    lowest = std::min(lowest, p.z());
  }
  EXPECT_LT(lowest, 30.0 - 5.0);  // it drapes, not just touches the pole
}

}  // namespace
}  // namespace knitforge
