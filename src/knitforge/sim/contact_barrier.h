#pragma once
/// \file contact_barrier.h
/// The scalar contact barrier (Li et al. 2020, "Incremental Potential
/// Contact"), in terms of the squared distance s = d² and its activation
/// ŝ = d̂² (d̂ the contact distance, mm), normalised by r = s / ŝ:
///
///   b(r) = -(r - 1)² ln r    for 0 < r < 1,   0 for r >= 1,
///   b'(r) = -2 (r - 1) ln r - (r - 1)² / r,
///   b''(r) = -2 ln r - 4 (r - 1) / r + (r - 1)² / r².
///
/// b is C² at r = 1, decreasing and convex on (0, 1), and tends to +inf as
/// r -> 0: a fabric vertex whose steps are collision free (collision_free_step.h)
/// can never reach the body.

#include <cmath>
#include <limits>

namespace knitforge {

struct BarrierValue {
  double b = 0.0, db = 0.0, d2b = 0.0;  ///< b(r), b'(r), b''(r)
};

/// b, b', b'' at r = s / ŝ (+inf value for r <= 0).
inline BarrierValue contact_barrier(double r) {
  if (r >= 1.0) return {};
  if (!(r > 0.0)) return {std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity(), 0.0};
  const double lr = std::log(r), rm = r - 1.0;
  return {-rm * rm * lr, -2.0 * rm * lr - rm * rm / r, -2.0 * lr - 4.0 * rm / r + rm * rm / (r * r)};
}

}  // namespace knitforge
