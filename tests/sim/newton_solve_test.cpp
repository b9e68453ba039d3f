// Newton's step growth (newton_solve.h) on a barrier-dominated problem where
// the Newton step is far too short: one vertex whose height z starts next to
// a logarithmic barrier, E = ½(x² + y²) - ln z + z (minimum at z = 1).
// Near the barrier the Newton step only doubles z (p = z - z²), so without
// growth Newton crawls out; with it the step is grown while the energy
// falls. The minimiser is the same, every trial stays within the
// collision-free limit, and the iterates are deterministic.
#include "knitforge/sim/newton_solve.h"

#include <cmath>
#include <limits>

#include <gtest/gtest.h>

#include "knitforge/util/errors.h"

namespace knitforge {
namespace {

// E = ½(x² + y²) - ln z + z + (wall > 0 ? -ln(wall - z) : 0); infinite
// outside the admissible interval.
struct BarrierProblem {
  double wall = 0.0;
  std::shared_ptr<const HessianPattern> pattern =
      std::make_shared<HessianPattern>(1, std::span<const std::array<int, 4>>{});
  EnergyEval operator()(const Eigen::VectorXd& q, Derivatives what) const {
    EnergyEval ev(1, what, what == Derivatives::Hessian ? pattern : nullptr);
    const double z = q[2];
    if (!(z > 0) || (wall > 0 && !(z < wall))) {
      ev.value = std::numeric_limits<double>::infinity();
      return ev;
    }
    ev.value = 0.5 * (q[0] * q[0] + q[1] * q[1]) - std::log(z) + z;
    double g = -1 / z + 1, h = 1 / (z * z);
    if (wall > 0) {
      ev.value -= std::log(wall - z);
      g += 1 / (wall - z);
      h += 1 / ((wall - z) * (wall - z));
    }
    if (ev.wants_gradient()) ev.add_gradient(0, Vec3(q[0], q[1], g));
    if (ev.wants_hessian()) ev.add_hessian_block(0, 0, Vec3(1, 1, h).asDiagonal().toDenseMatrix());
    return ev;
  }
};

// x and y are at their minimum: the problem is one-dimensional (a grown
// step would overshoot a component Newton's model gets right).
Eigen::VectorXd start(double z) { return Eigen::Vector3d(0.0, 0.0, z); }

NewtonResult solve(const BarrierProblem& problem, double growth, const MaxStep& max_step) {
  NewtonOptions o;
  o.max_iterations = 200;
  o.force_tolerance_mn = 1e-10;
  o.max_step_growth = growth;
  SparseSolver solver;
  return newton_solve(start(1e-6), {}, problem, max_step, o, solver);
}

const MaxStep kFree = [](const Eigen::VectorXd&, const Eigen::VectorXd&) { return 1.0; };

TEST(NewtonSolve, StepGrowthCutsTheIterationsOfAShortNewtonStep) {
  const BarrierProblem problem;
  const NewtonResult plain = solve(problem, 1.0, kFree);
  const NewtonResult grown = solve(problem, 64.0, kFree);
  ASSERT_TRUE(plain.converged) << plain.stop_reason;
  ASSERT_TRUE(grown.converged) << grown.stop_reason;
  // The same minimiser.
  EXPECT_NEAR(plain.x[2], 1.0, 1e-9);
  EXPECT_NEAR(grown.x[2], 1.0, 1e-9);
  // Without growth z only doubles per iteration: about log2(1e6) = 20 of
  // them to get out of the barrier; with it about log65(1e6) plus a few.
  EXPECT_GE(plain.iterations, 20);
  EXPECT_EQ(plain.grown_steps, 0);
  EXPECT_GT(grown.grown_steps, 0);
  EXPECT_LE(2 * grown.iterations, plain.iterations) << grown.iterations << " vs " << plain.iterations;
  // Every iteration lowered the energy.
  for (size_t k = 1; k < grown.energies.size(); ++k) EXPECT_LE(grown.energies[k], grown.energies[k - 1]);
}

TEST(NewtonSolve, GrownStepsStayWithinTheCollisionFreeLimit) {
  // A second barrier at z = 2 (minimum at 2 - √2), and a collision-free limit
  // that lets a move go at most halfway to it: no trial may pass that limit.
  BarrierProblem problem;
  problem.wall = 2.0;
  double limit = 0.0;  // the highest z the last max_step() call allowed
  bool beyond = false;
  const MaxStep half_way = [&](const Eigen::VectorXd& a, const Eigen::VectorXd& b) {
    const double dz = b[2] - a[2];
    const double t = dz > 0 ? std::min(1.0, 0.5 * (problem.wall - a[2]) / dz) : 1.0;
    limit = a[2] + t * std::max(dz, 0.0);
    return t;
  };
  const BarrierProblem watched = problem;
  const EvaluateEnergy evaluate = [&](const Eigen::VectorXd& q, Derivatives what) {
    if (what == Derivatives::Value && q[2] > limit + 1e-12) beyond = true;
    return watched(q, what);
  };
  NewtonOptions o;
  o.force_tolerance_mn = 1e-10;
  SparseSolver solver;
  const NewtonResult r = newton_solve(start(1e-6), {}, evaluate, half_way, o, solver);
  ASSERT_TRUE(r.converged) << r.stop_reason;
  EXPECT_NEAR(r.x[2], 2.0 - std::sqrt(2.0), 1e-9);
  EXPECT_GT(r.grown_steps, 0);
  EXPECT_FALSE(beyond) << "a trial point went past the collision-free limit";
}

TEST(NewtonSolve, StepGrowthIsDeterministic) {
  const BarrierProblem problem;
  const NewtonResult a = solve(problem, 64.0, kFree);
  const NewtonResult b = solve(problem, 64.0, kFree);
  EXPECT_EQ(a.iterations, b.iterations);
  EXPECT_EQ(a.energies, b.energies);  // bit for bit
  EXPECT_EQ(a.x, b.x);
}

TEST(NewtonSolve, RefusesAStepGrowthThatIsNotAPowerOfTwo) {
  const BarrierProblem problem;
  NewtonOptions o;
  SparseSolver solver;
  for (double g : {0.5, 3.0, 2048.0}) {
    o.max_step_growth = g;
    EXPECT_THROW(newton_solve(start(0.5), {}, problem, kFree, o, solver), InvalidInput) << g;
  }
}

}  // namespace
}  // namespace knitforge
