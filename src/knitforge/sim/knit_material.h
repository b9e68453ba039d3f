#pragma once
/// \file knit_material.h
/// The homogenised knit material of the simulator (docs/sim.md): an
/// orthotropic membrane in each element's course/wale frame, with separate
/// tension curves along courses and wales, a low shear stiffness, a
/// course-wale coupling (Poisson effect), direction-dependent bending
/// rigidity, areal density, thickness and damping.
///
/// Units (the simulator's system: mm, kg, s; so forces are mN and energies
/// µJ = mN·mm): tensions and stiffnesses per unit width in N/m (= mN/mm, the
/// same number), bending rigidity in µN·m (= mN·mm), areal density in g/m²,
/// thickness in mm, friction dimensionless.
///
/// The strain measures are those of a tensile test: along a material
/// direction the engineering strain ε = λ - 1 of the course (wale) line
/// element, λ = |F a| for the unit rest direction a; shear is γ = f_c · f_w,
/// the dot product of the deformed course and wale line elements (the
/// cosine of their angle for unit stretch; Baraff and Witkin 1998, "Large
/// steps in cloth simulation"). Energy per rest area:
///
///   W = Φ_c(ε_c) + Φ_w(ε_w) + ν_cw k_w ε_c ε_w + Φ_s(γ),
///
/// where Φ_c' is the course TensionCurve (nominal tension in N/m against
/// ε, what a strip tensile test measures), Φ_w' the wale curve, k_w the wale
/// curve's initial slope and Φ_s' the shear curve (symmetric in γ). The
/// curves are piecewise linear (Wang, O'Brien and Ramamoorthi 2011, the
/// data-driven model the seed fits, ch. 4): a knit is soft at small strain
/// and stiffens sharply once the loops straighten.

#include <string>
#include <utility>
#include <vector>

namespace knitforge {

/// Nominal tension (N/m) against engineering strain along one material
/// direction, piecewise linear through (0, 0):
///  - for ε >= 0, slope segments[k].second (N/m per unit strain) from strain
///    segments[k].first on (segments[0].first must be 0, starts ascending);
///  - for ε < 0, slope `compression_n_per_m`.
/// All slopes > 0 (a convex energy). For the shear curve the argument is
/// |γ| and `compression_n_per_m` is not used.
struct TensionCurve {
  std::vector<std::pair<double, double>> segments{{0.0, 100.0}};
  double compression_n_per_m = 100.0;

  /// Initial tensile slope (N/m), segments[0].second.
  double initial_stiffness() const { return segments.empty() ? 0.0 : segments.front().second; }
};

/// Φ(ε), Φ'(ε) (tension, N/m) and Φ''(ε) of a tension curve at strain ε;
/// `symmetric` uses |ε| (shear).
struct CurveValue {
  double energy = 0.0;   ///< Φ(ε): energy per rest area, N/m = µJ/mm²
  double tension = 0.0;  ///< Φ'(ε), N/m
  double slope = 0.0;    ///< Φ''(ε), N/m
};
CurveValue evaluate_curve(const TensionCurve& curve, double strain, bool symmetric = false);

/// One knit material. The defaults are default_single_jersey() (cotton
/// single jersey; its `source` says where each value comes from, several
/// are estimates).
struct KnitMaterial {
  std::string name = "single-jersey";
  /// Tension along courses (the stitch frame's x).
  TensionCurve course{{{0.0, 60.0}, {0.3, 1500.0}}, 60.0};
  /// Tension along wales (the stitch frame's y).
  TensionCurve wale{{{0.0, 150.0}, {0.15, 2500.0}}, 150.0};
  /// Shear "tension" (N/m) against |γ|; stiffens where the loops jam.
  TensionCurve shear{{{0.0, 20.0}, {0.5, 200.0}}, 20.0};
  /// Lateral contraction coupling ν_cw: a course stretch ε gives a wale strain
  /// -ν_cw ε in a free strip (small strain). Needs ν_cw² k_w < k_c.
  double poisson_course_wale = 0.3;
  double bending_course_un_m = 1.0;   ///< rigidity for curvature along courses (µN·m = mN·mm)
  double bending_wale_un_m = 2.0;     ///< rigidity for curvature along wales (µN·m)
  double areal_density_g_m2 = 170.0;  ///< mass per area (g/m²)
  double thickness_mm = 0.6;          ///< for stress in kPa = tension / thickness
  /// Mass-proportional (air) damping: a force -α m v, α in 1/s.
  double damping_per_s = 0.5;
  /// Where each value comes from (free text, shown in docs and reports).
  std::string source;
};

/// The default material: cotton single jersey, with values from published
/// Kawabata (KES-F) ranges for cotton single-jersey knits; the tension curve
/// shapes and the bending anisotropy are estimates (docs/sim.md gives the
/// sources and which values are estimates).
KnitMaterial default_single_jersey();

/// Checks a material: finite positive slopes, ascending segment starts from
/// 0, positive density/thickness/rigidities, damping >= 0, the coupling
/// convex (ν² k_w < k_c). \throw InvalidInput naming the material and field.
void validate_material(const KnitMaterial& m);

/// Areal density in the simulator's units (kg/mm²).
inline double areal_density_kg_mm2(const KnitMaterial& m) { return m.areal_density_g_m2 * 1e-9; }

}  // namespace knitforge
