#pragma once
/// \file mesh_point.h
/// MeshPoint: a point on a triangle mesh given combinatorially — a mesh
/// vertex, a point on a mesh edge (edge (v0, v1) at `ratio`, the seed's
/// (e_i0, e_i1, r_i) of Alg. 2.1/2.2), or a point inside a face (barycentric
/// coordinates). Isocurves (isocurves.h) produce vertex and edge points; mesh
/// splitting (split_mesh_along_path.h) consumes all three kinds.
///
/// The fields v0, v1, ratio mean the same as in GeodesicPathPoint
/// (geodesic_path.h); a GeodesicPathPoint p converts as
/// `p.is_face_point() ? MeshPoint::in_face(p.point.face, {bary}) :
/// MeshPoint::on_edge(p.v0, p.v1, p.ratio)`, and a SurfacePoint of
/// geodesic_source.h (face + barycentric coordinates with exact zeros on
/// edges) as MeshPoint::in_face(): split_mesh_along_path() moves face points
/// with (near-)zero coordinates onto the edge or vertex.

#include <array>
#include <vector>

#include "knitforge/geometry/tri_mesh.h"
#include "knitforge/geometry/vec.h"

namespace knitforge {

/// A point on a TriMesh.
///
/// - vertex point: `face < 0`, `v0 == v1` (ratio is ignored);
/// - edge point:   `face < 0`, `v0 != v1`, position (1 - ratio) p[v0] +
///                 ratio p[v1], ratio in [0, 1] ((v0, v1) must be a mesh edge);
/// - face point:   `face >= 0`, position bary[0] p[a] + bary[1] p[b] +
///                 bary[2] p[c] for faces[face] = {a, b, c} (v0, v1, ratio
///                 ignored).
struct MeshPoint {
  int v0 = -1;
  int v1 = -1;
  double ratio = 0.0;
  int face = -1;
  std::array<double, 3> bary{0.0, 0.0, 0.0};

  static MeshPoint at_vertex(int v) { return MeshPoint{v, v, 0.0, -1, {0.0, 0.0, 0.0}}; }
  static MeshPoint on_edge(int a, int b, double ratio) {
    return MeshPoint{a, b, ratio, -1, {0.0, 0.0, 0.0}};
  }
  static MeshPoint in_face(int f, const std::array<double, 3>& barycentric) {
    return MeshPoint{-1, -1, 0.0, f, barycentric};
  }

  bool is_vertex() const { return face < 0 && v0 == v1; }
  bool is_edge() const { return face < 0 && v0 != v1; }
  bool is_face() const { return face >= 0; }
};

/// 3D position of p on `mesh` (mm).
/// \pre the indices of p are valid for `mesh` (not checked).
inline Vec3 mesh_point_position(const TriMesh& mesh, const MeshPoint& p) {
  if (p.is_face()) {
    const auto& t = mesh.faces[p.face];
    return p.bary[0] * mesh.vertices[t[0]] + p.bary[1] * mesh.vertices[t[1]] +
           p.bary[2] * mesh.vertices[t[2]];
  }
  if (p.v0 == p.v1) return mesh.vertices[p.v0];
  return (1.0 - p.ratio) * mesh.vertices[p.v0] + p.ratio * mesh.vertices[p.v1];
}

/// Linear interpolation of a per-vertex scalar at p (the piecewise-linear
/// field's value there).
/// \pre values.size() >= mesh.num_vertices() and valid indices (not checked).
inline double mesh_point_value(const TriMesh& mesh, const std::vector<double>& values,
                             const MeshPoint& p) {
  if (p.is_face()) {
    const auto& t = mesh.faces[p.face];
    return p.bary[0] * values[t[0]] + p.bary[1] * values[t[1]] + p.bary[2] * values[t[2]];
  }
  if (p.v0 == p.v1) return values[p.v0];
  return (1.0 - p.ratio) * values[p.v0] + p.ratio * values[p.v1];
}

}  // namespace knitforge
