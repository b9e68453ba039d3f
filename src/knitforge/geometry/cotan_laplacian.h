#pragma once
/// \file cotan_laplacian.h
/// The cotangent discretisation of the Laplace-Beltrami operator on a
/// triangle mesh (the P1 finite-element stiffness matrix) and the mixed
/// Voronoi vertex areas of Meyer et al. 2003, used by the harmonic governing
/// field and the divergence metric of seed §3.3 (eq. 3.6, L1504).
///
/// Stiffness: L_ij = -(cot a_ij + cot b_ij) / 2 for an edge ij with opposite
/// angles a_ij, b_ij (one angle on the boundary), L_ii = -sum_j L_ij. L is
/// symmetric positive semidefinite with the constants as its null space on
/// every connected component; x^T L x = the Dirichlet energy of the
/// piecewise-linear function x. A harmonic function is one with (L x)_i = 0
/// at every free vertex i; the free (Neumann) boundary needs no extra term.
///
/// Mixed Voronoi area: for a non-obtuse triangle each corner gets its
/// Voronoi part (|e|^2 cot terms / 8); an obtuse triangle gives half its
/// area to the obtuse corner and a quarter to each other corner. The areas
/// sum to the mesh area exactly.

#include <vector>

#include "knitforge/geometry/sparse_solver.h"
#include "knitforge/geometry/tri_mesh.h"

namespace knitforge {

/// The cotangent stiffness matrix (n x n, both triangles stored; units: none,
/// cotangents are dimensionless). Every vertex has a diagonal entry (0 for a
/// vertex no face uses). Cotangents of (near-)degenerate corners are clamped
/// to +-1e6 so the matrix stays finite.
/// \throw InvalidInput for a face with an index out of range.
SparseMatrix cotan_laplacian(const TriMesh& mesh);

/// Mixed Voronoi area per vertex (mm^2); 0 for a vertex no face uses.
/// \throw InvalidInput for a face with an index out of range.
std::vector<double> mixed_voronoi_areas(const TriMesh& mesh);

/// The lumped (diagonal) mass matrix diag(mixed_voronoi_areas(mesh)).
SparseMatrix voronoi_mass_matrix(const TriMesh& mesh);

}  // namespace knitforge
