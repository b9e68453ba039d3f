#pragma once
/// \file harmonic_field.h
/// The governing field of the short-column route (seed §3.3.3, L1303-1322):
/// the harmonic function f on a disk with f = 0 on R_s = [b0, b1], f = 1 on
/// R_e = [b2, b3] (boundary_intervals.h) and the natural (Neumann) condition
/// on the rest of the boundary, by the cotangent Laplace-Beltrami operator
/// (L1504, geometry/cotan_laplacian.h): (L f)_i = 0 at every vertex that is
/// not Dirichlet. A harmonic function has no interior extrema (so no closed
/// isocurves, L1319) and its isocurves meet the free boundary orthogonally
/// (boundary-aware, L1320, Fig. 3.12). With obtuse triangles the discrete
/// maximum principle can fail slightly; HarmonicField::interior_extrema
/// counts the interior vertices that are nevertheless strict local extrema.
///
/// Cheap repeated solves (the optimisation evaluates many b). The Dirichlet
/// rows and columns are replaced by the identity inside the full pattern of
/// L, so every b gives a matrix with the same sparsity pattern: the solver
/// orders and analyses it once (SparseSolver::analyze()) and each solve()
/// is one numeric Cholesky factorisation and one solve
/// (docs/shortcolumn.md, benchmarks). The one-shot harmonic_field() does
/// both.
///
/// Other fields (§3.3.3: "any other field without interior extrema"):
/// fiedler_field() (the low-order Laplacian eigenvector of [134], L1216) and
/// any per-vertex field given by the user.

#include <memory>
#include <string>
#include <vector>

#include "knitforge/design/shortcolumn/boundary_intervals.h"
#include "knitforge/geometry/sparse_solver.h"
#include "knitforge/geometry/tri_mesh.h"

namespace knitforge {

/// A harmonic governing field.
struct HarmonicField {
  std::vector<double> value;  ///< f per vertex, in [0, 1]
  DirichletSets sets;         ///< where f = 0 and f = 1 were imposed
  BoundaryVector b{};         ///< the requested boundary vector
  /// Interior vertices that are strict local extrema of f (0 for a valid
  /// harmonic field on a Delaunay-like mesh).
  int interior_extrema = 0;
};

/// Solves the harmonic field for many boundary vectors on one mesh.
class HarmonicFieldSolver {
 public:
  /// Builds the cotangent Laplacian, the boundary parameterisation and the
  /// symbolic factorisation.
  /// \throw TopologyError unless `mesh` is a valid disk (require_disk());
  ///        InvalidInput as parameterise_boundary().
  explicit HarmonicFieldSolver(const TriMesh& mesh);
  ~HarmonicFieldSolver();
  HarmonicFieldSolver(HarmonicFieldSolver&&) noexcept;
  HarmonicFieldSolver& operator=(HarmonicFieldSolver&&) noexcept;
  HarmonicFieldSolver(const HarmonicFieldSolver&) = delete;
  HarmonicFieldSolver& operator=(const HarmonicFieldSolver&) = delete;

  /// The field of b (feasible, eq. 3.8). Not thread-safe (the factor is
  /// reused).
  /// \throw InvalidInput / TopologyError from dirichlet_sets(); SolverError
  ///        when the factorisation fails.
  HarmonicField solve(const BoundaryVector& b);
  /// The field with the given Dirichlet sets (vertex ids, disjoint, at least
  /// one vertex in each).
  /// \throw InvalidInput for empty, overlapping or out-of-range sets.
  std::vector<double> solve_sets(const std::vector<int>& zero, const std::vector<int>& one);

  const BoundaryParameterisation& boundary() const;
  const TriMesh& mesh() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// One-shot: the harmonic field of b on `mesh`.
/// \throw as HarmonicFieldSolver.
HarmonicField harmonic_field(const TriMesh& mesh, const BoundaryVector& b);

/// Number of interior vertices of `mesh` that are strict local minima or
/// maxima of `field` over their edge neighbours.
/// \throw InvalidInput when field.size() != mesh.num_vertices().
int count_interior_extrema(const TriMesh& mesh, const std::vector<double>& field);

/// The Fiedler field: the eigenvector of L v = lambda M v (cotangent
/// Laplacian, lumped Voronoi mass) of the smallest non-zero eigenvalue,
/// by block inverse iteration (4 vectors, Rayleigh-Ritz, constants projected
/// out), rescaled to [0, 1] with the sign that makes its entry of largest
/// magnitude positive (deterministic; the start vertex is then the minimum
/// f = 0). `converged` is false when the residual
/// |L v - lambda M v| / (lambda |M v|) stayed above 1e-6 after 300 iterations
/// (a near-degenerate eigenvalue, e.g. on a symmetric shape: any vector of
/// the eigenspace is then a Fiedler vector).
struct FiedlerField {
  std::vector<double> value;
  double eigenvalue = 0.0;  ///< 1/mm^2
  double residual = 0.0;
  int iterations = 0;
  bool converged = false;
  int interior_extrema = 0;
};
/// \throw TopologyError unless `mesh` is a valid disk; SolverError when the
///        factorisation fails.
FiedlerField fiedler_field(const TriMesh& mesh);

}  // namespace knitforge
