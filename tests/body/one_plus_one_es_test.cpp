#include "knitforge/body/one_plus_one_es.h"

#include <cmath>

#include <gtest/gtest.h>

#include "knitforge/util/errors.h"

namespace knitforge {
namespace {

double sphere(const Eigen::VectorXd& x) { return x.squaredNorm(); }

TEST(OnePlusOneEs, SphereConvergesAtALinearRate) {
  const int n = 10;
  const Eigen::VectorXd x0 = Eigen::VectorXd::Constant(n, 3.0);
  OnePlusOneEsOptions o;
  o.max_evaluations = 20000;
  o.min_step = 1e-6;
  const OnePlusOneEsResult r = minimise_one_plus_one_es(sphere, x0, Eigen::VectorXd::Ones(n), o);
  EXPECT_TRUE(r.converged) << r.stop_reason;
  EXPECT_EQ(r.stop_reason, "step below min_step");
  EXPECT_EQ(r.initial_cost, 90.0);
  EXPECT_LT(r.cost, 1e-9);
  EXPECT_EQ(r.cost, sphere(r.x));
  // The 1/5th rule keeps about a fifth of the children (between 0.1 and 0.3).
  const double rate = static_cast<double>(r.successes) / (r.evaluations - 1);
  EXPECT_GT(rate, 0.1);
  EXPECT_LT(rate, 0.3);
  // Linear convergence: about a factor 10 in cost per ~20 n evaluations on the
  // sphere; 1e10 here in far fewer evaluations than a random search needs.
  EXPECT_LT(r.evaluations, 5000);
  // Never worse: the kept costs fall.
  for (size_t i = 1; i < r.cost_history.size(); ++i) EXPECT_LE(r.cost_history[i], r.cost_history[i - 1]);
}

TEST(OnePlusOneEs, ScalesFixAndShapeTheSteps) {
  // An ill-scaled quadratic: with matching scales it is the sphere again;
  // a coordinate of scale 0 never moves.
  auto cost = [](const Eigen::VectorXd& x) { return std::pow(x[0] / 100.0, 2) + std::pow(x[1] * 100.0, 2) + x[2] * x[2]; };
  Eigen::VectorXd x0(3);
  x0 << 300.0, 0.03, 7.0;
  Eigen::VectorXd scales(3);
  scales << 100.0, 0.01, 0.0;
  OnePlusOneEsOptions o;
  o.max_evaluations = 5000;
  o.min_step = 1e-7;
  const OnePlusOneEsResult r = minimise_one_plus_one_es(cost, x0, scales, o);
  EXPECT_EQ(r.x[2], 7.0);
  EXPECT_NEAR(r.x[0], 0.0, 1e-3);
  EXPECT_NEAR(r.x[1], 0.0, 1e-7);
  EXPECT_NEAR(r.cost, 49.0, 1e-6);
}

TEST(OnePlusOneEs, BudgetStallAndDeterminism) {
  const Eigen::VectorXd x0 = Eigen::VectorXd::Constant(5, 1.0);
  OnePlusOneEsOptions o;
  o.max_evaluations = 50;
  const OnePlusOneEsResult a = minimise_one_plus_one_es(sphere, x0, Eigen::VectorXd::Ones(5), o);
  EXPECT_EQ(a.evaluations, 50);
  EXPECT_FALSE(a.converged);
  EXPECT_EQ(a.stop_reason, "evaluation budget");
  const OnePlusOneEsResult b = minimise_one_plus_one_es(sphere, x0, Eigen::VectorXd::Ones(5), o);
  EXPECT_EQ(a.x, b.x);
  o.seed = 2;
  const OnePlusOneEsResult c = minimise_one_plus_one_es(sphere, x0, Eigen::VectorXd::Ones(5), o);
  EXPECT_NE(a.x, c.x);
  // A flat cost: every child is kept, so the step grows; the stall test ends it.
  OnePlusOneEsOptions flat;
  flat.stall_window = 30;
  const OnePlusOneEsResult f =
      minimise_one_plus_one_es([](const Eigen::VectorXd&) { return 1.0; }, x0, Eigen::VectorXd::Ones(5), flat);
  EXPECT_EQ(f.stop_reason, "stalled");
  EXPECT_EQ(f.evaluations, 32);
  EXPECT_GT(f.final_step, 1.0);
}

TEST(OnePlusOneEs, NonFiniteChildrenAreRejected) {
  // Outside the unit ball the cost is NaN: the parent never leaves it.
  auto cost = [](const Eigen::VectorXd& x) {
    return x.norm() > 1.0 ? std::nan("") : (x - Eigen::VectorXd::Constant(x.size(), 0.5)).squaredNorm();
  };
  OnePlusOneEsOptions o;
  o.max_evaluations = 3000;
  const OnePlusOneEsResult r = minimise_one_plus_one_es(cost, Eigen::VectorXd::Zero(2), Eigen::VectorXd::Ones(2), o);
  EXPECT_LE(r.x.norm(), 1.0);
  EXPECT_LT(r.cost, 1e-6);
}

TEST(OnePlusOneEs, BadInputThrows) {
  const Eigen::VectorXd x0 = Eigen::VectorXd::Zero(2);
  EXPECT_THROW(minimise_one_plus_one_es(sphere, x0, Eigen::VectorXd::Ones(3)), InvalidInput);
  EXPECT_THROW(minimise_one_plus_one_es(sphere, x0, Eigen::VectorXd::Zero(2)), InvalidInput);
  EXPECT_THROW(minimise_one_plus_one_es(sphere, x0, Eigen::VectorXd::Constant(2, -1.0)), InvalidInput);
  OnePlusOneEsOptions o;
  o.max_evaluations = 0;
  EXPECT_THROW(minimise_one_plus_one_es(sphere, x0, Eigen::VectorXd::Ones(2), o), InvalidInput);
  o = {};
  o.initial_step = std::nan("");
  EXPECT_THROW(minimise_one_plus_one_es(sphere, x0, Eigen::VectorXd::Ones(2), o), InvalidInput);
  EXPECT_THROW(minimise_one_plus_one_es([](const Eigen::VectorXd&) { return INFINITY; }, x0, Eigen::VectorXd::Ones(2)),
               InvalidInput);
}

}  // namespace
}  // namespace knitforge
