#pragma once
/// \file turbo_optimize.h
/// Trust-region Bayesian optimisation, TuRBO-1 of Eriksson et al. 2019 [47]
/// (the optimiser of seed §3.3.5), written from the paper on Eigen:
///
///  1. an initial design of `initial_points` points (a Latin hypercube in
///     the unit cube, mapped into the feasible set by `sample_feasible` when
///     given: "we sample all points in the feasible space", L1469);
///  2. repeat: fit a GP (Matern-5/2 ARD, gaussian_process.h) to the data of
///     the current trust region; draw `candidates` uniform points in the
///     trust-region box around the best point (trust_region.h); take one
///     joint posterior sample over them (Thompson sampling) and evaluate its
///     minimiser;
///  3. if that point is infeasible, `project` gives the nearest feasible
///     point x' (eq. 3.9); the objective is evaluated there and both pairs
///     (x', f(x')) and (x, f(x') + exp(|x' - x|^2)) join the data (L1473-1476:
///     the penalty teaches the model that the infeasible region is worse);
///  4. the trust region grows or shrinks by successes and failures; when it
///     collapses (length < length_min) it restarts with a fresh initial
///     design and a fresh model (TuRBO-1), keeping the overall history.
///
/// Always minimises. All randomness comes from options.seed (a
/// splitmix64/xoshiro256** generator of our own, so the same seed gives the
/// same run on every platform). The budget counts objective evaluations.

#include <cstdint>
#include <functional>
#include <vector>

#include <Eigen/Core>

#include "knitforge/design/shortcolumn/gaussian_process.h"
#include "knitforge/design/shortcolumn/trust_region.h"

namespace knitforge {

/// The problem: a box, the objective (called at feasible points only), and
/// the optional feasibility hooks.
struct TurboProblem {
  Eigen::VectorXd lower, upper;  ///< the box (problem units), lower < upper
  std::function<double(const Eigen::VectorXd&)> objective;
  /// Nearest feasible point (problem units); empty = every box point is feasible.
  std::function<Eigen::VectorXd(const Eigen::VectorXd&)> project;
  /// Maps a point of the unit cube to a feasible point (problem units) for
  /// the initial designs; empty = the box itself.
  std::function<Eigen::VectorXd(const Eigen::VectorXd&)> sample_feasible;
};

/// One objective evaluation.
struct TurboEvaluation {
  int index = 0;           ///< 0-based
  int region = 0;          ///< trust region (restart) it belongs to
  bool initial = false;    ///< part of an initial design
  Eigen::VectorXd suggested;  ///< the point the optimiser chose (problem units)
  Eigen::VectorXd evaluated;  ///< where the objective was evaluated (feasible)
  bool projected = false;  ///< evaluated != suggested (eq. 3.9)
  double value = 0.0;      ///< objective at `evaluated`
  double penalised = 0.0;  ///< value + exp(|evaluated - suggested|^2), fed at `suggested` when projected
  double best = 0.0;       ///< best value so far, this one included
  double trust_length = 0.0;  ///< trust-region length when suggested (0 for initial points)
};

/// Options; the defaults are TuRBO's (ENGINES-STYLE.md).
struct TurboOptions {
  int max_evaluations = 100;
  int initial_points = 0;  ///< per trust region; <= 0: max(2 dim, 5)
  int candidates = 0;      ///< Thompson-sampling candidates; <= 0: min(100 dim, 5000)
  TrustRegionOptions trust_region;
  GpFitOptions gp;
  uint64_t seed = 0;
  /// Called after every evaluation (progress).
  std::function<void(const TurboEvaluation&)> on_evaluation;
};

/// Result of turbo_optimize().
struct TurboResult {
  std::vector<TurboEvaluation> history;
  Eigen::VectorXd best_x;   ///< the feasible point with the smallest value
  double best_value = 0.0;
  int best_index = -1;
  int regions = 0;          ///< trust regions started (1 + restarts)
};

/// Minimises problem.objective.
/// \throw InvalidInput for an empty or inverted box, a missing objective,
///        max_evaluations < 1, a non-finite objective value (naming the
///        point) or a projection/sample of the wrong size.
TurboResult turbo_optimize(const TurboProblem& problem, const TurboOptions& options);

/// The deterministic generator of turbo_optimize() (xoshiro256**, seeded by
/// splitmix64), exposed for tests and for samplers that must match it.
class TurboRandom {
 public:
  explicit TurboRandom(uint64_t seed);
  uint64_t next();
  double uniform();  ///< in [0, 1)
  double normal();   ///< standard normal (Box-Muller)

 private:
  uint64_t s_[4];
  bool has_spare_ = false;
  double spare_ = 0.0;
};

/// A Latin hypercube of n points in [0, 1]^dim (rows).
Eigen::MatrixXd latin_hypercube(int n, int dim, TurboRandom& rng);

}  // namespace knitforge
