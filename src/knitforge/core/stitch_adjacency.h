#pragma once
/// \file stitch_adjacency.h
/// Neighbour and knitting-order queries on a StitchMesh (seed §1.2.1: "it is
/// easy to find the next stitch of f taking advantage of the half-edge data
/// structure").
///
/// Neighbours are indexed by the Side of the stitch they lie across. Two
/// stitches in the same course meet across Left/Right sides, two in the same
/// wale across Bottom/Top sides. The side the neighbour sees is kept too, so
/// a mismatched pairing (my Right edge is your Top edge) can be reported by the
/// knittability checker instead of being silently accepted.

#include <array>
#include <vector>

#include "knitforge/core/stitch_mesh.h"
#include "knitforge/geometry/halfedges.h"

namespace knitforge {

class StitchAdjacency {
 public:
  /// Builds the half-edge connectivity of `mesh` and the side table.
  /// \throw TopologyError when the mesh is not an oriented edge-manifold
  ///        polygon mesh, or a stitch has an invalid corner list.
  explicit StitchAdjacency(const StitchMesh& mesh);

  const Halfedges& halfedges() const { return he_; }
  int num_stitches() const { return static_cast<int>(nb_.size() / 4); }

  /// The stitch across side `side` of stitch s, or -1 (boundary, or the type
  /// has no such side).
  int neighbor(int s, Side side) const { return nb_[4 * s + static_cast<int>(side)]; }
  /// The side of neighbor(s, side) on which s lies (meaningful only when the
  /// neighbour exists). For a well-formed mesh it is opposite_side(side).
  Side neighbor_side(int s, Side side) const { return nb_side_[4 * s + static_cast<int>(side)]; }

  /// Neighbour in the same course after s in knitting order (the Right
  /// neighbour when s is knitted left to right, else the Left one), or -1.
  int next_in_course(int s) const;
  /// Neighbour in the same course before s in knitting order, or -1.
  int previous_in_course(int s) const;
  /// The stitch knitted after s: next_in_course(s) when it exists, otherwise
  /// the Top neighbour when that one starts its course (the yarn turns and
  /// goes up); -1 when s is the last stitch (or the one-stroke order breaks).
  int next_stitch(int s) const;
  /// The stitch knitted before s (inverse of next_stitch), or -1.
  int previous_stitch(int s) const;

  /// True when vertex v is on the mesh boundary.
  bool is_boundary_vertex(int v) const { return he_.is_boundary_vertex(v); }

 private:
  const StitchMesh* mesh_;
  Halfedges he_;
  std::vector<int> nb_;
  std::vector<Side> nb_side_;
};

}  // namespace knitforge
