#pragma once
/// \file trust_region.h
/// The trust region of TuRBO [47] (Eriksson et al. 2019, "Scalable Global
/// Optimization via Local Bayesian Optimization"): a hyperrectangle in the
/// unit cube centred at the best point so far, with base side length L
/// stretched per dimension by the GP lengthscales, grown after
/// `success_tolerance` consecutive improvements and shrunk after
/// `failure_tolerance` consecutive failures; when L falls below length_min
/// the region is restarted.
///
/// Defaults are the reference TuRBO's (ENGINES-STYLE.md): L0 = 0.8,
/// L_min = 0.5^7, L_max = 1.6, success tolerance 3, failure tolerance
/// ceil(max(4, dim) / batch) with batch size 1. An improvement is a value
/// below best - 1e-3 |best| (TuRBO's threshold).

#include <Eigen/Core>

namespace knitforge {

/// Options of the trust region.
struct TrustRegionOptions {
  double length_init = 0.8;
  double length_min = 0.0078125;  ///< 0.5^7
  double length_max = 1.6;
  int success_tolerance = 3;
  /// Consecutive failures before shrinking; <= 0 = ceil(max(4, dim)).
  int failure_tolerance = 0;
};

/// State of one trust region.
struct TrustRegionState {
  double length = 0.8;
  int successes = 0;
  int failures = 0;
  double best = 0.0;      ///< best value seen in this region
  bool has_best = false;
  bool restart = false;   ///< length fell below length_min
};

/// A fresh state with length_init.
TrustRegionState make_trust_region(const TrustRegionOptions& options);

/// The failure tolerance for `dim` (options.failure_tolerance when > 0).
int failure_tolerance(const TrustRegionOptions& options, int dim);

/// Records the value of one new evaluation: success (value < best - 1e-3
/// |best|) or failure, resizing the region as TuRBO does; `best` becomes
/// min(best, value). Sets `restart` when the length drops below length_min.
void update_trust_region(TrustRegionState& state, double value, int dim, const TrustRegionOptions& options);

/// The region's box [lower, upper] in the unit cube around `center`:
/// half-width L/2 x w_i with w = lengthscale / (geometric mean of the
/// lengthscales), clipped to [0, 1].
void trust_region_box(const TrustRegionState& state, const Eigen::VectorXd& center,
                      const Eigen::VectorXd& lengthscale, Eigen::VectorXd& lower, Eigen::VectorXd& upper);

}  // namespace knitforge
