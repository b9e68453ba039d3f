#include "knitforge/evaluate/scalar_colours.h"

#include <algorithm>
#include <cmath>

#include <fmt/core.h>

#include "knitforge/util/errors.h"

namespace knitforge {

namespace {

constexpr int kSamples = 9;
constexpr double kViridis[kSamples][3] = {
    {68, 1, 84},    {71, 44, 122},  {59, 81, 139},  {44, 113, 142}, {33, 145, 140},
    {40, 174, 128}, {94, 201, 98},  {170, 220, 50}, {253, 231, 37},
};

}  // namespace

Rgb8 viridis_colour(double v, double lo, double hi) {
  if (!std::isfinite(v) || !std::isfinite(lo) || !std::isfinite(hi) || lo > hi) {
    throw InvalidInput(fmt::format("colour map: value {} on range [{}, {}] (all finite, lo <= hi)", v, lo, hi));
  }
  const double u = hi > lo ? std::clamp((v - lo) / (hi - lo), 0.0, 1.0) : 0.0;
  const double pos = u * (kSamples - 1);
  const int i = std::min(static_cast<int>(pos), kSamples - 2);
  const double t = pos - i;
  Rgb8 c;
  for (int k = 0; k < 3; ++k) {
    c[k] = static_cast<uint8_t>(std::lround((1 - t) * kViridis[i][k] + t * kViridis[i + 1][k]));
  }
  return c;
}

std::vector<Rgb8> scalar_colours(std::span<const double> values, double lo, double hi) {
  std::vector<Rgb8> out(values.size());
  for (size_t i = 0; i < values.size(); ++i) out[i] = viridis_colour(values[i], lo, hi);
  return out;
}

std::vector<Rgb8> scalar_colours(std::span<const double> values) {
  double hi = 0;
  for (size_t i = 0; i < values.size(); ++i) {
    if (!(std::isfinite(values[i]) && values[i] >= 0)) {
      throw InvalidInput(fmt::format("colour map: value {} is {} (must be finite and >= 0)", i, values[i]));
    }
    hi = std::max(hi, values[i]);
  }
  return scalar_colours(values, 0.0, hi);
}

}  // namespace knitforge
