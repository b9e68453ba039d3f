// The optimiser of the short-column route (seed §3.3.5): Matern-5/2 kernel,
// Gaussian process, trust region, TuRBO on analytic objectives, and the
// feasible set eq. 3.8 with the projection QP eq. 3.9.
#include <cmath>
#include <numbers>

#include <gtest/gtest.h>

#include "knitforge/design/shortcolumn/feasible_set.h"
#include "knitforge/design/shortcolumn/gaussian_process.h"
#include "knitforge/design/shortcolumn/matern52_kernel.h"
#include "knitforge/design/shortcolumn/trust_region.h"
#include "knitforge/design/shortcolumn/turbo_optimize.h"
#include "knitforge/util/errors.h"

namespace knitforge {
namespace {

Eigen::MatrixXd random_points(int n, int d, uint64_t seed) {
  TurboRandom rng(seed);
  Eigen::MatrixXd X(n, d);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < d; ++j) X(i, j) = rng.uniform();
  return X;
}

TEST(Matern52Kernel, ValueAndLogGradientsMatchFiniteDifferences) {
  const Eigen::MatrixXd X = random_points(7, 3, 1);
  Matern52Params p;
  p.lengthscale = Eigen::Vector3d(0.3, 0.7, 1.4);
  p.outputscale = 2.5;
  const Eigen::MatrixXd K = matern52_matrix(X, X, p);
  EXPECT_NEAR(K(2, 2), 2.5, 1e-14);  // k(x, x) = s
  // Closed form at r = 1: s (1 + sqrt5 + 5/3) e^-sqrt5.
  Eigen::VectorXd a = Eigen::Vector3d(0, 0, 0), b = Eigen::Vector3d(0.3, 0, 0);
  EXPECT_NEAR(matern52(a, b, p), 2.5 * (1 + std::sqrt(5.0) + 5.0 / 3.0) * std::exp(-std::sqrt(5.0)), 1e-14);
  const auto G = matern52_log_gradients(X, p);
  ASSERT_EQ(G.size(), 4u);
  const double h = 1e-6;
  for (int j = 0; j < 4; ++j) {
    Matern52Params up = p, dn = p;
    if (j < 3) {
      up.lengthscale[j] *= std::exp(h);
      dn.lengthscale[j] *= std::exp(-h);
    } else {
      up.outputscale *= std::exp(h);
      dn.outputscale *= std::exp(-h);
    }
    const Eigen::MatrixXd fd = (matern52_matrix(X, X, up) - matern52_matrix(X, X, dn)) / (2 * h);
    EXPECT_LE((fd - G[j]).cwiseAbs().maxCoeff(), 1e-7) << "theta " << j;
  }
  p.lengthscale[1] = 0.0;
  EXPECT_THROW(matern52_matrix(X, X, p), InvalidInput);
}

TEST(GaussianProcess, LikelihoodGradientMatchesFiniteDifferences) {
  const Eigen::MatrixXd X = random_points(12, 2, 3);
  Eigen::VectorXd y(12);
  for (int i = 0; i < 12; ++i) y[i] = std::sin(6 * X(i, 0)) + X(i, 1) * X(i, 1);
  y = (y.array() - y.mean()).matrix();
  GpHyperparameters h;
  h.kernel.lengthscale = Eigen::Vector2d(0.4, 0.9);
  h.kernel.outputscale = 1.3;
  h.noise = 0.01;
  Eigen::VectorXd g;
  gp_log_likelihood(X, y, h, &g);
  ASSERT_EQ(g.size(), 4);
  const double eps = 1e-6;
  for (int j = 0; j < 4; ++j) {
    GpHyperparameters up = h, dn = h;
    auto bump = [&](GpHyperparameters& q, double f) {
      if (j < 2) q.kernel.lengthscale[j] *= f;
      else if (j == 2) q.kernel.outputscale *= f;
      else q.noise *= f;
    };
    bump(up, std::exp(eps));
    bump(dn, std::exp(-eps));
    const double fd = (gp_log_likelihood(X, y, up) - gp_log_likelihood(X, y, dn)) / (2 * eps);
    EXPECT_NEAR(g[j], fd, 1e-6 * (1 + std::abs(fd))) << "theta " << j;
  }
}

TEST(GaussianProcess, FitsASmoothFunctionAndHandlesDuplicateSamples) {
  Eigen::MatrixXd X = random_points(30, 2, 5);
  // Duplicate the first five points exactly (the projection does that).
  X.conservativeResize(35, 2);
  for (int i = 0; i < 5; ++i) X.row(30 + i) = X.row(i);
  auto f = [](double a, double b) { return 10 + 3 * std::sin(3 * a) * std::cos(2 * b); };
  Eigen::VectorXd y(35);
  for (int i = 0; i < 35; ++i) y[i] = f(X(i, 0), X(i, 1));
  const GaussianProcess gp = fit_gaussian_process(X, y);
  EXPECT_TRUE(std::isfinite(gp.log_likelihood));
  // Hyperparameters inside TuRBO's bounds.
  for (int i = 0; i < 2; ++i) {
    EXPECT_GE(gp.hyper.kernel.lengthscale[i], 0.005 - 1e-12);
    EXPECT_LE(gp.hyper.kernel.lengthscale[i], 2.0 + 1e-12);
  }
  EXPECT_GE(gp.hyper.noise, 5e-4 - 1e-15);
  const Eigen::MatrixXd T = random_points(50, 2, 9);
  const GpPrediction p = gp_predict(gp, T);
  double err = 0, var_max = 0;
  for (int i = 0; i < 50; ++i) {
    err += std::pow(p.mean[i] - f(T(i, 0), T(i, 1)), 2);
    var_max = std::max(var_max, p.variance[i]);
    EXPECT_GE(p.variance[i], 0.0);
  }
  EXPECT_LT(std::sqrt(err / 50), 0.25);  // RMS; the function spans 6 units
  // The fit improved the likelihood over the starting hyperparameters.
  GpHyperparameters def;
  def.kernel.lengthscale = Eigen::Vector2d(0.5, 0.5);
  EXPECT_GT(gp.log_likelihood, gp_log_likelihood(X, gp.y, def) + 1.0);
  // At a training point the posterior is nearly certain.
  const GpPrediction at = gp_predict(gp, X.topRows(1));
  EXPECT_LT(at.variance[0], 0.1 * var_max + 1e-9);
  // A posterior sample with z = 0 is the mean.
  const Eigen::VectorXd s0 = gp_posterior_sample(gp, T, Eigen::VectorXd::Zero(50));
  EXPECT_LE((s0 - p.mean).cwiseAbs().maxCoeff(), 1e-6);
  EXPECT_THROW(fit_gaussian_process(Eigen::MatrixXd(0, 2), Eigen::VectorXd(0)), InvalidInput);
}

TEST(TrustRegion, GrowsAfterSuccessesShrinksAfterFailuresAndRestarts) {
  TrustRegionOptions o;
  TrustRegionState s = make_trust_region(o);
  EXPECT_DOUBLE_EQ(s.length, 0.8);
  update_trust_region(s, 10.0, 4, o);  // first value sets best
  for (int i = 0; i < 3; ++i) update_trust_region(s, 9.0 - i, 4, o);
  EXPECT_DOUBLE_EQ(s.length, 1.6);  // 3 successes double it (capped at 1.6)
  EXPECT_DOUBLE_EQ(s.best, 7.0);
  int shrinks = 0;
  while (!s.restart) {
    update_trust_region(s, 7.0, 4, o);  // no improvement: failure
    if (s.failures == 0) ++shrinks;
  }
  EXPECT_EQ(shrinks, 8);  // 1.6 -> 0.8 ... -> 0.00625 < 0.5^7
  EXPECT_EQ(failure_tolerance(o, 4), 4);
  EXPECT_EQ(failure_tolerance(o, 9), 9);
  Eigen::VectorXd lo, hi;
  TrustRegionState t = make_trust_region(o);
  trust_region_box(t, Eigen::Vector2d(0.5, 0.95), Eigen::Vector2d(0.1, 0.4), lo, hi);
  // Weights 0.5 and 2 (geometric mean 1): half-widths 0.2 and 0.8, clipped.
  EXPECT_NEAR(lo[0], 0.3, 1e-12);
  EXPECT_NEAR(hi[0], 0.7, 1e-12);
  EXPECT_NEAR(lo[1], 0.15, 1e-12);
  EXPECT_NEAR(hi[1], 1.0, 1e-12);
}

TEST(TurboOptimize, ConvergesOnATwoDimensionalQuadratic) {
  TurboProblem p;
  p.lower = Eigen::Vector2d(-2, -2);
  p.upper = Eigen::Vector2d(3, 3);
  p.objective = [](const Eigen::VectorXd& x) { return (x[0] - 0.7) * (x[0] - 0.7) + 3 * (x[1] + 1.1) * (x[1] + 1.1) + 2; };
  TurboOptions o;
  o.max_evaluations = 60;
  o.seed = 42;
  int calls = 0;
  o.on_evaluation = [&](const TurboEvaluation& e) { EXPECT_EQ(e.index, calls++); };
  const TurboResult r = turbo_optimize(p, o);
  EXPECT_EQ(calls, 60);
  EXPECT_EQ(static_cast<int>(r.history.size()), 60);
  EXPECT_NEAR(r.best_value, 2.0, 0.01);
  EXPECT_NEAR(r.best_x[0], 0.7, 0.1);
  EXPECT_NEAR(r.best_x[1], -1.1, 0.06);
  // The running best never increases, and the best is in the history.
  for (size_t k = 1; k < r.history.size(); ++k) EXPECT_LE(r.history[k].best, r.history[k - 1].best);
  EXPECT_EQ(r.history[static_cast<size_t>(r.best_index)].value, r.best_value);
  // Deterministic: the same seed gives the same run, another seed another.
  o.on_evaluation = nullptr;
  const TurboResult again = turbo_optimize(p, o);
  for (size_t k = 0; k < r.history.size(); ++k) EXPECT_EQ(again.history[k].value, r.history[k].value);
  o.seed = 43;
  o.max_evaluations = 5;  // the initial design (max(2 dim, 5) points) holds history[0]; no GP fits
  EXPECT_NE(turbo_optimize(p, o).history[0].value, r.history[0].value);
}

TEST(TurboOptimize, FindsTheGlobalMinimumOfBraninAndRestartsWhenTheRegionCollapses) {
  // Branin on [-5, 10] x [0, 15]: three global minima of value 0.397887.
  TurboProblem p;
  p.lower = Eigen::Vector2d(-5, 0);
  p.upper = Eigen::Vector2d(10, 15);
  p.objective = [](const Eigen::VectorXd& x) {
    const double pi = std::numbers::pi;
    const double a = x[1] - 5.1 / (4 * pi * pi) * x[0] * x[0] + 5 / pi * x[0] - 6;
    return a * a + 10 * (1 - 1 / (8 * pi)) * std::cos(x[0]) + 10;
  };
  TurboOptions o;
  o.max_evaluations = 120;
  o.seed = 7;
  const TurboResult r = turbo_optimize(p, o);
  EXPECT_LT(r.best_value, 0.397887 + 0.02);
  EXPECT_GE(r.regions, 2);  // a collapsed region restarted within the budget
}

TEST(TurboOptimize, ProjectsInfeasibleSuggestionsAndFeedsThePenalty) {
  // Minimise the distance to (0.9, 0.9) over the triangle x + y <= 1: the
  // unconstrained optimum is infeasible, the constrained one is (0.5, 0.5).
  LinearConstraints k;
  k.A = Eigen::MatrixXd(3, 2);
  k.A << 1, 0, 0, 1, -1, -1;
  k.c = Eigen::Vector3d(0, 0, -1);
  TurboProblem p;
  p.lower = Eigen::Vector2d(0, 0);
  p.upper = Eigen::Vector2d(1, 1);
  p.objective = [&](const Eigen::VectorXd& x) {
    EXPECT_TRUE(k.contains(x, 1e-9)) << "evaluated outside the feasible set";
    return (x - Eigen::Vector2d(0.9, 0.9)).squaredNorm();
  };
  p.project = [&](const Eigen::VectorXd& x) { return project_onto_constraints(k, x); };
  p.sample_feasible = [](const Eigen::VectorXd& u) {  // uniform on the triangle
    const double a = std::min(u[0], u[1]), b = std::max(u[0], u[1]);
    return Eigen::VectorXd(Eigen::Vector2d(a, b - a));
  };
  TurboOptions o;
  o.max_evaluations = 40;
  o.seed = 3;
  const TurboResult r = turbo_optimize(p, o);
  int projected = 0;
  for (const TurboEvaluation& e : r.history) {
    if (e.initial) {
      EXPECT_FALSE(e.projected);
    }
    if (!e.projected) continue;
    ++projected;
    EXPECT_NEAR(e.penalised, e.value + std::exp((e.evaluated - e.suggested).squaredNorm()), 1e-12);
    EXPECT_GT(e.penalised, e.value + 1.0 - 1e-12);
  }
  EXPECT_GT(projected, 0);
  EXPECT_NEAR(r.best_x[0], 0.5, 0.03);
  EXPECT_NEAR(r.best_x[1], 0.5, 0.03);
}

TEST(FeasibleSet, ProjectionIsTheNearestFeasiblePoint) {
  const LinearConstraints k = boundary_constraints();
  TurboRandom rng(11);
  for (int trial = 0; trial < 200; ++trial) {
    Eigen::Vector4d y;
    for (int i = 0; i < 4; ++i) y[i] = -0.5 + 2.5 * rng.uniform();
    const Eigen::VectorXd x = project_onto_constraints(k, y);
    ASSERT_TRUE(k.contains(x, 1e-10));
    // Idempotent, and no feasible point from a cloud of random ones is nearer.
    EXPECT_LE((project_onto_constraints(k, x) - x).norm(), 1e-10);
    const double dx = (x - y).norm();
    for (int s = 0; s < 300; ++s) {
      Eigen::Vector4d u;
      for (int i = 0; i < 4; ++i) u[i] = rng.uniform();
      const BoundaryVector b = boundary_from_unit(u);
      const Eigen::Vector4d z(b[0], b[1], b[2], b[3]);
      ASSERT_TRUE(k.contains(z, 1e-12));
      EXPECT_GE((z - y).norm(), dx - 1e-9);
    }
    // Optimality (KKT): moving from x along any feasible direction does not get closer.
    for (int s = 0; s < 20; ++s) {
      Eigen::Vector4d dir;
      for (int i = 0; i < 4; ++i) dir[i] = rng.normal();
      const Eigen::Vector4d x2 = x + 1e-4 * dir;
      if (k.contains(x2, 0.0)) {
        EXPECT_GE((x2 - y).norm(), dx - 1e-12);
      }
    }
  }
  // A feasible point is its own projection; eq. 3.8 itself is what is feasible.
  const Eigen::Vector4d f(0.1, 0.2, 0.5, 0.9);
  EXPECT_EQ(project_onto_constraints(k, f), Eigen::VectorXd(f));
  EXPECT_TRUE(is_feasible({0.1, 0.2, 0.5, 0.9}));
  // The symmetric variant: a + e <= min(g, 1 - g) - margin.
  const LinearConstraints s = symmetric_constraints(0.4);
  const Eigen::VectorXd q = project_onto_constraints(s, Eigen::Vector2d(0.5, 0.5));
  EXPECT_NEAR(q[0] + q[1], 0.4 - kFeasibleMargin, 1e-12);
  EXPECT_NEAR(q[0], q[1], 1e-12);
  const BoundaryVector b = symmetric_boundary(0.9, 0.4, q[0], q[1]);
  EXPECT_TRUE(is_feasible(b));
  EXPECT_NEAR(0.5 * (b[0] + b[1]), 0.9, 1e-12);
  EXPECT_THROW(symmetric_constraints(1.2), InvalidInput);
}

TEST(FeasibleSet, UnitCubeMapCoversTheFeasibleSetUniformly) {
  TurboRandom rng(5);
  // The fraction of samples with b1 - b0 > 1/2 is the volume fraction of the
  // simplex part with s0 > 1/2: (1/2)^3 = 1/8.
  int wide = 0;
  const int n = 20000;
  for (int i = 0; i < n; ++i) {
    Eigen::Vector4d u;
    for (int j = 0; j < 4; ++j) u[j] = rng.uniform();
    const BoundaryVector b = boundary_from_unit(u);
    ASSERT_TRUE(is_feasible(b));
    if (b[1] - b[0] > 0.5 * (1 - 2 * kFeasibleMargin)) ++wide;
  }
  EXPECT_NEAR(static_cast<double>(wide) / n, 0.125, 0.01);
  EXPECT_NEAR(boundary_distance({0.05, 0.1, 0.5, 0.6}, {0.95, 1.1, 1.5, 1.6}), 0.1, 1e-12);
}

}  // namespace
}  // namespace knitforge
