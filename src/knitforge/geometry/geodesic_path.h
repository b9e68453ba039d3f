#pragma once
/// \file geodesic_path.h
/// Exact shortest paths on a triangle mesh (seed §3.2.1): from a surface
/// point to the boundary (the cut that opens a closed wale curve, from the
/// local maximum of the field inside it) or to another surface point. The
/// path is returned as the sequence of its vertex and edge crossings, in the
/// form the mesh splitting of seed §2.B takes (a path vertex divides edge
/// (v0, v1) at ratio r; v0 == v1 when it passes through a vertex).
///
/// Method: the exact window propagation of geodesic_distance() from the
/// start point, then the back-trace of the straight rays through the unfolded
/// faces (windows remember their parents). The path is a polyhedral geodesic:
/// straight inside faces and across edges, bending only at saddle or boundary
/// vertices.

#include <vector>

#include "knitforge/geometry/geodesic_source.h"
#include "knitforge/geometry/tri_mesh.h"
#include "knitforge/geometry/vec.h"

namespace knitforge {

/// One point of a surface path.
struct GeodesicPathPoint {
  /// The point divides edge (v0, v1) at `ratio`: (1 - ratio) x_v0 + ratio x_v1,
  /// 0 < ratio < 1. At a vertex v0 == v1 and ratio = 0. Inside a face (only
  /// the end points of a path can be) v0 == v1 == -1 and `point` tells where.
  int v0 = -1;
  int v1 = -1;
  double ratio = 0.0;
  SurfacePoint point;            ///< the same point as face + barycentric coordinates (always set)
  Vec3 position = Vec3::Zero();  ///< mm

  bool is_vertex() const { return v0 >= 0 && v0 == v1; }
  bool is_edge_point() const { return v0 >= 0 && v0 != v1; }
  bool is_face_point() const { return v0 < 0; }
};

/// A shortest path on the surface.
struct GeodesicPath {
  std::vector<GeodesicPathPoint> points;  ///< from the start to the end; consecutive points share a face
  double length = 0.0;                    ///< mm, the sum of the straight pieces
};

/// The shortest path on the surface from `start` to the boundary (to the
/// closest boundary point, which may lie inside a boundary edge).
/// \throw InvalidInput when `start` is not a valid surface point (face out of
///        range, barycentric coordinates negative or not summing to 1);
///        TopologyError when the mesh has no boundary reachable from `start`
///        (closed surface) or is not a valid manifold mesh.
GeodesicPath geodesic_path_to_boundary(const TriMesh& mesh, const SurfacePoint& start);

/// The shortest path on the surface from `source` (its polylines, as the
/// geodesic field's source) to the nearest of the vertices `targets`
/// (e.g. the vertices of the other boundary loops, for a seam between two
/// loops): from a source point (first) to that target vertex (last). Ties
/// go to the target listed first.
/// \throw InvalidInput for an empty source or target list, an invalid
///        source point or a target out of range; TopologyError when no
///        target is reachable from the source.
GeodesicPath geodesic_path_from_source(const TriMesh& mesh, const GeodesicSource& source,
                                       const std::vector<int>& targets);

/// The shortest path on the surface from `from` to `to`.
/// \throw InvalidInput for an invalid surface point; TopologyError when `to`
///        is not reachable from `from` (different components).
GeodesicPath geodesic_path(const TriMesh& mesh, const SurfacePoint& from, const SurfacePoint& to);

}  // namespace knitforge
