#pragma once
/// \file scalar_stats.h
/// Summary statistics of a list of per-element values (per-stitch distortion,
/// per-vertex distance), for reports.

#include <span>

namespace knitforge {

struct ScalarStats {
  int count = 0;         ///< number of values
  double min = 0.0;
  double mean = 0.0;
  double rms = 0.0;      ///< sqrt(mean of squares)
  double max = 0.0;
  int argmax = -1;       ///< index of the (first) largest value, -1 when empty
  double p50 = 0.0;      ///< median
  double p90 = 0.0;
  double p95 = 0.0;
  double p99 = 0.0;
};

/// Percentile q in [0, 100] of the sorted values, by linear interpolation
/// between closest ranks (position q/100 * (n-1)); 0 when there are none.
double percentile_of_sorted(std::span<const double> sorted, double q);

/// Statistics of `values` (all zero and argmax -1 when empty).
/// \throw InvalidInput when a value is not finite (naming its index).
ScalarStats scalar_stats(std::span<const double> values);

}  // namespace knitforge
