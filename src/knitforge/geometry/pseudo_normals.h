#pragma once
/// \file pseudo_normals.h
/// Angle-weighted pseudo-normals of a triangle mesh (Bærentzen and Aanæs,
/// "Signed distance computation using the angle weighted pseudonormal",
/// IEEE TVCG 2005), for telling the two sides of a surface apart:
///  - in a face's interior, the face's unit normal;
///  - on an edge, the sum of the unit normals of the faces sharing it;
///  - at a vertex, the sum of the unit normals of its faces, each weighted
///    by the face's angle at the vertex.
/// For a closed, consistently oriented mesh, a point p lies outside (on the
/// side the face normals point to) exactly when (p - c) . N > 0, with c the
/// closest point of the mesh to p and N the pseudo-normal of the feature c
/// lies on. On an open mesh the same test tells the side the normals point
/// to near the surface. Degenerate faces add nothing.

#include <cstdint>
#include <unordered_map>
#include <vector>

#include "knitforge/geometry/mesh_measures.h"
#include "knitforge/geometry/tri_mesh.h"

namespace knitforge {

/// The pseudo-normals of one pose of a mesh (unnormalised sums; only their
/// direction matters).
struct PseudoNormals {
  std::vector<Vec3> face;    ///< unit normal per face (zero when degenerate)
  std::vector<Vec3> vertex;  ///< angle-weighted sum per vertex
  std::unordered_map<std::uint64_t, Vec3> edge;  ///< per undirected edge (key: undirected_edge_key(), edge_key.h)
  /// The pseudo-normal where `where` lies on face `face` of `mesh`
  /// (its region and feature, closest_triangle_point()).
  Vec3 at(const TriMesh& mesh, int face, const TrianglePoint& where) const;
};

/// \throw InvalidInput for a face index out of range.
PseudoNormals pseudo_normals(const TriMesh& mesh);

/// True when every edge of the mesh has exactly two faces (no boundary and
/// no edge of three or more faces), which makes its inside well defined.
bool is_closed_mesh(const TriMesh& mesh);

}  // namespace knitforge
