// The L-BFGS phase in the backward-Euler steps (StepOptions::quasi_newton,
// step_simulation.h): a step reaches the state Newton alone reaches (the
// incremental potential's minimiser, to the tolerance), with fewer
// factorisations; a sheet draped on a dome and pushed by a rising dome
// never gets inside it; reruns are bit-identical.

#include <cmath>

#include <gtest/gtest.h>

#include "knitforge/geometry/shapes.h"
#include "knitforge/sim/step_simulation.h"
#include "sim_test_meshes.h"

namespace knitforge {
namespace {

using test::at_rest;
using test::square_stitches;

StepOptions with_quasi_newton(StepOptions o, int iterations) {
  o.quasi_newton.max_iterations = iterations;
  return o;
}

// A 16 x 16 sheet 0.45 mm above a dome's pole, dropped under gravity.
struct DropScene {
  double radius = 30.0;
  KinematicBody body{hemisphere(30.0, 3.0)};
  SimModel model = build_sim_model(test::knit_sheet(16, 16, 3.0, 3.0), square_stitches(3.0));
  Eigen::VectorXd start() const {
    Eigen::VectorXd x0 = test::flatten(model.rest_positions);
    for (int v = 0; v < model.num_vertices(); ++v) x0.segment<3>(3 * v) += Vec3(-24.0, -24.0, radius + 0.45);
    return x0;
  }
};

void expect_outside(const KinematicBody& body, const Eigen::VectorXd& x, int step) {
  for (Eigen::Index v = 0; v < x.size() / 3; ++v) {
    const Vec3 p = x.segment<3>(3 * v);
    const auto q = body.closest_point_within(p, 1e9);
    ASSERT_TRUE(q.has_value());
    ASSERT_GT(q->distance2, 0.0) << "vertex " << v << " touches the body at step " << step;
    ASSERT_GT((p - q->where.point).dot(body.face_normal(q->face)), -1e-12)
        << "vertex " << v << " is inside the body at step " << step;
  }
}

// Step by step from the same states, the L-BFGS phase + Newton and Newton
// alone land on the same minimiser of each step's incremental potential
// (strictly convex near it: the inertia term M/h² dominates), in contact
// with friction; the phase needs fewer factorisations over the run.
TEST(StepQuasiNewton, ReachesNewtonsStateInContact) {
  DropScene s;
  SimWorkspace ws(s.model);
  StepOptions o;
  o.contact.friction = 0.3;
  o.newton.force_tolerance_mn = 1e-7;
  const StepOptions q = with_quasi_newton(o, 400);
  SimState st = at_rest(s.start());
  int factorizations_newton = 0, factorizations_quasi = 0, lbfgs = 0, contacts = 0;
  for (int k = 0; k < 12; ++k) {
    const StepResult a = step_simulation(ws, st, s.body, {}, {}, o);
    const StepResult b = step_simulation(ws, st, s.body, {}, {}, q);
    ASSERT_TRUE(a.converged && b.converged) << "step " << k;
    EXPECT_EQ(a.quasi_newton_iterations, 0);
    EXPECT_LE(b.max_force_mn, 1e-7);
    // Both within the force tolerance of the minimiser: 1e-7 mN against a
    // stiffness of at least m/h² ~ 0.1 mN/mm gives ~1e-6 mm.
    EXPECT_LT((a.state.positions_mm - b.state.positions_mm).lpNorm<Eigen::Infinity>(), 1e-5) << "step " << k;
    EXPECT_GT(b.min_distance_mm, 0.0);
    expect_outside(s.body, b.state.positions_mm, k);
    factorizations_newton += a.factorizations;
    factorizations_quasi += b.factorizations;
    lbfgs += b.quasi_newton_iterations;
    contacts = std::max(contacts, b.contacts);
    st = b.state;  // go on from the L-BFGS run's state
  }
  EXPECT_GT(contacts, 0);  // it did touch the dome
  EXPECT_GT(lbfgs, 0);
  EXPECT_LT(factorizations_quasi, factorizations_newton);
}

// 40 steps of the drape and 30 of a dome rising into a pinned sheet with
// the phase on: every step converges, no vertex ever gets inside.
TEST(StepQuasiNewton, DrapeAndRisingDomeNeverPenetrate) {
  {
    DropScene s;
    SimWorkspace ws(s.model);
    StepOptions o;
    o.contact.friction = 0.3;
    o.newton.force_tolerance_mn = 1e-6;
    o = with_quasi_newton(o, 400);
    SimState st = at_rest(s.start());
    double lowest = INFINITY;
    for (int k = 0; k < 40; ++k) {
      const StepResult r = step_simulation(ws, st, s.body, {}, {}, o);
      ASSERT_TRUE(r.converged) << "step " << k;
      st = r.state;
      ASSERT_GT(r.min_distance_mm, 0.0) << "step " << k;
      expect_outside(s.body, st.positions_mm, k);
      for (Eigen::Index v = 0; v < st.positions_mm.size() / 3; ++v)
        lowest = std::min(lowest, st.positions_mm[3 * v + 2]);
    }
    EXPECT_LT(lowest, s.radius - 8.0);  // it really draped
  }
  const int cols = 12;
  SimModel model = build_sim_model(test::knit_sheet(cols, cols, 3.0, 3.0), square_stitches(3.0));
  model.pinned = {0, cols, cols * (cols + 1), (cols + 1) * (cols + 1) - 1};
  SimWorkspace ws(model);
  StepOptions o;
  o.contact.friction = 0.3;
  o.newton.force_tolerance_mn = 1e-6;
  o = with_quasi_newton(o, 400);
  Eigen::VectorXd x0 = test::flatten(model.rest_positions);
  for (int v = 0; v < model.num_vertices(); ++v) x0.segment<3>(3 * v) -= Vec3(18.0, 18.0, 0.0);
  TriMesh dome_mesh = hemisphere(12.0, 2.0);
  for (Vec3& p : dome_mesh.vertices) p.z() -= 14.0;  // pole 2 mm below the sheet
  KinematicBody dome(dome_mesh);
  SimState st = at_rest(x0);
  double highest = -INFINITY;
  for (int k = 0; k < 30; ++k) {
    std::vector<Vec3> next = dome.mesh().vertices;
    for (Vec3& p : next) p += Vec3(0, 0, 0.5);
    const StepResult r = step_simulation(ws, st, dome, next, {}, o);
    dome.move_to(next);
    st = r.state;
    ASSERT_TRUE(r.converged) << "step " << k;
    ASSERT_GT(r.min_distance_mm, 0.0) << "step " << k;
    expect_outside(dome, st.positions_mm, k);
    for (Eigen::Index v = 0; v < st.positions_mm.size() / 3; ++v)
      highest = std::max(highest, st.positions_mm[3 * v + 2]);
  }
  EXPECT_GT(highest, 10.0);  // the dome pushed the sheet up
}

TEST(StepQuasiNewton, RerunsAreBitIdentical) {
  DropScene s;
  StepOptions o;
  o.contact.friction = 0.3;
  o.newton.force_tolerance_mn = 1e-6;
  o = with_quasi_newton(o, 400);
  auto run = [&] {
    SimWorkspace ws(s.model);
    SimState st = at_rest(s.start());
    int lbfgs = 0;
    for (int k = 0; k < 8; ++k) {
      const StepResult r = step_simulation(ws, st, s.body, {}, {}, o);
      st = r.state;
      lbfgs += r.quasi_newton_iterations;
    }
    return std::make_pair(st.positions_mm, lbfgs);
  };
  const auto a = run(), b = run();
  EXPECT_EQ(a.second, b.second);
  ASSERT_EQ(a.first.size(), b.first.size());
  for (Eigen::Index k = 0; k < a.first.size(); ++k) ASSERT_EQ(a.first[k], b.first[k]) << k;
}

}  // namespace
}  // namespace knitforge
