#pragma once
/// \file thicken_surface.h
/// Thickening an open surface into a solid for fabrication (seed §2.C.2:
/// "the open surface is converted to a solid by thickening. We create an
/// opposite surface by inverting the face orientation of the original
/// surface. All vertices of the opposite surface are moved by t in their
/// normal directions ... the original surface and the opposite surface are
/// connected"). Since both layers have the same boundary vertices, the
/// connecting band is a strip of quads (each split into two triangles along
/// its shorter diagonal) — what the graph-based loop tessellation
/// (loop_tessellation.h) yields for two loops of equal size and matching
/// vertices.

#include <vector>

#include "knitforge/geometry/tri_mesh.h"

namespace knitforge {

/// Robust vertex normals for offsetting: area-weighted (the sum of the
/// incident faces' area vectors); where that sum nearly cancels (below 1e-6
/// of the summed face areas — a crease folded back on itself, slivers) the
/// sum of the incident unit face normals is used instead. Isolated vertices
/// get a zero normal.
/// \param fallback_count if not null, receives the number of vertices that
///        needed the fallback.
/// \throw InvalidInput naming the vertex when neither rule gives a direction
///        (the incident faces cancel exactly), or a coordinate is not finite.
std::vector<Vec3> offset_normals(const TriMesh& mesh, int* fallback_count = nullptr);

/// Moves every vertex by `distance` (mm, negative: against the normal) along
/// offset_normals(). Faces are unchanged.
/// \param flipped_faces if not null, receives the number of faces turned
///        inside out (the offset area vector, or one of the face's edges,
///        points opposite to the original one): the offset exceeded the
///        local radius of curvature there.
/// \throw InvalidInput when `distance` is not finite, as offset_normals().
TriMesh offset_surface(const TriMesh& mesh, double distance, int* flipped_faces = nullptr);

/// Which side of the surface the material goes.
enum class ThickenSide {
  Both,     ///< t/2 along the normal and t/2 against it (the surface is the mid-surface)
  Outside,  ///< along the normal (the surface is the inner face of the solid)
  Inside,   ///< against the normal (the surface is the outer face of the solid)
};

/// Options of thicken_surface().
struct ThickenOptions {
  double thickness = 2.0;  ///< mm, > 0
  ThickenSide side = ThickenSide::Both;
};

/// A thickened surface.
struct ThickenResult {
  /// Closed, consistently oriented, outward-facing solid: vertices 0..V-1 are
  /// the layer on the normal side (original orientation), V..2V-1 the layer
  /// on the other side (reversed), where V is the number of vertices used by
  /// the input faces (unused input vertices are dropped, order kept).
  TriMesh solid;
  /// Faces of either layer turned inside out by the offset (area vector or
  /// an edge reversed): the thickness exceeds the local radius of curvature
  /// there and the solid intersects itself. 0 for a clean result.
  int flipped_faces = 0;
  /// Vertices whose normal needed the fallback of offset_normals().
  int fallback_normals = 0;
};

/// Thickens an oriented surface (open or closed, any genus) into a solid:
/// both layers plus, along every boundary loop, a band of quads joining them.
/// Every edge of the result is shared by exactly two faces. A closed input
/// gives two nested shells (a hollow solid).
/// \throw InvalidInput when the thickness is not positive and finite or the
///        mesh has no faces or a non-finite coordinate.
/// \throw TopologyError when the surface is not an oriented edge-manifold
///        (build_halfedges()).
ThickenResult thicken_surface(const TriMesh& surface, const ThickenOptions& options = {});

}  // namespace knitforge
