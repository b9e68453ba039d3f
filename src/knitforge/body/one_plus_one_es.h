#pragma once
/// \file one_plus_one_es.h
/// The (1+1) evolution strategy: the gradient-free optimiser the seed fits
/// its body template with (§5.2.1 and §5.3, "(1+1) evolutionary algorithm"
/// [44], about a minute a fit). One parent x; each generation draws one
/// child x + sigma * (scales ⊙ z), z ~ N(0, I), and keeps it when its cost
/// is not higher. The step sigma follows the 1/5th success rule in its
/// smooth form (Rechenberg; Auger & Hansen's tutorial form):
///   sigma <- sigma * exp((s - 1/5) / d),  s = 1 for a kept child, else 0,
///   d = sqrt(n + 1) (n = the number of free coordinates),
/// so sigma grows while more than a fifth of the children are kept and
/// shrinks otherwise; on a quadratic the cost then falls at a linear rate.
///
/// `scales` sets the size of a unit step per coordinate (e.g. mm for a
/// translation, rad for a rotation); a coordinate with scale 0 is fixed.
/// Deterministic for a given seed (std::mt19937_64 and this library's
/// normal distribution).

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include <Eigen/Core>

namespace knitforge {

struct OnePlusOneEsOptions {
  int max_evaluations = 4000;  ///< cost evaluations at most, the start's included (>= 1)
  double initial_step = 1.0;   ///< sigma at the start (> 0; steps are sigma * scales)
  /// Stop when sigma falls below this (> 0): steps smaller than
  /// min_step * scales no longer matter.
  double min_step = 1e-3;
  /// Stop when the last `stall_window` generations lowered the cost by less
  /// than this fraction of it (0 switches the test off).
  double relative_tolerance = 1e-7;
  int stall_window = 400;
  std::uint64_t seed = 1;
  /// Called after every generation with the evaluations so far and the
  /// parent's cost (e.g. for a progress line); may be empty.
  std::function<void(int evaluations, double cost)> on_generation;
};

struct OnePlusOneEsResult {
  Eigen::VectorXd x;        ///< the best point found (the last parent)
  double cost = 0.0;        ///< its cost
  double initial_cost = 0.0;
  int evaluations = 0;      ///< cost evaluations made, the start's included
  int successes = 0;        ///< children kept
  double final_step = 0.0;  ///< sigma at the end
  /// True when it stopped on min_step or on the stall test, false when the
  /// evaluation budget ran out first.
  bool converged = false;
  std::string stop_reason;  ///< "step below min_step", "stalled", "evaluation budget"
  /// The parent's cost after each generation that kept its child.
  std::vector<double> cost_history;
};

/// Minimises `cost` from `x0`. A child whose cost is not finite is
/// rejected (a failure for the step rule).
/// \throw InvalidInput when x0 and scales differ in size, a scale is
///        negative or not finite, every scale is 0, x0 or its cost is not
///        finite, or an option is out of range (naming it).
OnePlusOneEsResult minimise_one_plus_one_es(const std::function<double(const Eigen::VectorXd&)>& cost,
                                            const Eigen::VectorXd& x0, const Eigen::VectorXd& scales,
                                            const OnePlusOneEsOptions& options = {});

}  // namespace knitforge
