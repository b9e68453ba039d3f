#pragma once
/// \file laplacian_eigenvectors.h
/// The lowest eigenvectors of the cotangent Laplacian (geometry/
/// cotan_laplacian.h): L x = lambda M x with M the lumped Voronoi mass
/// matrix (free, Neumann boundary), the constant one left out. The first of
/// them is the Fiedler vector, which seed §3.3.8 (L1562) takes as the shape's
/// "diameter direction": on a long cylinder it is cos(pi z / length), on a
/// sphere-like cap a linear function across it.
///
/// Method: subspace iteration with the shift-inverted pencil
/// (L + sigma M)^-1 M (one CHOLMOD factor, sparse_solver.h), sigma = 1e-6 x
/// trace L / trace M, on a block of `count` + 4 vectors started from the
/// coordinate monomials of degree 1 and 2 (x, y, z, x^2, ...; deterministic),
/// each step M-orthogonal to the constants, with a Rayleigh-Ritz projection.
/// It stops when every wanted pair's relative residual |L x - lambda M x| /
/// (lambda |M x|) is below `tolerance`, or after `max_iterations` (then
/// `converged` is false and the vectors are the best found).
///
/// Normalisation: x^T M x = 1 (unit L2 norm on the surface, mm^-1 area
/// weight: values in 1/mm); sign such that the vertex of largest |x| is
/// positive (the first one on ties).

#include <vector>

#include "knitforge/geometry/sparse_solver.h"
#include "knitforge/geometry/tri_mesh.h"

namespace knitforge {

/// Options of laplacian_eigenvectors().
struct EigenvectorOptions {
  int count = 1;             ///< eigenpairs wanted, >= 1 (the Fiedler vector is the first)
  int max_iterations = 200;  ///< subspace iterations
  double tolerance = 1e-6;   ///< relative residual
};

/// The lowest non-constant eigenpairs, by increasing eigenvalue.
struct LaplacianEigenvectors {
  std::vector<double> values;                ///< lambda (1/mm^2)
  std::vector<std::vector<double>> vectors;  ///< per pair: one value per vertex
  int iterations = 0;
  bool converged = false;
};

/// \throw InvalidInput when the mesh is empty, not one connected piece (a
///        second piece would give a second constant: refused, naming the
///        count), has fewer vertices than count + 5, or count < 1;
///        SolverError from the factorisation.
LaplacianEigenvectors laplacian_eigenvectors(const TriMesh& mesh, const EigenvectorOptions& options = {});

/// The Fiedler vector (laplacian_eigenvectors() with count 1).
std::vector<double> fiedler_vector(const TriMesh& mesh);

/// The lowest non-constant eigenpairs of K x = lambda M x for another
/// stiffness matrix K (n x n, symmetric positive semidefinite with the
/// constants in its null space, e.g. directional_stiffness()); M and the
/// method as laplacian_eigenvectors().
/// \throw as laplacian_eigenvectors(); InvalidInput when K is not n x n.
LaplacianEigenvectors stiffness_eigenvectors(const TriMesh& mesh, const SparseMatrix& K,
                                             const EigenvectorOptions& options = {});

/// The stiffness of the energy sum_f A_f <grad x, d_f>^2 + epsilon x^T L x:
/// change along the direction d_f of each face (unit, or shorter to weigh
/// the face less, e.g. flat_weighted_directions(); a zero d_f: none)
/// plus epsilon of the cotangent Laplacian (which keeps the lowest modes
/// smooth across the directions). Its lowest eigenvectors change least
/// along d: with d the normalised gradient of the Fiedler vector, the field
/// orthogonal to it (design/tube/tube_field_candidates.h).
/// \throw InvalidInput when directions.size() != faces, epsilon < 0, or a
///        face index is out of range.
SparseMatrix directional_stiffness(const TriMesh& mesh, const std::vector<Vec3>& directions, double epsilon);

/// Directions of a field for directional_stiffness(): per face its unit
/// gradient (isocurve_tangent false) or the unit tangent of its isocurve
/// (n x grad / |grad|, true), scaled by min(1, |grad| / the area-weighted
/// RMS of |grad| over the mesh). Where a field is flat (beside a free rim,
/// round an extremum) its direction is round-off, and these faces then
/// weigh little against the smoothing term, so round-off cannot steer
/// the result. All zero for a constant field.
/// \throw InvalidInput when field has not one value per vertex.
std::vector<Vec3> flat_weighted_directions(const TriMesh& mesh, const std::vector<double>& field,
                                           bool isocurve_tangent);

/// Area-weighted mean, over the faces where both gradients are non-zero, of
/// |cos| of the angle between grad a and grad b (0: orthogonal everywhere,
/// 1: parallel everywhere). Used to pick the field orthogonal to the
/// Fiedler vector (design/tube/tube_field_candidates.h).
/// \throw InvalidInput when a or b has not one value per vertex.
double gradient_alignment(const TriMesh& mesh, const std::vector<double>& a, const std::vector<double>& b);

}  // namespace knitforge
