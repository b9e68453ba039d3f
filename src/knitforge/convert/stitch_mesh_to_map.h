#pragma once
/// \file stitch_mesh_to_map.h
/// Stitch mesh -> knitting map (seed §1.3.1, Algorithm 1.1).
///
/// Rows are the components of stitches joined across Left/Right sides,
/// columns those joined across Bottom/Top sides. Rows are ordered by a
/// topological sort of "the Bottom neighbour's row is knitted before the Top
/// neighbour's row" (ties, which a knittable mesh never has, go to the row
/// with the smallest Stitch::course label, then the smallest stitch index, so
/// a design route that ordered its courses keeps that order); columns by "the Left neighbour's column
/// is left of the Right neighbour's column", ties broken by Kahn's algorithm
/// taking, among the ready columns, the one whose lowest stitch has the
/// smallest row, then the smallest stitch index. When every stitch carries a
/// wale label (Stitch::wale >= 0) and the labels agree with the mesh (a Right
/// neighbour has a larger label, a Top neighbour the same, no two stitches of
/// a row share one), the labels are the columns instead: a design route can
/// then place pieces of fabric that are separated vertically (the two sides
/// of a notch in the boundary) in the same columns. Each stitch fills the cell
/// (row, column) with its type and yarn; cells between two mesh neighbours
/// that are not grid neighbours become Collapsed, all other cells Empty. The
/// row direction is the direction of its stitches. The result is canonical:
/// map_to_stitch_mesh_topology() of it gives the same stitches back, and for
/// canonical maps map -> mesh -> map is the identity.
///
/// Tubes: when the columns form a cycle and every stitch has a wale label,
/// the mesh is read as a tube (docs/tubes.md): the labels (minus the
/// smallest) are the columns, a Right neighbour with a smaller or equal label
/// closes its row (a round), and the round's seam is the canonical one (as
/// canonical_cells()): the grid line just after its highest-index stitch in
/// its direction (stitches numbered in knitting order, as
/// map_to_stitch_mesh_topology() numbers them).
///
/// Runs in O(stitches + rows * cols).

#include "knitforge/core/knitting_map.h"
#include "knitforge/core/stitch_mesh.h"

namespace knitforge {

/// The knitting map of a stitch mesh (vertex positions are not used).
/// \throw InvalidInput naming the stitches when the mesh is empty, the rows or
///        columns form a cycle (a helix), stitches of one row disagree on the
///        direction, two stitches fall into the same cell, or two
///        neighbours meet across sides that are not opposite (my Right against
///        your Top); TopologyError when the mesh is not an oriented manifold.
KnittingMap stitch_mesh_to_map(const StitchMesh& mesh);

}  // namespace knitforge
