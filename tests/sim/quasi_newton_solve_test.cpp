// The quasi-Newton phase (quasi_newton_solve.h): the L-BFGS two-loop
// recursion on exact quadratics, and the whole phase on a small strictly
// convex, non-quadratic problem against Newton (newton_solve.h).
#include "knitforge/sim/quasi_newton_solve.h"

#include <cmath>
#include <limits>

#include <Eigen/Dense>
#include <gtest/gtest.h>

#include "knitforge/util/errors.h"

namespace knitforge {
namespace {

// A symmetric positive definite n x n matrix with spread eigenvalues.
Eigen::MatrixXd spd_matrix(int n) {
  Eigen::MatrixXd m(n, n);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) m(i, j) = std::sin(1.0 + 3 * i + 7 * j);
  return m * m.transpose() + Eigen::MatrixXd::Identity(n, n);
}

const auto kIdentity = [](const Eigen::VectorXd& q) { return q; };

TEST(LbfgsDirection, WithoutPairsIsMinusTheInitialInverseHessianTimesTheGradient) {
  const Eigen::VectorXd g = Eigen::Vector3d(1.0, -2.0, 0.5);
  const Eigen::VectorXd d = lbfgs_direction(g, {}, {}, [](const Eigen::VectorXd& q) { return Eigen::VectorXd(2.0 * q); });
  EXPECT_TRUE(d.isApprox(-2.0 * g));
}

TEST(LbfgsDirection, SatisfiesTheSecantEquationOfTheNewestPair) {
  // BFGS: H_k y_{k-1} = s_{k-1}, whatever the older pairs and H_0.
  const int n = 6;
  const Eigen::MatrixXd a = spd_matrix(n);
  std::vector<Eigen::VectorXd> s, y;
  for (int k = 0; k < 4; ++k) {
    Eigen::VectorXd sk(n);
    for (int i = 0; i < n; ++i) sk[i] = std::cos(2.0 * k + i);
    s.push_back(sk);
    y.push_back(a * sk);
  }
  const Eigen::VectorXd d = lbfgs_direction(y.back(), s, y, kIdentity);
  EXPECT_LT((d + s.back()).norm(), 1e-10 * s.back().norm());
}

TEST(LbfgsDirection, WithExactLineSearchMinimisesAQuadraticInAtMostNSteps) {
  // On ½xᵀAx - bᵀx with exact line searches, BFGS with full memory is
  // conjugate directions: the minimiser after at most n steps.
  const int n = 8;
  const Eigen::MatrixXd a = spd_matrix(n);
  Eigen::VectorXd b(n);
  for (int i = 0; i < n; ++i) b[i] = 1.0 + i;
  Eigen::VectorXd x = Eigen::VectorXd::Zero(n);
  std::vector<Eigen::VectorXd> s, y;
  int steps = 0;
  for (; steps < n; ++steps) {
    const Eigen::VectorXd g = a * x - b;
    if (g.norm() <= 1e-10 * b.norm()) break;
    const Eigen::VectorXd p = lbfgs_direction(g, s, y, kIdentity);
    ASSERT_LT(g.dot(p), 0.0);
    const double alpha = -g.dot(p) / p.dot(a * p);
    s.push_back(alpha * p);
    y.push_back(a * s.back());
    x += s.back();
  }
  const Eigen::VectorXd exact = a.ldlt().solve(b);
  EXPECT_LT((x - exact).norm(), 1e-8 * exact.norm()) << steps << " steps";
  EXPECT_LT((a * x - b).norm(), 1e-8 * b.norm());
}

// A chain of n vertices: springs ½|x_a - x_b - d_ab|² between neighbours
// and quartic anchors ¼ w |x_v - t_v|⁴, vertex 0 fixed. Strictly convex on
// the free unknowns (the springs alone are positive definite there), not
// quadratic: one minimiser, which L-BFGS and Newton must both find.
struct ChainProblem {
  int n = 12;
  double w = 0.5;
  std::shared_ptr<const HessianPattern> pattern;
  std::vector<char> fixed;
  ChainProblem() {
    std::vector<std::array<int, 4>> stencils;
    for (int v = 0; v + 1 < n; ++v) stencils.push_back({v, v + 1, -1, -1});
    pattern = std::make_shared<HessianPattern>(n, stencils);
    fixed.assign(3 * n, 0);
    for (int k = 0; k < 3; ++k) fixed[k] = 1;
  }
  Vec3 rest(int v) const { return Vec3(1.0 + 0.1 * std::sin(v), 0.2 * std::cos(3.0 * v), 0.1 * v); }
  Vec3 target(int v) const { return Vec3(0.5 * v, std::sin(0.7 * v), 0.3 * std::cos(v)); }
  EnergyEval operator()(const Eigen::VectorXd& x, Derivatives what) const {
    EnergyEval ev(n, what, what == Derivatives::Hessian ? pattern : nullptr);
    for (int v = 0; v + 1 < n; ++v) {
      const Vec3 u = x.segment<3>(3 * (v + 1)) - x.segment<3>(3 * v) - rest(v);
      ev.value += 0.5 * u.squaredNorm();
      if (ev.wants_gradient()) {
        ev.add_gradient(v + 1, u);
        ev.add_gradient(v, -u);
      }
      if (ev.wants_hessian()) {
        const Mat3 i = Mat3::Identity();
        ev.add_hessian_block(v, v, i);
        ev.add_hessian_block(v + 1, v + 1, i);
        ev.add_hessian_block(v + 1, v, -i);
        ev.add_hessian_block(v, v + 1, -i);
      }
    }
    for (int v = 0; v < n; ++v) {
      const Vec3 u = x.segment<3>(3 * v) - target(v);
      const double r2 = u.squaredNorm();
      ev.value += 0.25 * w * r2 * r2;
      if (ev.wants_gradient()) ev.add_gradient(v, w * r2 * u);
      if (ev.wants_hessian()) ev.add_hessian_block(v, v, w * (r2 * Mat3::Identity() + 2.0 * u * u.transpose()));
    }
    return ev;
  }
  Eigen::VectorXd start() const {
    Eigen::VectorXd x = Eigen::VectorXd::Zero(3 * n);
    for (int v = 1; v < n; ++v) x.segment<3>(3 * v) = Vec3(0.1 * v, 0.0, 0.0);
    return x;
  }
};

const MaxStep kFree = [](const Eigen::VectorXd&, const Eigen::VectorXd&) { return 1.0; };

QuasiNewtonOptions lbfgs_options() {
  QuasiNewtonOptions o;
  o.max_iterations = 1000;
  o.force_tolerance_mn = 1e-7;  // well above the energy's round-off (Armijo compares energies)
  return o;
}

// After a failed trial the line search moves to the minimiser of the
// quadratic through E(0), E'(0) and E(alpha): exact for a quadratic energy,
// kept within [0.1, 0.5] alpha, halving without a finite trial or a minimum.
TEST(NextTrialStep, IsTheQuadraticsMinimiserWithinSafeguards) {
  const double e0 = 5.0, slope = -2.0;
  auto quadratic = [&](double c, double a) { return e0 + slope * a + c * a * a; };
  // E = 5 - 2a + 4a^2: minimum at a = 0.25, within [0.1, 0.5] of a trial at 1.
  EXPECT_NEAR(next_trial_step(1.0, e0, slope, quadratic(4.0, 1.0)), 0.25, 1e-15);
  // The same from a trial at 0.8 (minimum 0.25 within [0.08, 0.4]).
  EXPECT_NEAR(next_trial_step(0.8, e0, slope, quadratic(4.0, 0.8)), 0.25, 1e-15);
  // A very stiff quadratic (minimum 0.01) is held at 0.1 alpha; a shallow
  // one whose minimum lies beyond half the trial at 0.5 alpha.
  EXPECT_DOUBLE_EQ(next_trial_step(1.0, e0, slope, quadratic(100.0, 1.0)), 0.1);
  EXPECT_DOUBLE_EQ(next_trial_step(1.0, e0, slope, quadratic(1.5, 1.0)), 0.5);
  // Not finite, or no curvature: halve.
  EXPECT_DOUBLE_EQ(next_trial_step(0.6, e0, slope, std::numeric_limits<double>::infinity()), 0.3);
  EXPECT_DOUBLE_EQ(next_trial_step(0.6, e0, slope, std::nan("")), 0.3);
  EXPECT_DOUBLE_EQ(next_trial_step(0.6, e0, slope, quadratic(-1.0, 0.6)), 0.3);
}

TEST(QuasiNewtonSolve, ReachesNewtonsMinimumOfAConvexProblem) {
  const ChainProblem problem;
  SparseSolver solver;
  NewtonOptions no;
  no.force_tolerance_mn = 1e-10;
  const NewtonResult newton = newton_solve(problem.start(), problem.fixed, problem, kFree, no, solver);
  ASSERT_TRUE(newton.converged) << newton.stop_reason;
  // The matrix is the Hessian at the start (the problem is convex, so it
  // is its own projection), factored once: no refresh.
  QuasiNewtonOptions o = lbfgs_options();
  o.max_refreshes = 0;
  o.stall_window = 1000;
  const QuasiNewtonResult q = quasi_newton_solve(problem.start(), problem.fixed, problem, problem, kFree, o, solver);
  EXPECT_EQ(q.stop_reason, "small force");
  EXPECT_LE(q.max_force_mn, 1e-7);
  EXPECT_EQ(q.factorizations, 1);
  EXPECT_GT(q.iterations, 1);
  // Within what a force of 1e-7 allows (the smallest curvature is ~0.01).
  EXPECT_LT((q.x - newton.x).norm(), 1e-4) << (q.x - newton.x).norm();
  EXPECT_NEAR(q.energy, newton.energy, 1e-9);
  // The fixed vertex stayed; every iteration lowered the energy.
  EXPECT_EQ(q.x.head<3>(), problem.start().head<3>());
  ASSERT_EQ(static_cast<int>(q.energies.size()), q.iterations + 1);
  for (size_t k = 1; k < q.energies.size(); ++k) EXPECT_LT(q.energies[k], q.energies[k - 1]);
}

TEST(QuasiNewtonSolve, RefreshesRefactorWhenProgressStalls) {
  // stall_decrease 1: every window stalls, so A is refactored every
  // stall_window iterations until the limit; the minimum is the same.
  const ChainProblem problem;
  SparseSolver solver;
  QuasiNewtonOptions o = lbfgs_options();
  o.stall_window = 2;
  o.stall_decrease = 1.0;
  o.max_refreshes = 2;
  const QuasiNewtonResult q = quasi_newton_solve(problem.start(), problem.fixed, problem, problem, kFree, o, solver);
  EXPECT_EQ(q.factorizations, 1 + 2);
  EXPECT_EQ(q.stop_reason, "stalled");
  EXPECT_EQ(q.iterations, 3 * 2);
  QuasiNewtonOptions many = lbfgs_options();
  many.stall_window = 2;
  many.stall_decrease = 1.0;
  many.max_refreshes = 1000;
  const QuasiNewtonResult r = quasi_newton_solve(problem.start(), problem.fixed, problem, problem, kFree, many, solver);
  EXPECT_EQ(r.stop_reason, "small force");
  const QuasiNewtonResult once = quasi_newton_solve(problem.start(), problem.fixed, problem, problem, kFree,
                                                    lbfgs_options(), solver);
  EXPECT_LT((r.x - once.x).norm(), 1e-4);
}

TEST(QuasiNewtonSolve, StopsAtTheIterationLimitWithoutClaimingAnything) {
  const ChainProblem problem;
  SparseSolver solver;
  QuasiNewtonOptions o = lbfgs_options();
  o.max_iterations = 2;
  const QuasiNewtonResult q = quasi_newton_solve(problem.start(), problem.fixed, problem, problem, kFree, o, solver);
  EXPECT_EQ(q.iterations, 2);
  EXPECT_EQ(q.stop_reason, "iteration limit");
  EXPECT_GT(q.max_force_mn, 1e-3);
  // Off: x0 back, nothing evaluated.
  o.max_iterations = 0;
  const QuasiNewtonResult off = quasi_newton_solve(problem.start(), problem.fixed, problem, problem, kFree, o, solver);
  EXPECT_EQ(off.x, problem.start());
  EXPECT_EQ(off.evaluations, 0);
}

TEST(QuasiNewtonSolve, IsDeterministic) {
  const ChainProblem problem;
  SparseSolver s1, s2;
  const QuasiNewtonResult a = quasi_newton_solve(problem.start(), problem.fixed, problem, problem, kFree,
                                                 lbfgs_options(), s1);
  const QuasiNewtonResult b = quasi_newton_solve(problem.start(), problem.fixed, problem, problem, kFree,
                                                 lbfgs_options(), s2);
  EXPECT_EQ(a.energies, b.energies);  // bit for bit
  EXPECT_EQ(a.x, b.x);
}

TEST(QuasiNewtonSolve, KeepsStepsWithinTheCollisionFreeLimit) {
  // A wall: vertex 5's x may not pass 1.0 (it is pulled beyond); the
  // energy is infinite past it, and max_step lets a move go half way.
  const ChainProblem base;
  const EvaluateEnergy walled = [&](const Eigen::VectorXd& x, Derivatives what) {
    EnergyEval ev = base(x, what);
    if (x[15] >= 1.0) ev.value = std::numeric_limits<double>::infinity();
    return ev;
  };
  const MaxStep limit = [](const Eigen::VectorXd& a, const Eigen::VectorXd& b) {
    const double d = b[15] - a[15];
    return d > 0 ? std::min(1.0, 0.5 * (1.0 - a[15]) / d) : 1.0;
  };
  SparseSolver solver;
  QuasiNewtonOptions o = lbfgs_options();
  o.max_iterations = 50;
  const QuasiNewtonResult q = quasi_newton_solve(base.start(), base.fixed, walled, base, limit, o, solver);
  EXPECT_GT(q.iterations, 0);
  EXPECT_LT(q.x[15], 1.0);
  for (size_t k = 1; k < q.energies.size(); ++k) EXPECT_LT(q.energies[k], q.energies[k - 1]);
}

TEST(QuasiNewtonSolve, RefusesBadInput) {
  const ChainProblem problem;
  SparseSolver solver;
  QuasiNewtonOptions o = lbfgs_options();
  EXPECT_THROW(quasi_newton_solve(Eigen::VectorXd::Zero(5), problem.fixed, problem, problem, kFree, o, solver),
               InvalidInput);
  o.stall_window = 0;
  EXPECT_THROW(quasi_newton_solve(problem.start(), problem.fixed, problem, problem, kFree, o, solver), InvalidInput);
}

}  // namespace
}  // namespace knitforge
