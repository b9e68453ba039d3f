#include "knitforge/sim/knit_material.h"

#include <cmath>

#include <fmt/core.h>

#include "knitforge/util/errors.h"

namespace knitforge {

CurveValue evaluate_curve(const TensionCurve& curve, double strain, bool symmetric) {
  CurveValue out;
  const double sign = strain < 0 ? -1.0 : 1.0;
  const double e = symmetric ? std::abs(strain) : strain;
  if (e < 0) {
    const double k = curve.compression_n_per_m;
    return {0.5 * k * e * e, k * e, k};
  }
  // Integrate the piecewise-linear tension over [0, e].
  double tension = 0.0, energy = 0.0, slope = curve.segments.empty() ? 0.0 : curve.segments[0].second;
  for (size_t k = 0; k < curve.segments.size(); ++k) {
    const double start = curve.segments[k].first;
    const double end = k + 1 < curve.segments.size() ? curve.segments[k + 1].first : INFINITY;
    if (e <= start) break;
    const double d = std::min(e, end) - start;
    slope = curve.segments[k].second;
    energy += tension * d + 0.5 * slope * d * d;
    tension += slope * d;
  }
  out.energy = energy;
  out.tension = symmetric ? sign * tension : tension;
  out.slope = slope;
  return out;
}

KnitMaterial default_single_jersey() {
  KnitMaterial m;
  m.source =
      "cotton single jersey. Tension curves: piecewise-linear fits to the Kawabata KES-FB1 tensile range of cotton "
      "single jersey (extension EMT at 500 gf/cm = 490 N/m about 60 % along courses and 33 % along wales; the "
      "break points and initial slopes are estimates). Shear 20 N/m (KES-FB1 shear rigidity G about 0.3-1 gf/cm/deg "
      "= 17-56 N/m per radian for knits; estimate at the low end), stiffening at |gamma| = 0.5 (loop jamming, "
      "estimate). Poisson coupling 0.3 (estimate). Bending 1.0 / 2.0 uN m along courses / wales (KES-FB2 B about "
      "0.01-0.03 gf cm2/cm = 1-3 uN m; the anisotropy is an estimate). 170 g/m2 (typical T-shirt jersey "
      "140-200 g/m2), thickness 0.6 mm (KES-FB3 T0 0.5-0.8 mm), air damping 0.5 /s (estimate). Calibrate with a "
      "drape test as the seed did (ch. 4) before trusting absolute numbers.";
  return m;
}

namespace {

void check_positive(const KnitMaterial& m, const char* field, double v) {
  if (!(std::isfinite(v) && v > 0)) {
    throw InvalidInput(fmt::format("material '{}': {} is {}; it must be a positive number", m.name, field, v));
  }
}

void check_curve(const KnitMaterial& m, const char* which, const TensionCurve& c, bool shear) {
  if (c.segments.empty()) {
    throw InvalidInput(fmt::format("material '{}': the {} tension curve has no segment; give at least [[0, slope]]",
                                   m.name, which));
  }
  if (c.segments[0].first != 0.0) {
    throw InvalidInput(fmt::format("material '{}': the {} tension curve must start at strain 0 (starts at {})",
                                   m.name, which, c.segments[0].first));
  }
  for (size_t k = 0; k < c.segments.size(); ++k) {
    const auto& [start, slope] = c.segments[k];
    if (!std::isfinite(start) || (k > 0 && !(start > c.segments[k - 1].first))) {
      throw InvalidInput(fmt::format(
          "material '{}': the {} tension curve's segment {} starts at strain {}; starts must ascend", m.name,
          which, k, start));
    }
    if (!(std::isfinite(slope) && slope > 0)) {
      throw InvalidInput(fmt::format(
          "material '{}': the {} tension curve's segment {} has slope {} N/m; slopes must be positive", m.name,
          which, k, slope));
    }
  }
  if (!shear && !(std::isfinite(c.compression_n_per_m) && c.compression_n_per_m > 0)) {
    throw InvalidInput(fmt::format("material '{}': the {} compression slope is {} N/m; it must be positive", m.name,
                                   which, c.compression_n_per_m));
  }
}

}  // namespace

void validate_material(const KnitMaterial& m) {
  check_curve(m, "course", m.course, false);
  check_curve(m, "wale", m.wale, false);
  check_curve(m, "shear", m.shear, true);
  check_positive(m, "bending_course_un_m", m.bending_course_un_m);
  check_positive(m, "bending_wale_un_m", m.bending_wale_un_m);
  check_positive(m, "areal_density_g_m2", m.areal_density_g_m2);
  check_positive(m, "thickness_mm", m.thickness_mm);
  if (!(std::isfinite(m.damping_per_s) && m.damping_per_s >= 0)) {
    throw InvalidInput(fmt::format("material '{}': damping_per_s is {}; it must be >= 0", m.name, m.damping_per_s));
  }
  const double nu = m.poisson_course_wale;
  // The coupling must keep the energy convex at every point of the curves:
  // with the smallest slopes (the compression and initial slopes).
  double kc = m.course.compression_n_per_m, kw = m.wale.compression_n_per_m;
  for (const auto& s : m.course.segments) kc = std::min(kc, s.second);
  for (const auto& s : m.wale.segments) kw = std::min(kw, s.second);
  if (!std::isfinite(nu) || nu < 0 || nu * nu * m.wale.initial_stiffness() * m.wale.initial_stiffness() >= 0.95 * kc * kw) {
    throw InvalidInput(fmt::format(
        "material '{}': poisson_course_wale {} makes the membrane energy non-convex (needs 0 <= nu and "
        "(nu k_w)^2 < k_c k_w with the smallest slopes k_c = {} and k_w = {} N/m); lower it",
        m.name, nu, kc, kw));
  }
}

}  // namespace knitforge
