#pragma once
/// \file arap_flatten.h
/// As-rigid-as-possible flattening of a triangle mesh to the plane (seed
/// §2.3.1, eq. 2.1): minimise
///
///     E(u) = Σ_f  a_f Σ_{j ∈ f} || (u_j - ū_f) - R_f (x_j - x̄_f) ||²
///
/// over the 2D positions u, where x_j are the face's vertices in an
/// isometric 2D frame of the 3D triangle, ū_f, x̄_f the face centroids, R_f
/// the best-fitting 2D rotation and a_f the 3D face area (the seed's
/// weights; unlike cotangent weights they keep the system positive definite
/// on any mesh, e.g. noisy scans with obtuse triangles). Shape-Up style
/// local/global iterations: the local step computes every R_f in closed form
/// (the rotation part of the 2x2 cross-covariance), the global step solves
/// one sparse SPD system per coordinate, factored once (CHOLMOD via
/// SparseSolver). One vertex is pinned (translation); the rotation of the
/// result is the one the start shape has (rotations of the whole pattern are
/// a symmetry of E, the iterations keep the start's orientation).
///
/// Linear equality constraints for darts (seed §2.3.1: "we set two notches
/// of a dart as the same vertex"): groups of vertices whose x (or y)
/// coordinates must be equal are solved as one unknown, so they hold
/// exactly (to rounding) in every iteration.
///
/// Convergence: stop when the relative energy change between iterations is
/// below `tolerance` or after max_iterations.
#include <functional>
#include <utility>
#include <vector>
#include "knitforge/geometry/tri_mesh.h"
#include "knitforge/geometry/vec.h"

namespace knitforge {

struct ArapFlattenOptions {
  /// Start positions (one per vertex); empty: tutte_embedding().
  std::vector<Vec2> initial;
  int max_iterations = 300;
  /// Stop when |E_k - E_{k-1}| <= tolerance * E_{k-1} (or E_k <= 1e-14 · area²).
  double tolerance = 1e-6;
  /// Vertex whose start position is kept; -1: the vertex of the start shape
  /// closest to its centroid (used by a face).
  int pinned_vertex = -1;
  /// Pairs (a, b): u_a.x == u_b.x (a horizontal dart's notches, seed §2.2.2).
  std::vector<std::pair<int, int>> equal_x;
  /// Pairs (a, b): u_a.y == u_b.y (a vertical dart's notches).
  std::vector<std::pair<int, int>> equal_y;
  /// Called after every iteration with its number (1, 2, ...): progress for
  /// long runs. May be empty.
  std::function<void(int)> on_iteration;
  /// > 0: stop (not converged, ArapFlattenResult::stopped_folded) once this
  /// many iterations in a row have ended with a flipped face — for a caller
  /// that replaces a folded result by a fold-free solver's anyway
  /// (flatten_surface.h). 0: never; no flip test per iteration.
  int stop_after_folded_iterations = 0;
};

struct ArapFlattenResult {
  std::vector<Vec2> uv;         ///< 2D position per vertex (mm)
  int iterations = 0;           ///< local/global iterations done
  bool converged = false;       ///< tolerance reached before max_iterations
  double initial_energy = 0.0;  ///< E of the start shape (mm⁴), after the first local step
  double energy = 0.0;          ///< E of the result (mm⁴)
  /// E / Σ a_f², dimensionless (0 for an isometric flattening); comparable
  /// across meshes and units.
  double relative_energy = 0.0;
  /// Faces whose 2D triangle is flipped or degenerate (signed area <= 0),
  /// ascending. Empty for a valid flattening.
  std::vector<int> flipped_faces;
  /// Stopped by ArapFlattenOptions::stop_after_folded_iterations.
  bool stopped_folded = false;
};

/// 2D coordinates of the corners of face f in an isometric frame of its 3D
/// triangle (corner 0 at the origin, corner 1 on +x, corner 2 above the x
/// axis for a non-degenerate face).
std::array<Vec2, 3> isometric_triangle(const TriMesh& mesh, int f);

/// Flattens `mesh` (see the file comment).
/// \pre mesh is manifold, consistently oriented, one component, with a
///      boundary (for the default Tutte start).
/// \throw InvalidInput when `initial` has the wrong size or non-finite
///        entries, pinned_vertex or a constraint index is out of range,
///        max_iterations < 0 or tolerance < 0, or the mesh has no faces or
///        zero area; TopologyError from tutte_embedding(); SolverError when
///        the global system cannot be factored.
ArapFlattenResult arap_flatten(const TriMesh& mesh, const ArapFlattenOptions& options = {});

/// Signed area of the 2D triangle of face f under uv (positive = same
/// orientation as the start / counter-clockwise).
double signed_uv_area(const TriMesh& mesh, const std::vector<Vec2>& uv, int f);

/// True when some face's 2D triangle is flipped or degenerate
/// (signed_uv_area() <= 0 or not a number): uv is not injective.
bool has_flipped_face(const TriMesh& mesh, const std::vector<Vec2>& uv);

}  // namespace knitforge
