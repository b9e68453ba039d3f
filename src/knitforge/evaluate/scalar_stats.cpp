#include "knitforge/evaluate/scalar_stats.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include <fmt/core.h>

#include "knitforge/util/errors.h"

namespace knitforge {

double percentile_of_sorted(std::span<const double> sorted, double q) {
  if (sorted.empty()) return 0.0;
  const double pos = std::clamp(q, 0.0, 100.0) / 100.0 * static_cast<double>(sorted.size() - 1);
  const size_t i = static_cast<size_t>(std::floor(pos));
  if (i + 1 >= sorted.size()) return sorted.back();
  const double t = pos - static_cast<double>(i);
  return (1 - t) * sorted[i] + t * sorted[i + 1];
}

ScalarStats scalar_stats(std::span<const double> values) {
  ScalarStats s;
  if (values.empty()) return s;
  s.count = static_cast<int>(values.size());
  double sum = 0, sum2 = 0;
  s.min = s.max = values[0];
  s.argmax = 0;
  for (size_t i = 0; i < values.size(); ++i) {
    const double v = values[i];
    if (!std::isfinite(v)) throw InvalidInput(fmt::format("statistics: value {} is not finite", i));
    sum += v;
    sum2 += v * v;
    s.min = std::min(s.min, v);
    if (v > s.max) {
      s.max = v;
      s.argmax = static_cast<int>(i);
    }
  }
  s.mean = sum / s.count;
  s.rms = std::sqrt(sum2 / s.count);
  std::vector<double> sorted(values.begin(), values.end());
  std::sort(sorted.begin(), sorted.end());
  s.p50 = percentile_of_sorted(sorted, 50);
  s.p90 = percentile_of_sorted(sorted, 90);
  s.p95 = percentile_of_sorted(sorted, 95);
  s.p99 = percentile_of_sorted(sorted, 99);
  return s;
}

}  // namespace knitforge
