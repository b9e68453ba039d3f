#pragma once
/// \file membrane_energy.h
/// Orthotropic knit membrane energy of the triangles (docs/sim.md).
///
/// Per element with rest area A and deformation gradient F = [f_c f_w]
/// (3 x 2: the deformed course and wale line elements per unit rest length,
/// F = [x1 - x0, x2 - x0] MembraneElement::rest_inverse), with
/// ε_c = |f_c| - 1, ε_w = |f_w| - 1, γ = f_c · f_w:
///
///   E = A [Φ_c(ε_c) + Φ_w(ε_w) + ν_cw k_w ε_c ε_w + Φ_s(γ)]
///
/// (knit_material.h). The gradient and Hessian are exact; the Hessian is
/// formed in F-space (6 x 6), optionally projected to positive
/// semi-definite there (psd_projection.h), and mapped to the 9 x 9 Hessian
/// of the corner positions by the constant map dF/dx, so the projected
/// Hessian is positive semi-definite too.
///
/// Energy µJ (mN·mm), gradient mN, Hessian mN/mm, positions mm.

#include <Eigen/Core>

#include "knitforge/geometry/vec.h"
#include "knitforge/sim/energy_eval.h"
#include "knitforge/sim/psd_projection.h"
#include "knitforge/sim/sim_model.h"

namespace knitforge {

/// Energy of one membrane element at corner positions x0, x1, x2 (mm); the
/// gradient and Hessian are filled when `what` asks for them, the Hessian
/// projected as `projection` says.
ElementEnergy<3> membrane_element_energy(const Vec3& x0, const Vec3& x1, const Vec3& x2,
                                         const MembraneElement& element, const KnitMaterial& material,
                                         Derivatives what = Derivatives::Hessian,
                                         PsdProjection projection = PsdProjection::Clamp);

/// Adds the membrane energy of every element of `model` at positions x (3n,
/// mm) into `out`.
void add_membrane_energy(const SimModel& model, const Eigen::VectorXd& x, PsdProjection projection,
                         EnergyEval& out);

/// Membrane stress of one element at positions x0, x1, x2.
struct MembraneStress {
  double course_n_per_m = 0.0;  ///< nominal course tension ∂W/∂ε_c (N/m of rest width)
  double wale_n_per_m = 0.0;    ///< nominal wale tension ∂W/∂ε_w
  double shear_n_per_m = 0.0;   ///< ∂W/∂γ
  double course_strain = 0.0;   ///< ε_c
  double wale_strain = 0.0;     ///< ε_w
  double shear_strain = 0.0;    ///< γ
  /// Principal values of the Cauchy (true) membrane stress σ = P Fᵀ / J,
  /// J = |f_c x f_w| (N/m of deformed width), largest first.
  double principal_max_n_per_m = 0.0;
  double principal_min_n_per_m = 0.0;
  /// principal_max / thickness: the largest principal Cauchy stress in kPa.
  double principal_max_kpa = 0.0;
};
MembraneStress membrane_stress(const Vec3& x0, const Vec3& x1, const Vec3& x2, const MembraneElement& element,
                               const KnitMaterial& material);

}  // namespace knitforge
