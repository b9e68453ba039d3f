#pragma once
/// \file rigid_align.h
/// Best rigid motions: between corresponding point sets (weighted Kabsch,
/// seed §2.A.2 eq. 2.3-2.4) and of a point set onto a surface (ICP with
/// closest points on triangles).
///
/// A rigid motion here is a proper rotation (det R = +1, never a reflection)
/// and a translation; no scale.

#include <span>
#include <vector>

#include "knitforge/evaluate/surface_distance.h"
#include "knitforge/geometry/tri_mesh.h"
#include "knitforge/geometry/vec.h"

namespace knitforge {

/// x -> rotation * x + translation.
struct RigidTransform {
  Mat3 rotation = Mat3::Identity();
  Vec3 translation = Vec3::Zero();

  Vec3 apply(const Vec3& x) const { return rotation * x + translation; }
  /// this ∘ other: first `other`, then this.
  RigidTransform after(const RigidTransform& other) const {
    return {rotation * other.rotation, rotation * other.translation + translation};
  }
};

/// The rigid motion (R, t) minimising sum_i w_i |R from_i + t - to_i|^2 over
/// R in SO(3) (seed eq. 2.3): with the weighted centroids, S = sum w_i
/// (from_i - f̄)(to_i - t̄)^T = U Σ V^T, R = V diag(1, 1, det(V U^T)) U^T,
/// t = t̄ - R f̄ (eq. 2.4 with the reflection case fixed).
/// When the points do not determine the rotation (fewer than three
/// non-collinear points with positive weight) one of the minimisers is
/// returned, deterministically.
/// \param weights empty (all 1) or one weight >= 0 per point, not all zero.
/// \throw InvalidInput for empty or mismatched inputs, non-finite points or
///        weights, negative weights or zero total weight.
RigidTransform rigid_align(std::span<const Vec3> from, std::span<const Vec3> to,
                           std::span<const double> weights = {});

/// Options of align_to_surface().
struct IcpOptions {
  int max_iterations = 30;  ///< rounds (closest points, then a step) at most
  /// Stop when the RMS distance decreases by less than this fraction in two
  /// rounds in a row.
  double tolerance = 1e-5;
};

struct IcpResult {
  RigidTransform transform;  ///< maps the input points onto the surface
  double rms = 0.0;          ///< weighted RMS distance to the surface after `transform` (mm)
  double initial_rms = 0.0;  ///< the same for the initial transform (mm)
  int iterations = 0;        ///< rounds run
  bool converged = false;    ///< tolerance reached before max_iterations
};

/// ICP onto a surface: starting from `initial` (e.g. a correspondence fit
/// by rigid_align()), each round finds the closest surface point c_i of every
/// transformed point x_i and takes a step on f = 1/2 sum w_i |x_i - c_i|^2
/// over the six parameters of a rigid motion (a rotation about the start's
/// centroid and a translation): a quasi-Newton (BFGS) step whose matrix
/// starts as f's Hessian with the closest points kept on their features
/// (face, edge or corner: ClosestPoint::half_squared_distance_hessian(),
/// plus the rotation's second-order term) and learns from each step. When
/// it does not lower the true RMS distance, the Newton step with a fresh
/// Hessian (its eigenvalues replaced by their absolute values where it is
/// indefinite: a nearly flat shape over a flat target), then the Gauss-Newton (point-to-plane) step, then the
/// point-to-point step (rigid_align() of the points to their closest points,
/// which never increases it). A round is accepted only when the RMS
/// decreases, so the RMS never increases and the result is never worse than
/// `initial`. Point-to-plane steps alone converge slowly on a shape far from
/// its target (on a free hemisphere 0.87 a round, 30 rounds without
/// converging; with the Newton matrix 10). Stops (converged) when the relative
/// decrease is below `tolerance` in two rounds in a row or no step
/// decreases it; not converged after max_iterations rounds. Deterministic
/// (the closest points are searched on all hardware threads,
/// util/parallel_ranges.h, the sums taken in point order).
/// \param weights empty (all 1) or one weight >= 0 per point, not all zero.
/// \throw InvalidInput for no points, non-finite points, bad weights or
///        options; as SurfaceBvh for a bad surface.
IcpResult align_to_surface(std::span<const Vec3> points, const TriMesh& target,
                           const RigidTransform& initial = {}, const IcpOptions& options = {},
                           std::span<const double> weights = {});

/// align_to_surface() with a prebuilt tree of the target.
IcpResult align_to_surface(std::span<const Vec3> points, const SurfaceBvh& target,
                           const RigidTransform& initial = {}, const IcpOptions& options = {},
                           std::span<const double> weights = {});

}  // namespace knitforge
