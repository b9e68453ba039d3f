#pragma once
/// \file boundary_intervals.h
/// The variables of the short-column optimisation (seed §3.3.5, L1441-1462):
/// the boundary loop of a disk parameterised onto [0, 1) anticlockwise by
/// arc length, and the Dirichlet regions R_s = [b0, b1] (f = 0) and
/// R_e = [b2, b3] (f = 1) given by b = (b0, b1, b2, b3) in the feasible set
/// eq. 3.8: 0 <= b0 <= b1 < b2 <= b3 < 1 + b0 < 2 (values above 1 wrap).
///
/// Parameterisation. "Anticlockwise" is the direction of the boundary loop
/// with the surface on its left (Halfedges::boundary_loops()), i.e.
/// anticlockwise seen from the side the face normals point to. The seed does
/// not say where 0 is; we start at the boundary vertex with the largest x
/// coordinate (ties: smallest y, then z, then index), a geometric choice so
/// that one b means about the same boundary points on every remeshing of a
/// surface (the resolution study of Fig. 3.17). t(v) = arc length from the
/// start to v along the loop / loop length.
///
/// Discretisation (L1456-1462). Each b_i is snapped to the boundary vertex
/// whose parameter is nearest (circularly); R_s = the loop vertices from
/// snap(b0) forward to snap(b1), R_e likewise. b0 = b1 gives a point
/// condition. After snapping the sets can overlap (b2 - b1 below one edge)
/// or all their distinct vertices can lie in one triangle, where the field is
/// degenerate (the seed: "move one point out of this triangle"): R_e then
/// loses the vertices it shares with R_s, and while the sets are empty or
/// in one triangle R_e moves forward along the loop by one vertex (keeping
/// its vertex count), at most once around. `adjusted` says it happened.

#include <array>
#include <string>
#include <vector>

#include "knitforge/geometry/tri_mesh.h"

namespace knitforge {

/// The boundary loop of a disk with its arc-length parameter.
struct BoundaryParameterisation {
  std::vector<int> loop;  ///< boundary vertices, anticlockwise, loop[0] = the start vertex
  std::vector<double> t;  ///< per loop entry, parameter in [0, 1), t[0] = 0, increasing
  double length = 0.0;    ///< loop length (mm)

  int size() const { return static_cast<int>(loop.size()); }
  /// Index into `loop` of the vertex whose parameter is nearest to u (u taken
  /// modulo 1; ties to the smaller index).
  int nearest(double u) const;
  /// Parameter of loop entry k unwrapped to lie in [u, u + 1).
  double unwrapped(int k, double u) const;
};

/// Parameterises the single boundary loop of `mesh`.
/// \throw TopologyError when the mesh is not a manifold surface with exactly
///        one boundary loop (the message gives the number of loops);
///        InvalidInput when the loop has zero length.
BoundaryParameterisation parameterise_boundary(const TriMesh& mesh);

/// b = (b0, b1, b2, b3).
using BoundaryVector = std::array<double, 4>;

/// Margin used for the strict inequalities of eq. 3.8 in the optimiser's
/// projection (b1 + margin <= b2, b3 + margin <= 1 + b0, b0 <= 1 - margin).
inline constexpr double kFeasibleMargin = 1e-3;

/// True when b satisfies eq. 3.8 (strict inequalities strict, no margin).
bool is_feasible(const BoundaryVector& b);

/// "b0,b1,b2,b3" with six decimals.
std::string format_boundary_vector(const BoundaryVector& b);

/// Parses "b0,b1,b2,b3" (the --bc option).
/// \throw InvalidInput naming the text when it is not four numbers or not
///        in the feasible set (the message states eq. 3.8).
BoundaryVector parse_boundary_vector(const std::string& text);

/// The Dirichlet vertex sets of b on a parameterised boundary.
struct DirichletSets {
  std::vector<int> zero;  ///< R_s vertices (f = 0), in loop order
  std::vector<int> one;   ///< R_e vertices (f = 1), in loop order
  /// Loop indices of the first and last vertex of each set.
  int zero_first = -1, zero_last = -1, one_first = -1, one_last = -1;
  bool adjusted = false;  ///< R_e was moved (overlap or one triangle, see the file comment)
};

/// Snaps b to boundary vertices (see the file comment).
/// \throw InvalidInput when b is not feasible (eq. 3.8) or the boundary has
///        fewer than 3 vertices; TopologyError when no valid placement exists.
DirichletSets dirichlet_sets(const TriMesh& mesh, const BoundaryParameterisation& boundary,
                             const BoundaryVector& b);

}  // namespace knitforge
