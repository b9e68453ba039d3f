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

namespace knitforge {
namespace {

// A 12 x 10 sheet designed 20 % small in both directions and rolled onto a
// cylinder of radius 12 mm (courses round it): every stitch is compressed
// and bent, so the exact Hessian of the start is indefinite. The free
// equilibrium is the flat sheet at the stitch size (energy 0, unique up to
// rigid motion). The projected start (Clamp steps until the exact Hessian
// first factors, EquilibriumOptions::start_projection) reaches the same
// equilibrium as Levenberg-Marquardt shifts from the start, in fewer
// iterations (24 / 35 factorisations against 55 / 84 when measured), and
// reruns bit-identically.
StitchMesh rolled_small_sheet() {
  const int cols = 12, rows = 10;
  StitchMesh sheet = test::knit_sheet(cols, rows, 0.8 * 3.5, 0.8 * 2.8);
  const double radius = 12.0;
  for (Vec3& p : sheet.vertices) {
    const double a = p.x() / radius;
    p = Vec3(radius * std::sin(a), p.y(), radius * (1.0 - std::cos(a)));
  }
  return sheet;
}

// Newton alone (no quasi-Newton phase), from the given start projection.
PredictResult predict_rolled(PsdProjection start) {
  PredictOptions o;
  o.equilibrium.start_projection = start;
  o.equilibrium.quasi_newton.max_iterations = 0;
  return predict_shape(rolled_small_sheet(), stitch(3.5, 2.8), nullptr, o);
}

void expect_same_edge_lengths(const StitchMesh& a, const StitchMesh& b, double tolerance) {
  for (const Stitch& st : a.stitches) {
    for (int k = 0; k < st.corners(); ++k) {
      const int i = st.v[k], j = st.v[(k + 1) % st.corners()];
      EXPECT_NEAR((a.vertices[i] - a.vertices[j]).norm(), (b.vertices[i] - b.vertices[j]).norm(), tolerance);
    }
  }
}

TEST(PredictShape, ProjectedStartReachesTheSameEquilibriumInFewerIterations) {
  const PredictResult shifted = predict_rolled(PsdProjection::None);
  const PredictResult projected = predict_rolled(PsdProjection::Clamp);
  ASSERT_TRUE(shifted.solve.converged) << shifted.solve.stop_reason;
  ASSERT_TRUE(projected.solve.converged) << projected.solve.stop_reason;
  EXPECT_LE(projected.solve.max_force_mn, 1e-5);
  // The start is indefinite: the first step is the projected Hessian's;
  // without the projected start, no step is.
  ASSERT_FALSE(projected.solve.history.empty());
  EXPECT_TRUE(projected.solve.history.front().projected);
  for (const NewtonIterate& h : shifted.solve.history) EXPECT_FALSE(h.projected);
  // Once the exact Hessian has factored, no projected step follows.
  bool exact_seen = false;
  for (const NewtonIterate& h : projected.solve.history) {
    if (exact_seen) {
      EXPECT_FALSE(h.projected);
    }
    exact_seen = exact_seen || !h.projected;
  }
  EXPECT_EQ(static_cast<int>(projected.solve.history.size()), projected.solve.iterations);
  // The same equilibrium: flat at the stitch size, energy ~0, the same
  // edge lengths (the two differ by a rigid motion at most).
  EXPECT_LT(projected.solve.energy, 1e-6);
  EXPECT_LT(shifted.solve.energy, 1e-6);
  expect_same_edge_lengths(projected.predicted, shifted.predicted, 1e-5);
  EXPECT_LT(projected.solve.iterations, shifted.solve.iterations)
      << projected.solve.factorizations << " vs " << shifted.solve.factorizations << " factorisations";
  EXPECT_LT(projected.solve.factorizations, shifted.solve.factorizations);
}

TEST(PredictShape, ProjectedStartIsDeterministic) {
  const PredictResult a = predict_rolled(PsdProjection::Clamp);
  const PredictResult b = predict_rolled(PsdProjection::Clamp);
  ASSERT_EQ(a.solve.iterations, b.solve.iterations);
  for (size_t v = 0; v < a.predicted.vertices.size(); ++v) EXPECT_EQ(a.predicted.vertices[v], b.predicted.vertices[v]);
}

// The quasi-Newton phase (L-BFGS with the factored Clamp Hessian,
// PredictOptions' default) on the same rolled sheet: the same flat
// equilibrium as Newton alone, a strict minimum (the exact Hessian factors
// there), with fewer factorisations, and rerun bit-identically.
PredictResult predict_rolled_quasi_newton(int quasi_newton_iterations, int newton_iterations) {
  PredictOptions o;
  o.equilibrium.quasi_newton.max_iterations = quasi_newton_iterations;
  o.equilibrium.newton.max_iterations = newton_iterations;
  return predict_shape(rolled_small_sheet(), stitch(3.5, 2.8), nullptr, o);
}

TEST(PredictShape, QuasiNewtonPhaseReachesNewtonsEquilibriumWithFewerFactorisations) {
  ASSERT_GT(PredictOptions().equilibrium.quasi_newton.max_iterations, 0);  // on by default
  const PredictResult newton = predict_rolled(PsdProjection::Clamp);
  const PredictResult qn = predict_rolled_quasi_newton(10000, 500);
  ASSERT_TRUE(newton.solve.converged) << newton.solve.stop_reason;
  ASSERT_TRUE(qn.solve.converged) << qn.solve.stop_reason;
  EXPECT_LE(qn.solve.max_force_mn, 1e-5);
  EXPECT_TRUE(qn.solve.local_minimum);
  EXPECT_TRUE(newton.solve.local_minimum);
  EXPECT_GT(qn.solve.quasi_newton_iterations, 0);
  EXPECT_GE(qn.solve.quasi_newton_evaluations, qn.solve.quasi_newton_iterations);
  EXPECT_EQ(newton.solve.quasi_newton_iterations, 0);
  EXPECT_LT(qn.solve.energy, 1e-6);
  expect_same_edge_lengths(qn.predicted, newton.predicted, 1e-4);
  EXPECT_LT(qn.solve.factorizations, newton.solve.factorizations);
}

TEST(PredictShape, QuasiNewtonPhaseAloneDoesNotClaimConvergence) {
  // A few L-BFGS steps and no Newton iteration: far from the equilibrium,
  // and said so.
  const PredictResult r = predict_rolled_quasi_newton(3, 0);
  EXPECT_EQ(r.solve.quasi_newton_iterations, 3);
  EXPECT_EQ(r.solve.iterations, 0);
  EXPECT_FALSE(r.solve.converged);
  EXPECT_FALSE(r.solve.local_minimum);
  EXPECT_EQ(r.solve.stop_reason, "iteration limit");
  EXPECT_GT(r.solve.max_force_mn, 1e-5);
}

TEST(PredictShape, QuasiNewtonPhaseIsDeterministic) {
  const PredictResult a = predict_rolled_quasi_newton(10000, 500);
  const PredictResult b = predict_rolled_quasi_newton(10000, 500);
  ASSERT_EQ(a.solve.quasi_newton_evaluations, b.solve.quasi_newton_evaluations);
  ASSERT_EQ(a.solve.iterations, b.solve.iterations);
  for (size_t v = 0; v < a.predicted.vertices.size(); ++v) EXPECT_EQ(a.predicted.vertices[v], b.predicted.vertices[v]);
}

}  // namespace
}  // namespace knitforge
