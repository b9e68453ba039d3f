#pragma once
/// \file clip_mesh_by_field.h
/// The part of a triangle mesh where a piecewise-linear scalar field is
/// positive, cut exactly along the field's zero level: the boundary of the
/// result runs through the triangles (new vertices on the edges where the
/// field changes sign, at the linearly interpolated zero), not along the
/// triangle edges, so a smooth field gives a smooth rim instead of the
/// zigzag of whole faces.
///
/// Steps:
///  1. Snapping: where the zero crossing on an edge lies within
///     `snap_fraction` of the edge's length from one end, that vertex is
///     moved onto the crossing (along the edge, so it stays on the
///     surface) and its value set to 0. This removes the sliver triangles a
///     crossing next to a vertex would give.
///  2. Clipping (Sutherland-Hodgman per triangle against f >= 0): a
///     triangle with all values >= 0 and at least one > 0 is kept; one with
///     all values <= 0 is dropped; a triangle with both signs keeps its
///     positive part (a triangle or a quadrilateral, split along its shorter
///     diagonal). A crossing vertex is shared by the two triangles of its
///     edge, so the result is as connected as the input.
///  3. Vertices no kept face uses are dropped; the others keep their order
///     (input vertices first, then the crossings in order of creation).
///
/// Deterministic; O(V + F).

#include <vector>

#include "knitforge/geometry/tri_mesh.h"

namespace knitforge {

/// Options of clip_mesh_by_field().
struct ClipFieldOptions {
  /// Crossings closer than this fraction of the edge length to a vertex snap
  /// the vertex onto them, in [0, 0.5).
  double snap_fraction = 0.2;
};

/// Result of clip_mesh_by_field().
struct ClippedMesh {
  TriMesh mesh;
  /// For every vertex of `mesh`: the input vertex it is (possibly moved by
  /// snapping), or -1 for a new vertex on an edge.
  std::vector<int> vertex_origin;
  int snapped_vertices = 0;  ///< input vertices moved onto the zero level
};

/// The part of `mesh` with field > 0, cut along field = 0 (file comment).
/// \throw InvalidInput when the field's size is not the number of vertices,
///        a value is not finite, a face index is out of range, or
///        snap_fraction is outside [0, 0.5).
ClippedMesh clip_mesh_by_field(const TriMesh& mesh, const std::vector<double>& field,
                               const ClipFieldOptions& options = {});

}  // namespace knitforge
