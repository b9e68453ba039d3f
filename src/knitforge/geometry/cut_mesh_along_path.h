#pragma once
/// \file cut_mesh_along_path.h
/// Cutting a mesh open along a path of mesh edges (the second step of seed
/// §2.B: split first with split_mesh_along_path(), then cut), for darts
/// (seed §2.2) and for removing closed wale curves (seed §3.2.1: cut from the
/// enclosed local maximum to the boundary).
///
/// Every path edge that is an interior edge becomes two boundary edges. At
/// each vertex the faces around it are grouped into wedges separated by the
/// cut edges; every wedge gets its own copy of the vertex. The first wedge
/// keeps the original index, further copies are appended (in order of the
/// original vertex, then around it), so vertices off the path keep their
/// indices and positions, and the faces keep their order and orientation.
/// Hence:
///  - an interior path end (one cut edge at an interior vertex) is not
///    duplicated: the slit ends there;
///  - an interior vertex in the middle of the path gets two copies;
///  - a path vertex on the boundary gets one copy more than its number of
///    cut edges (a boundary end of the path is duplicated);
///  - a path that touches itself, or a closed path, is handled the same way.
/// The result is manifold. A disk cut from an interior point to the boundary
/// stays a disk (one boundary loop, longer by twice the path length); a disk
/// cut from boundary to boundary falls into two components. Path edges that
/// are already boundary edges cut nothing.

#include <vector>

#include "knitforge/geometry/tri_mesh.h"

namespace knitforge {

/// The cut mesh and how it relates to the input.
struct CutMeshResult {
  TriMesh mesh;
  /// For every vertex of `mesh`, the input vertex it is a copy of.
  std::vector<int> vertex_origin;
  /// The two sides of the cut: for every path vertex i, its copy in the
  /// wedge to the left of the path (the face holding the half-edge
  /// path[i] -> path[i+1], or path[i-1] -> path[i] for the last vertex) and
  /// to the right (the face holding the opposite half-edge); -1 where there
  /// is no face on that side (a boundary edge).
  std::vector<int> left;
  std::vector<int> right;
  /// Number of interior edges cut (each became two boundary edges).
  int num_cut_edges = 0;
  /// Connected components of the result (faces joined by edges).
  int num_components = 0;
  /// Component id per face of `mesh`.
  std::vector<int> face_component;
};

/// Cuts `mesh` open along the vertex path (consecutive vertices must be
/// joined by mesh edges).
/// \pre mesh is manifold and consistently oriented.
/// \throw InvalidInput naming the position in the path when the path has
///        fewer than two vertices, a vertex index is out of range, two
///        consecutive vertices are equal or not joined by an edge.
/// \throw TopologyError from build_halfedges() for a non-manifold mesh.
CutMeshResult cut_mesh_along_path(const TriMesh& mesh, const std::vector<int>& path);

/// Cuts `mesh` open along several vertex paths at once (the union of their
/// edges: a cut graph, e.g. the seams of cut_to_disk.h); the same wedge
/// rule as above. `left` and `right` list the sides of every path's
/// vertices, path after path.
/// \pre as cut_mesh_along_path().
/// \throw as cut_mesh_along_path() (naming the path), InvalidInput when
///        `paths` is empty.
CutMeshResult cut_mesh_along_paths(const TriMesh& mesh, const std::vector<std::vector<int>>& paths);

}  // namespace knitforge
