#pragma once
/// \file friction_energy.h
/// Lagged, smoothed Coulomb friction between fabric and body (Li et al.
/// 2020, "Incremental Potential Contact", §5). At the lagged state (the
/// start of a time step) every contact pair freezes its normal force λ
/// (mN), its body point (face and barycentrics) and a tangent basis T (3 x 2,
/// orthonormal, perpendicular to the contact normal). During the step the
/// vertex's tangential slip relative to the body point is
///
///   u = Tᵀ ((x - x_n) - (c_{n+1} - c_n))   (mm; c the frozen body point),
///
/// and the friction potential is D = μ λ F(|u|) with the mollifier
///   F(y) = -y³/(3ε²) + y²/ε + ε/3 for y < ε,  F(y) = y otherwise,
/// ε = ε_v h (mm). Its gradient is the friction force μ λ F'(|u|) T û with
/// F' = 1 when sliding faster than ε_v: Coulomb's law; below ε_v the force
/// ramps smoothly to zero (static friction becomes creep slower than ε_v).
/// The Hessian μ λ T [F''(y) ûûᵀ + F'(y)/y (I - ûûᵀ)] Tᵀ is positive
/// semi-definite everywhere (no projection needed).
///
/// Every contact pair (one per vertex and body part, contact_candidates.h)
/// is a friction pair of its own, with its own λ, frozen point and body
/// motion: a vertex in the crook of an elbow is dragged by the forearm's
/// pair and held by the upper arm's, each by its own normal force.

#include <vector>

#include <Eigen/Core>

#include "knitforge/sim/contact_energy.h"

namespace knitforge {

struct FrictionPair {
  int vertex = -1;
  int face = -1;
  int part = 0;  ///< the body part of the frozen point
  Vec3 bary = Vec3::Zero();
  Eigen::Matrix<double, 3, 2> tangent = Eigen::Matrix<double, 3, 2>::Zero();
  double normal_force_mn = 0.0;  ///< λ
  Vec3 body_motion = Vec3::Zero();  ///< c_{n+1} - c_n over the step (mm)
};

/// Friction pairs of the contacts at the lagged positions x_lag (3n) against
/// the body at the start of the step (`body_start`), with the body motion of
/// each frozen point to `body_end` (same mesh, moved). Pairs with zero normal
/// force are dropped; μ = 0 gives none.
std::vector<FrictionPair> build_friction_pairs(const SimModel& model, const std::vector<ContactPair>& contacts,
                                               const KinematicBody& body_start, const KinematicBody& body_end,
                                               const Eigen::VectorXd& x_lag, const ContactParams& params);

/// Adds Σ μ λ F(|u|) over the pairs, u from x and the start positions x_n.
void add_friction_energy(const std::vector<FrictionPair>& pairs, const Eigen::VectorXd& x,
                         const Eigen::VectorXd& x_start, double h_s, const ContactParams& params, EnergyEval& out);

}  // namespace knitforge
