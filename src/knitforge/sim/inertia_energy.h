#pragma once
/// \file inertia_energy.h
/// Inertia, damping and gravity terms of the incremental potential of
/// backward Euler (docs/sim.md). One time step of length h from (x_n, v_n)
/// minimises over x
///
///   E(x) = 1/(2h²) (x - x̃)ᵀ M (x - x̃) + 1/(2h) (x - x_n)ᵀ C (x - x_n) + Ψ(x),
///   x̃ = x_n + h v_n + h² g      (predict_positions()),
///
/// with the lumped mass M, the air damping C (SimModel::vertex_damping_kg_s)
/// and the elastic, contact and friction energies Ψ; its stationarity is
/// M (x - x_n - h v_n) / h² = M g - C v_{n+1} - ∇Ψ(x) with v_{n+1} =
/// (x - x_n) / h: backward Euler. The whole energy is divided by h² (the
/// other terms keep their units), so gradients are forces in mN in statics and
/// dynamics alike. For statics, gravity is the potential -Σ m_i g·x_i.

#include <Eigen/Core>

#include "knitforge/geometry/vec.h"
#include "knitforge/sim/energy_eval.h"
#include "knitforge/sim/sim_model.h"

namespace knitforge {

/// x̃ = x + h v + h² g (3n; mm, mm/s, s, mm/s²).
Eigen::VectorXd predict_positions(const Eigen::VectorXd& x, const Eigen::VectorXd& v, double h_s,
                                  const Vec3& gravity_mm_s2);

/// Adds 1/(2h²) Σ m_i |x_i - x̃_i|² + 1/(2h) Σ c_i |x_i - x_n,i|².
void add_inertia_energy(const SimModel& model, const Eigen::VectorXd& x, const Eigen::VectorXd& x_tilde,
                        const Eigen::VectorXd& x_previous, double h_s, EnergyEval& out);

/// Adds the gravity potential -Σ m_i g·x_i (statics).
void add_gravity_energy(const SimModel& model, const Eigen::VectorXd& x, const Vec3& gravity_mm_s2, EnergyEval& out);

}  // namespace knitforge
