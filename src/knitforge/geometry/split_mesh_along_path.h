#pragma once
/// \file split_mesh_along_path.h
/// Mesh splitting along a polyline path on the surface (seed §2.B,
/// Algorithms 2.1 and 2.2): after splitting, the path is a chain of mesh
/// edges through mesh vertices, ready for cutting (cut_mesh_along_path.h).
///
/// The path is a sequence of MeshPoints: mesh vertices, points on edges
/// (edge (v0, v1) at ratio r — the seed's (e_i0, e_i1, r_i)) and, in addition
/// to the seed, points inside faces. Consecutive points must lie on a common
/// face (closed faces include their edges and corners); a segment between
/// them runs either along a mesh edge or across the face.
///
/// Algorithm 2.2 (complete splitting): every edge is split at all the path
/// points on it (sorted), then every face touched by the path is
/// re-triangulated with the path segments crossing it as constraints (a
/// constrained Delaunay triangulation in the plane of the face, CGAL), so a
/// face crossed several times (a zig-zag path) is handled. Faces that only
/// carry points on their edges, or one crossing, are first triangulated by
/// successive edge splits (Algorithm 2.1, the fast path); the constrained
/// triangulation is only used where that does not produce the path segments
/// as edges.
///
/// Guarantees: existing vertices keep their indices and positions; new
/// vertices are appended in the order in which the path reaches them; faces
/// keep their orientation; the total area is preserved (up to rounding);
/// every consecutive pair of `path` is a mesh edge of the result; untouched
/// faces are copied unchanged (in their original order relative to the
/// others); the result is as manifold as the input.
///
/// Snapping (no degenerate triangles): an edge point with ratio r < snap or
/// r > 1 - snap (i.e. closer than snap x the edge length to an end) becomes
/// that vertex; two points on one edge closer than snap x its length merge;
/// a face point whose barycentric coordinate is below snap is moved onto the
/// opposite edge (onto the vertex when two are); two face points in one face
/// whose barycentric coordinates differ by less than snap merge. Default
/// snap = 1e-4.

#include <vector>

#include "knitforge/geometry/mesh_point.h"
#include "knitforge/geometry/tri_mesh.h"

namespace knitforge {

/// Options of split_mesh_along_path().
struct SplitOptions {
  /// Relative snapping distance (fraction of an edge length / barycentric
  /// coordinate), see the file comment. Must be in [0, 0.25).
  double snap = 1e-4;
};

/// The split mesh and how it relates to the input.
struct SplitMeshResult {
  TriMesh mesh;
  /// The path as vertices of `mesh`, consecutive duplicates removed; when a
  /// path segment runs along an edge that carries further path points, these
  /// are included, so every consecutive pair is an edge of `mesh`.
  std::vector<int> path;
  /// split_mesh_along_paths(): every path as vertices of `mesh`, as `path`
  /// is for one (path == paths[0]).
  std::vector<std::vector<int>> paths;
  /// For every input path point, its vertex in `mesh` (after snapping); the
  /// points of all paths one after the other for split_mesh_along_paths().
  std::vector<int> point_vertices;
  /// For every face of `mesh`, the face of the input it lies in.
  std::vector<int> face_origin;
  /// Number of vertices of the input; vertices below it are the input's.
  int original_num_vertices = 0;
  /// For every new vertex v (v >= original_num_vertices), its position on
  /// the input mesh: new_vertex_origin[v - original_num_vertices] (an edge
  /// point or a face point of the input).
  std::vector<MeshPoint> new_vertex_origin;
  /// Number of faces re-triangulated by the fast path (Alg. 2.1) and by the
  /// constrained triangulation (Alg. 2.2).
  int faces_split_simple = 0;
  int faces_split_constrained = 0;
};

/// Splits `mesh` along `path` so that the path becomes a chain of mesh edges.
/// \pre mesh is edge-manifold and consistently oriented.
/// \throw InvalidInput naming the path point (index) when a point refers to a
///        non-existent vertex, edge or face, has a ratio outside [0, 1] or
///        barycentric coordinates that are negative or do not sum to 1, or
///        when two consecutive points do not lie on a common face; naming
///        the face when path segments cross each other (or pass through
///        another path point) inside it; when snap is outside [0, 0.25).
/// \throw TopologyError from build_halfedges() for non-manifold input.
SplitMeshResult split_mesh_along_path(const TriMesh& mesh, const std::vector<MeshPoint>& path,
                                      const SplitOptions& options = {});

/// Splits `mesh` along several paths at once (e.g. the pieces of a plane
/// section), as split_mesh_along_path() does for one: a segment joins
/// consecutive points of one path only. Points of different paths that
/// fall within the snapping distance of each other become one vertex;
/// segments of different paths must not cross inside a face.
/// \throw as split_mesh_along_path(), naming the path and its point.
SplitMeshResult split_mesh_along_paths(const TriMesh& mesh, const std::vector<std::vector<MeshPoint>>& paths,
                                       const SplitOptions& options = {});

/// Carries a per-vertex scalar of the input mesh over to the split mesh
/// (copied for old vertices, linearly interpolated for new ones, which is
/// exact for the piecewise-linear field).
/// \throw InvalidInput when values.size() != split.original_num_vertices.
std::vector<double> carry_vertex_scalar(const TriMesh& original, const SplitMeshResult& split,
                                        const std::vector<double>& values);

}  // namespace knitforge
