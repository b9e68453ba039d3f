#pragma once
/// \file feasible_set.h
/// The feasible set Omega of the boundary vector (seed eq. 3.8) as linear
/// inequalities, the projection QP of eq. 3.9 that maps an infeasible
/// suggestion of the optimiser to the nearest feasible point, a uniform
/// sampler of Omega for the initial design ("we sample all points in the
/// feasible space", L1469), and the 2D symmetric variant (L1484, Fig. 3.15).
///
/// Eq. 3.8, 0 <= b0 <= b1 < b2 <= b3 < 1 + b0 < 2, is six linear
/// constraints A b >= c (L1473); the strict ones get the margin m
/// (kFeasibleMargin of boundary_intervals.h):
///   b0 >= 0,  b1 - b0 >= 0,  b2 - b1 >= m,  b3 - b2 >= 0,
///   1 + b0 - b3 >= m,  -b0 >= m - 1.
///
/// Projection (eq. 3.9): argmin ||beta - b||^2 over {A beta >= c}. For the few
/// constraints here the exact solution is found by enumerating active sets:
/// for every subset S of at most `dim` constraints with independent rows the
/// equality-constrained minimiser beta_S = b + A_S^T (A_S A_S^T)^-1 (c_S - A_S b)
/// is computed, and the feasible beta_S nearest to b is the projection (the
/// projection onto a convex polytope is the projection onto the affine hull
/// of the face it lands in, and no feasible point is nearer).
///
/// Symmetric variant: for a surface mirror-symmetric about a plane that
/// crosses the boundary at parameters p and q = p + g (0 < g < 1), R_s is
/// centred at p and R_e at q: b = (p - a, p + a, q - e, q + e) with the two
/// half-widths (a, e) as the variables; eq. 3.8 becomes a >= 0, e >= 0,
/// a + e <= g - m, a + e <= 1 - g - m (the triangle of Fig. 3.15).

#include <array>
#include <vector>

#include <Eigen/Core>

#include "knitforge/design/shortcolumn/boundary_intervals.h"

namespace knitforge {

/// Linear inequalities A x >= c.
struct LinearConstraints {
  Eigen::MatrixXd A;
  Eigen::VectorXd c;
  int dim() const { return static_cast<int>(A.cols()); }
  /// True when A x >= c - tolerance holds row by row.
  bool contains(const Eigen::VectorXd& x, double tolerance = 1e-12) const;
};

/// The six constraints of eq. 3.8 on b (margin m for the strict ones).
LinearConstraints boundary_constraints(double margin = kFeasibleMargin);

/// The constraints of the symmetric variant on (a, e) for the gap g.
/// \throw InvalidInput when g is not in (2 m, 1 - 2 m).
LinearConstraints symmetric_constraints(double gap, double margin = kFeasibleMargin);

/// The nearest point of {A x >= c} to y (eq. 3.9), exact (see the file
/// comment). At most 8 constraints and 8 dimensions.
/// \throw InvalidInput for sizes out of range; InvalidInput when the set is
///        empty (no subset gives a feasible point).
Eigen::VectorXd project_onto_constraints(const LinearConstraints& k, const Eigen::VectorXd& y);

/// The uniform map from the unit cube [0, 1]^4 onto eq. 3.8 with margins:
/// b0 = u0 (1 - m); the sorted u1..u3, s0 <= s1 <= s2, give the gaps
/// b1 - b0 = w s0, b2 - b1 = m + w (s1 - s0), b3 - b2 = w (s2 - s1) with
/// w = 1 - 2 m. Uniform u gives uniform b over the shrunk set.
BoundaryVector boundary_from_unit(const Eigen::Vector4d& u, double margin = kFeasibleMargin);

/// b of the symmetric variant (values wrapped so that b0 is in [0, 1)).
BoundaryVector symmetric_boundary(double p, double gap, double a, double e);

/// b moved by rounding-size amounts into eq. 3.8 exactly (is_feasible()):
/// the projection and the tolerance of LinearConstraints::contains() leave
/// violations of ~1e-12 (b3 a hair below b2), which dirichlet_sets() would
/// reject. Each coordinate is clamped in order: b0 to [0, 1 - m], b1 >= b0,
/// b2 >= b1 + m, b3 >= b2, then b3 <= 1 + b0 - m when that keeps b3 >= b2.
/// \throw InvalidInput when b is farther than 1e-9 from the set (a caller's
///        bug, not rounding).
BoundaryVector snap_feasible(const BoundaryVector& b, double margin = kFeasibleMargin);

/// b wrapped to the canonical range: b0 in [0, 1), the others shifted by the
/// same integer.
BoundaryVector canonical_boundary(const BoundaryVector& b);

/// Circular distance between two boundary vectors (each coordinate's
/// difference taken modulo 1 to [-1/2, 1/2]), Euclidean over the four.
double boundary_distance(const BoundaryVector& a, const BoundaryVector& b);

}  // namespace knitforge
