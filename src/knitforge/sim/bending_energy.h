#pragma once
/// \file bending_energy.h
/// Discrete-shell bending (Grinspun et al. 2003, "Discrete shells") on the
/// hinges of SimModel, with a flat rest state: per hinge with dihedral angle
/// θ (0 when the two triangles are coplanar)
///
///   E = k θ²,   k = ½ D_e |ē|² / (Ā_0 + Ā_1)
///
/// with the rest edge length |ē|, the rest areas Ā of the two triangles and
/// D_e = D_c (n·c)² + D_w (n·w)², n the in-plane normal of the edge and c, w
/// the course and wale directions (sim_model.h). On a strip of rectangles
/// split into triangles bent into a cylinder of curvature κ across its
/// edges this sums to exactly ½ D κ² per area (the plate energy).
///
/// θ = atan2((n_A x n_B)·ê, n_A·n_B) with n_A = e x (x2 - x0), n_B =
/// (x3 - x0) x e, e = x1 - x0. Gradient (exact, Bridson et al. 2003):
/// ∂θ/∂x2 = -n̂_A / h_A, ∂θ/∂x3 = -n̂_B / h_B (h = height of the opposite
/// vertex over the edge), ∂θ/∂x0 = -(1 - t_A) ∂θ/∂x2 - (1 - t_B) ∂θ/∂x3,
/// ∂θ/∂x1 = -t_A ∂θ/∂x2 - t_B ∂θ/∂x3 (t = the opposite vertex's position
/// along e, as a fraction). Hessian by `projection`:
///  - None: exact, 2k (∇θ ∇θᵀ + θ ∇²θ), with ∇²θ the Jacobian of the
///    gradient formula by forward-mode differentiation (Eigen's
///    AutoDiffScalar, 12 derivatives);
///  - Abs: the exact one with absolute eigenvalues;
///  - Clamp: the Gauss-Newton part 2k ∇θ ∇θᵀ, positive semi-definite by
///    construction and exact at θ = 0 (no eigen-decomposition: the cheap
///    choice for time steps, where inertia dominates).
/// The exact Hessian keeps Newton quadratic where bending dominates: the
/// free cup (knitforge predict) converges in 70 iterations to 6e-8 mN with
/// it, and is still at 0.8 mN after 100 with the Gauss-Newton part.
/// A hinge whose triangles are degenerate (height below 1e-9 of the edge)
/// contributes its value only.

#include <Eigen/Core>

#include "knitforge/geometry/vec.h"
#include "knitforge/sim/energy_eval.h"
#include "knitforge/sim/membrane_energy.h"
#include "knitforge/sim/sim_model.h"

namespace knitforge {

/// Signed dihedral angle θ of a hinge (radians, in (-π, π]).
double dihedral_angle(const Vec3& x0, const Vec3& x1, const Vec3& x2, const Vec3& x3);

/// Energy of one hinge (vertex order of BendingHinge::v).
ElementEnergy<4> hinge_element_energy(const Vec3& x0, const Vec3& x1, const Vec3& x2, const Vec3& x3,
                                      const BendingHinge& hinge, Derivatives what = Derivatives::Hessian,
                                      PsdProjection projection = PsdProjection::None);

/// Adds the bending energy of every hinge of `model` at positions x (3n, mm).
void add_bending_energy(const SimModel& model, const Eigen::VectorXd& x, EnergyEval& out,
                        PsdProjection projection = PsdProjection::Clamp);

}  // namespace knitforge
