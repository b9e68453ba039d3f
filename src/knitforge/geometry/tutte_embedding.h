#pragma once
/// \file tutte_embedding.h
/// Tutte's barycentric embedding (seed §2.3.1: the "barycentric mapping"
/// [19] that starts the ARAP flattening): the outer boundary loop is fixed on
/// a circle, parameterised by arc length, and every other vertex is the
/// average of its neighbours (uniform weights). For a disk the result is a
/// bijective map onto the convex disk (Tutte / Floater): no face is flipped.
///
/// Meshes with further boundary loops (a disk with interior slits, as after
/// cutting two-end darts) are accepted: the longest loop (3D length) is the
/// fixed outer boundary, the other loops' vertices are free like interior
/// vertices (the embedding is then not guaranteed to be bijective near them,
/// which the ARAP iterations that follow repair).
#include <vector>
#include "knitforge/geometry/tri_mesh.h"
#include "knitforge/geometry/vec.h"

namespace knitforge {

/// The embedding and which loop was fixed.
struct TutteEmbedding {
  /// 2D position per vertex (mm); the circle has the 3D length of the outer
  /// loop as circumference and is centred at the origin. Vertices no face
  /// uses are placed at the origin.
  std::vector<Vec2> uv;
  /// The outer boundary loop (vertex cycle, mesh to its left), placed
  /// counter-clockwise on the circle starting at angle 0.
  std::vector<int> outer_loop;
  double radius = 0.0;  ///< mm
};

/// Tutte embedding of a mesh with at least one boundary loop (see the file
/// comment).
/// \pre mesh is manifold and consistently oriented; all its faces form one
///      connected component.
/// \throw TopologyError (from build_halfedges()) for a non-manifold mesh;
///        TopologyError when the mesh has no boundary (closed surface: cut it
///        open first) or several components; InvalidInput when the outer
///        loop has zero length.
TutteEmbedding tutte_embedding(const TriMesh& mesh);

}  // namespace knitforge
