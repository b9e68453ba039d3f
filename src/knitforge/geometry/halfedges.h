#pragma once
/// \file halfedges.h
/// Half-edge connectivity of a polygon mesh (triangles, quads, mixed), shared
/// by TriMesh (input surfaces) and StitchMesh (stitches).
///
/// Half-edges are the face corners: half-edge h = face_start(f) + k runs from
/// the k-th vertex of face f to the (k+1)-th. A boundary edge has one
/// half-edge whose opposite() is -1; no separate boundary half-edges exist.

#include <array>
#include <span>
#include <vector>

namespace knitforge {

/// Connectivity of an oriented, edge-manifold polygon mesh.
class Halfedges {
 public:
  Halfedges() = default;

  int num_vertices() const { return num_vertices_; }
  int num_faces() const { return static_cast<int>(face_start_.size()) - 1; }
  int num_halfedges() const { return static_cast<int>(to_.size()); }
  /// Number of undirected edges (interior edges count once).
  int num_edges() const { return num_edges_; }

  int face_start(int f) const { return face_start_[f]; }
  int face_size(int f) const { return face_start_[f + 1] - face_start_[f]; }
  /// The half-edge leaving the k-th vertex of face f.
  int halfedge(int f, int k) const { return face_start_[f] + k; }

  int from(int h) const { return from_[h]; }
  int to(int h) const { return to_[h]; }
  int face(int h) const { return face_[h]; }
  /// Index of h inside its face (0 for the half-edge leaving the first vertex).
  int corner(int h) const { return h - face_start_[face_[h]]; }
  int next(int h) const { return h + 1 < face_start_[face_[h] + 1] ? h + 1 : face_start_[face_[h]]; }
  int prev(int h) const { return h > face_start_[face_[h]] ? h - 1 : face_start_[face_[h] + 1] - 1; }
  /// The half-edge of the neighbouring face on the same edge, or -1 on the boundary.
  int opposite(int h) const { return opposite_[h]; }
  bool is_boundary_halfedge(int h) const { return opposite_[h] < 0; }
  /// Undirected edge index of h, in [0, num_edges()).
  int edge(int h) const { return edge_[h]; }

  /// The face across edge k of face f (the edge leaving its k-th vertex), or -1.
  int neighbor(int f, int k) const {
    const int o = opposite_[face_start_[f] + k];
    return o < 0 ? -1 : face_[o];
  }

  /// True when vertex v lies on a boundary edge.
  bool is_boundary_vertex(int v) const { return vertex_on_boundary_[v] != 0; }
  /// True when no face uses vertex v.
  bool is_isolated_vertex(int v) const { return vertex_halfedge_[v] < 0; }
  /// Faces around vertex v, ordered around it (one fan; manifold vertices only).
  std::vector<int> vertex_faces(int v) const;
  /// Vertices adjacent to v by an edge, in the same order as vertex_faces().
  std::vector<int> vertex_neighbors(int v) const;

  /// Boundary loops as vertex cycles, each oriented along its boundary
  /// half-edges (so the mesh lies to the left). Sorted by their smallest vertex.
  std::vector<std::vector<int>> boundary_loops() const;

  /// Connected components of faces (via shared edges): component id per face.
  std::vector<int> face_components(int* count = nullptr) const;

 private:
  friend Halfedges build_halfedges(int, std::span<const int>, std::span<const int>);
  int num_vertices_ = 0;
  int num_edges_ = 0;
  std::vector<int> face_start_{0};
  std::vector<int> from_, to_, face_, opposite_, edge_;
  std::vector<int> vertex_halfedge_;  ///< a half-edge leaving v (a boundary one if any), -1 if isolated
  std::vector<char> vertex_on_boundary_;
};

/// Builds the connectivity of a polygon mesh given in compressed form: face f
/// has vertices face_vertices[face_start[f] .. face_start[f+1]).
/// \pre face_start.size() == num_faces + 1, face_start[0] == 0.
/// \throw TopologyError naming the faces and vertices involved when a face has
///        fewer than 3 or repeated vertices or an index out of range, an edge
///        is used by more than two faces, two faces use an edge in the same
///        direction (inconsistent orientation), or a vertex is non-manifold
///        (its faces form more than one fan).
Halfedges build_halfedges(int num_vertices, std::span<const int> face_start,
                          std::span<const int> face_vertices);

/// Convenience for triangle meshes.
Halfedges build_halfedges(int num_vertices, const std::vector<std::array<int, 3>>& triangles);

}  // namespace knitforge
