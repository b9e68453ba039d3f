#pragma once
/// \file slim_flatten.h
/// Locally injective flattening: a 2D map of a triangle mesh in which no
/// triangle is flipped or degenerate, by minimising the symmetric Dirichlet
/// energy
///
///     E(u) = Σ_f a_f (||J_f||² + ||J_f⁻¹||²)     (= 4 Σ a_f for an isometry)
///
/// (J_f the Jacobian of the map of face f from its 3D triangle, a_f the 3D
/// area) with Scalable Locally Injective Maps (SLIM, Rabinovich, Poranne,
/// Panozzo and Sorkine-Hornung 2017): a local step computes, per face, the
/// closest rotation R_f and the weights W_f = U diag(w) Uᵀ of the SVD
/// J_f = U Σ Vᵀ (w_i² = (σ_i − σ_i⁻³) / (σ_i − 1), 4 at σ_i = 1), the global
/// step minimises the quadratic proxy Σ a_f ||W_f (J_f(u) − R_f)||² (one
/// sparse SPD system, CHOLMOD via SparseSolver), and the step towards its
/// minimiser is cut at the first parameter where any triangle would become
/// degenerate (the smallest positive root of each triangle's signed area
/// along the step, Smith and Schaefer 2015), then shortened until the energy
/// decreases. The energy is infinite at a degenerate triangle, so starting
/// from a map without flipped triangles every iterate has none: injectivity
/// is a property of the method, not a check after the fact.
///
/// Linear equality constraints (dart notches, seed §2.3.1: equal x for a
/// horizontal dart, equal y for a vertical one) are solved as one unknown per
/// group in the global step. The start need not satisfy them: the steps move
/// towards the constrained proxy minimiser, so the constraint residual shrinks
/// by the factor (1 − t) with each step length t, and is met exactly once a
/// full step is taken. When the residual stalls (the constraints cannot be
/// met without a fold), the result says so (constraints_met false).
///
/// Used by flatten_surface() where the ARAP flattening (arap_flatten.h) folds.
#include <functional>
#include <utility>
#include <vector>
#include "knitforge/geometry/tri_mesh.h"
#include "knitforge/geometry/vec.h"

namespace knitforge {

struct SlimFlattenOptions {
  /// Start positions, one per vertex (mm): no face may be flipped or
  /// degenerate in them (signed_uv_area() > 0 for every face).
  std::vector<Vec2> initial;
  int max_iterations = 300;
  /// Stop when the constraints hold and the relative energy change of an
  /// iteration is at most this (the energy is >= 1 and changes by ~1e-5 per
  /// iteration in the tail on the mannequin panel: 1e-5 stops after ~16).
  double tolerance = 1e-5;
  /// Pairs (a, b): u_a.x == u_b.x, and u_a.y == u_b.y (as arap_flatten()).
  std::vector<std::pair<int, int>> equal_x;
  std::vector<std::pair<int, int>> equal_y;
  /// Called after every iteration with its number (1, 2, ...): progress for
  /// long runs. May be empty.
  std::function<void(int)> on_iteration;
};

struct SlimFlattenResult {
  std::vector<Vec2> uv;  ///< 2D position per vertex (mm); unused vertices keep their start
  int iterations = 0;
  bool converged = false;  ///< tolerance reached (with the constraints met) before max_iterations
  /// E / (4 Σ a_f) of the start and of the result: 1 for an isometry, > 1 otherwise.
  double initial_energy = 0.0;
  double energy = 0.0;
  /// Largest |u_a.x − u_b.x| (|u_a.y − u_b.y|) over the constraint groups (mm).
  double constraint_residual = 0.0;
  /// The residual is at most 1e-9 x the pattern size.
  bool constraints_met = true;
  /// Faces with signed area <= 0 in the result (always empty: kept as the
  /// proof the callers test and report).
  std::vector<int> flipped_faces;
};

/// Minimises the symmetric Dirichlet energy from options.initial (see the
/// file comment).
/// \pre mesh has faces with vertex indices in range; its faces of zero 3D
///      area carry no energy (they only keep their orientation).
/// \throw InvalidInput when `initial` has the wrong size, a non-finite entry
///        or a face that is flipped or degenerate (naming it), a constraint
///        names a vertex out of range, max_iterations < 0 or tolerance < 0,
///        or the mesh has zero area; SolverError from the sparse solver.
SlimFlattenResult slim_flatten(const TriMesh& mesh, const SlimFlattenOptions& options);

}  // namespace knitforge
