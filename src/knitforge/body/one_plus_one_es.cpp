#include "knitforge/body/one_plus_one_es.h"

#include <cmath>
#include <random>

#include <fmt/core.h>

#include "knitforge/util/errors.h"

namespace knitforge {

OnePlusOneEsResult minimise_one_plus_one_es(const std::function<double(const Eigen::VectorXd&)>& cost,
                                            const Eigen::VectorXd& x0, const Eigen::VectorXd& scales,
                                            const OnePlusOneEsOptions& o) {
  if (x0.size() != scales.size())
    throw InvalidInput(fmt::format("(1+1)-ES: {} start coordinates but {} scales", x0.size(), scales.size()));
  if (o.max_evaluations < 1)
    throw InvalidInput(fmt::format("(1+1)-ES: max_evaluations {} must be at least 1", o.max_evaluations));
  if (!(std::isfinite(o.initial_step) && o.initial_step > 0.0) || !(std::isfinite(o.min_step) && o.min_step > 0.0))
    throw InvalidInput(fmt::format("(1+1)-ES: initial_step {} and min_step {} must be positive", o.initial_step,
                                   o.min_step));
  if (!(o.relative_tolerance >= 0.0) || o.stall_window < 1)
    throw InvalidInput(fmt::format("(1+1)-ES: relative_tolerance {} must be >= 0 and stall_window {} >= 1",
                                   o.relative_tolerance, o.stall_window));
  int free = 0;
  for (Eigen::Index i = 0; i < scales.size(); ++i) {
    if (!(std::isfinite(scales[i]) && scales[i] >= 0.0))
      throw InvalidInput(fmt::format("(1+1)-ES: scale {} is {}; scales must be finite and >= 0", i, scales[i]));
    if (scales[i] > 0.0) ++free;
  }
  if (free == 0) throw InvalidInput("(1+1)-ES: every scale is 0: nothing to optimise");
  if (!x0.allFinite()) throw InvalidInput("(1+1)-ES: the start point is not finite");

  OnePlusOneEsResult r;
  r.x = x0;
  r.cost = cost(x0);
  r.evaluations = 1;
  if (!std::isfinite(r.cost)) throw InvalidInput("(1+1)-ES: the cost at the start point is not finite");
  r.initial_cost = r.cost;

  const double damping = std::sqrt(static_cast<double>(free) + 1.0);
  const double grow = std::exp(0.8 / damping), shrink = std::exp(-0.2 / damping);
  double sigma = o.initial_step;
  std::mt19937_64 rng(o.seed);
  std::normal_distribution<double> normal(0.0, 1.0);
  // The parent's cost at the end of each of the last stall_window generations.
  std::vector<double> window(static_cast<size_t>(o.stall_window), r.cost);
  long generation = 0;
  Eigen::VectorXd child(x0.size());
  r.stop_reason = "evaluation budget";
  while (r.evaluations < o.max_evaluations) {
    for (Eigen::Index i = 0; i < child.size(); ++i)
      child[i] = scales[i] > 0.0 ? r.x[i] + sigma * scales[i] * normal(rng) : r.x[i];
    const double c = cost(child);
    ++r.evaluations;
    if (std::isfinite(c) && c <= r.cost) {
      r.x = child;
      r.cost = c;
      ++r.successes;
      sigma *= grow;
      r.cost_history.push_back(c);
    } else {
      sigma *= shrink;
    }
    if (o.on_generation) o.on_generation(r.evaluations, r.cost);
    if (sigma < o.min_step) {
      r.converged = true;
      r.stop_reason = "step below min_step";
      break;
    }
    double& oldest = window[static_cast<size_t>(generation % o.stall_window)];
    if (o.relative_tolerance > 0.0 && generation >= o.stall_window &&
        oldest - r.cost <= o.relative_tolerance * std::abs(oldest)) {
      r.converged = true;
      r.stop_reason = "stalled";
      break;
    }
    oldest = r.cost;
    ++generation;
  }
  r.final_step = sigma;
  return r;
}

}  // namespace knitforge
