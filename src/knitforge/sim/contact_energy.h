#pragma once
/// \file contact_energy.h
/// The contact barrier summed over the contact pairs (docs/sim.md):
///
///   E = Σ_pairs K_i b(d_i² / d̂²),   K_i = P A_i d̂,
///
/// with b from contact_barrier.h, d_i the distance of vertex i to its
/// closest body point, A_i the vertex's rest area (mm²) and P the barrier
/// pressure (kPa = mN/mm²): at d = d̂/2 a vertex pushes on the body with
/// about 4.3 P A_i. d² is differentiated as a function of the vertex with
/// the body fixed: ∇ d² = 2 (x - c), ∇² d² = 2 n nᵀ in the face interior,
/// 2 (I - t tᵀ) on an edge (direction t), 2 I at a corner. The vertex
/// Hessian is projected to positive semi-definite (psd_projection.h).

#include <vector>

#include <Eigen/Core>

#include "knitforge/sim/contact_candidates.h"
#include "knitforge/sim/energy_eval.h"
#include "knitforge/sim/psd_projection.h"
#include "knitforge/sim/sim_model.h"

namespace knitforge {

/// Contact and friction parameters.
struct ContactParams {
  double distance_mm = 0.5;         ///< d̂: the barrier acts below this distance
  double barrier_pressure_kpa = 1.0;  ///< P (see the file comment)
  double friction = 0.5;            ///< Coulomb coefficient μ (0 = frictionless)
  /// ε_v: below this sliding speed friction is smoothed (static friction
  /// becomes a creep slower than ε_v), mm/s.
  double friction_velocity_mm_s = 1.0;
};

/// Value, gradient and projected Hessian of one pair's barrier with respect
/// to its vertex, and the normal force magnitude -∂E/∂d (mN).
struct PairBarrier {
  double value = 0.0;
  Vec3 gradient = Vec3::Zero();
  Mat3 hessian = Mat3::Zero();
  double normal_force_mn = 0.0;
};
PairBarrier pair_barrier(const Vec3& x, const ContactPair& pair, const KinematicBody& body, double weight_mm2,
                         const ContactParams& params, PsdProjection projection = PsdProjection::Clamp);

/// Adds the barrier of every pair (each pair's closest point recomputed at x
/// on the pair's face) into `out`.
void add_contact_energy(const SimModel& model, const std::vector<ContactPair>& pairs, const KinematicBody& body,
                        const Eigen::VectorXd& x, const ContactParams& params, EnergyEval& out);

}  // namespace knitforge
