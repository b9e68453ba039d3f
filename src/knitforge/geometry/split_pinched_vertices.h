#pragma once
/// \file split_pinched_vertices.h
/// Makes a triangle mesh vertex-manifold by giving every extra fan of faces
/// around a vertex its own copy of that vertex ("pinched" vertices, where two
/// parts of a surface touch at one point: e.g. after removing the faces of a
/// band, the rest may hang together at single vertices). Faces around a
/// vertex belong to one fan when they are linked through edges at that vertex
/// (two faces sharing the edge (v, w)). Edges used by more than two faces are
/// not repaired (build_halfedges() still rejects them).

#include <vector>

#include "knitforge/geometry/tri_mesh.h"

namespace knitforge {

/// Splits pinched vertices in place; the copies are appended. Returns, per
/// vertex of the result, the vertex of the input it came from (the identity
/// for the original ones).
/// \throw InvalidInput for a face index out of range.
std::vector<int> split_pinched_vertices(TriMesh& mesh);

}  // namespace knitforge
