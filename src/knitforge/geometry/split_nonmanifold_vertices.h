#pragma once
/// \file split_nonmanifold_vertices.h
/// Splitting "bow-tie" vertices of a polygon mesh: a vertex whose faces form
/// several fans (faces that follow each other around the vertex across
/// shared edges) gets one copy per fan, so that the parts that only touch
/// at the vertex no longer share it. Used on stitch meshes, where two
/// stitches of different strips can meet at a single wale sample without
/// sharing an edge (they belong to no common course or wale, so nothing
/// about the knitting connects them; the half-edge structure needs them
/// apart).
///
/// Fans: the corners of one vertex are linked when their faces share an
/// edge at that vertex (the same undirected edge (v, w)); each class is a
/// fan. The fan of the vertex's first corner (in face order) keeps the
/// vertex index; every further fan gets a new vertex appended (in order of
/// the vertex, then of the fan's first corner), so vertices that need no
/// split keep their indices and the faces keep their order and corner
/// order. Deterministic. A mesh without bow-tie vertices is returned
/// unchanged (num_split == 0).

#include <span>
#include <vector>

namespace knitforge {

/// The corners after the split.
struct VertexFanSplit {
  /// The faces' corners (same layout as the input face_vertices) with the
  /// copies in place.
  std::vector<int> face_vertices;
  /// For every vertex of the result (the input's num_vertices first, then
  /// the copies), the input vertex it stands for.
  std::vector<int> vertex_origin;
  /// Number of input vertices that were split.
  int num_split = 0;
};

/// Splits every vertex whose faces form more than one fan (see the file
/// comment). Faces are given in compressed form: face f has the vertices
/// face_vertices[face_start[f] .. face_start[f+1]).
/// \throw InvalidInput when face_start is not a valid compressed layout
///        (not starting at 0, decreasing, not ending at face_vertices.size())
///        or a vertex index is outside [0, num_vertices).
VertexFanSplit split_nonmanifold_vertices(int num_vertices, std::span<const int> face_start,
                                          std::span<const int> face_vertices);

}  // namespace knitforge
