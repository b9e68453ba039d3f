#include "knitforge/design/shortcolumn/trust_region.h"

#include <algorithm>
#include <cmath>

namespace knitforge {

TrustRegionState make_trust_region(const TrustRegionOptions& o) {
  TrustRegionState s;
  s.length = o.length_init;
  return s;
}

int failure_tolerance(const TrustRegionOptions& o, int dim) {
  return o.failure_tolerance > 0 ? o.failure_tolerance : std::max(4, dim);
}

void update_trust_region(TrustRegionState& s, double value, int dim, const TrustRegionOptions& o) {
  if (!s.has_best) {
    s.best = value;
    s.has_best = true;
    return;
  }
  if (value < s.best - 1e-3 * std::abs(s.best)) {
    ++s.successes;
    s.failures = 0;
  } else {
    s.successes = 0;
    ++s.failures;
  }
  if (s.successes >= o.success_tolerance) {
    s.length = std::min(2.0 * s.length, o.length_max);
    s.successes = 0;
  } else if (s.failures >= failure_tolerance(o, dim)) {
    s.length /= 2.0;
    s.failures = 0;
  }
  s.best = std::min(s.best, value);
  if (s.length < o.length_min) s.restart = true;
}

void trust_region_box(const TrustRegionState& s, const Eigen::VectorXd& center, const Eigen::VectorXd& ls,
                      Eigen::VectorXd& lower, Eigen::VectorXd& upper) {
  Eigen::ArrayXd w = ls.array() / ls.array().mean();
  w /= std::exp(w.log().mean());  // geometric mean 1
  lower = (center.array() - 0.5 * s.length * w).max(0.0).matrix();
  upper = (center.array() + 0.5 * s.length * w).min(1.0).matrix();
}

}  // namespace knitforge
