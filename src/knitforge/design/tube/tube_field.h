#pragma once
/// \file tube_field.h
/// The governing field of the tube design route (seed §3.3.8, issue #15
/// item 2): on an annulus (one piece, two boundary loops, genus 0) the
/// harmonic function u with u = 0 on the start loop and u = 1 on the end
/// loop (cotangent Laplacian, geometry/cotan_laplacian.h). A harmonic field
/// on an annulus with constant values on its two rims has no interior
/// critical point (no extremum by the maximum principle, no saddle since
/// the Euler characteristic is 0), so every level 0 < u < 1 is one closed
/// loop round the tube: a round.
///
/// The start loop (where the tube is cast on) is the longer rim, so that a
/// tapering tube (a sleeve from the shoulder) is shaped by decreases; ties
/// go to the first loop of Halfedges::boundary_loops().
///
/// Round spacing: the levels of u are not evenly spaced on the surface. The
/// mean distance walked along the gradient from the start loop to level u
/// is D(u) = integral of the mean of 1/|grad u| over each level (co-area:
/// the area between two close levels divided by their length), tabulated
/// at 512 levels (midpoint rule). round_levels() cuts D into K = round(D(1)
/// / stitch height) equal steps: the rounds lie one stitch height apart on
/// average round the tube.

#include <string>
#include <vector>

#include "knitforge/geometry/sparse_solver.h"
#include "knitforge/geometry/tri_mesh.h"

namespace knitforge {

/// The harmonic field of an annulus and its two rims.
struct TubeField {
  std::vector<double> value;   ///< u per vertex, 0 on the start loop, 1 on the end loop
  std::vector<int> start_loop;  ///< boundary vertex cycle, the surface on its left
  std::vector<int> end_loop;    ///< boundary vertex cycle, the surface on its left
  double start_length = 0.0, end_length = 0.0;  ///< rim lengths (mm)
  int interior_extrema = 0;  ///< interior vertices that are strict local extrema (0 expected)
};

/// Solves the tube field of `mesh`.
/// \throw InvalidInput "<what> has N boundary loops ..." unless the mesh is
///        one piece with exactly two boundary loops and genus 0, naming
///        what was found and what to do; SolverError when the solve fails.
TubeField tube_field(const TriMesh& mesh, const std::string& what);

/// The field with `rims`' start loop at 0 and end loop at 1 that minimises
/// u^T K u over the other vertices, for a stiffness K (n x n, symmetric,
/// positive definite once the rims are fixed: the cotangent Laplacian gives
/// tube_field()'s field, directional_stiffness() one that follows given
/// isocurves, design_tube.cpp). Values clamped to [0, 1]; `rims`' loops and
/// lengths are kept, its values replaced, interior_extrema counted.
/// \throw InvalidInput when K is not n x n; SolverError when the solve fails.
TubeField field_with_level_rims(const TriMesh& mesh, const SparseMatrix& K, TubeField rims);

/// Levels of the rounds.
struct RoundLevels {
  std::vector<double> levels;  ///< u of round 0..K (0 and 1 at the rims)
  double mean_length = 0.0;    ///< D(1): mean distance from rim to rim (mm)
};

/// The levels of K + 1 rounds one stitch height apart on average (see the
/// file comment); K >= 1.
/// \throw InvalidInput when stitch_height is not positive, or a level of u
///        is not one closed loop (the field is not a tube's field).
RoundLevels round_levels(const TriMesh& mesh, const TubeField& field, double stitch_height);

}  // namespace knitforge
