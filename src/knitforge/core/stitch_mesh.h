#pragma once
/// \file stitch_mesh.h
/// StitchMesh: a manifold polygon mesh whose faces are stitches (seed §1.2.1).
/// Plain data; neighbour and knitting-order queries come from StitchAdjacency
/// (stitch_adjacency.h).

#include <array>
#include <cstdint>
#include <vector>

#include "knitforge/core/stitch.h"
#include "knitforge/geometry/vec.h"

namespace knitforge {

/// One stitch (face) of a stitch mesh.
struct Stitch {
  StitchType type = StitchType::Knit;
  /// Knitting direction: +1 knitted left to right (in the stitch's frame),
  /// -1 right to left.
  int8_t direction = 1;
  /// Corner vertex indices, counter-clockwise from the corner stitch.h gives
  /// for the type; the fourth entry is -1 for triangles.
  std::array<int, 4> v{-1, -1, -1, -1};
  int course = -1;    ///< course (map row) index, -1 when unknown
  int wale = -1;      ///< wale (map column) index, -1 when unknown
  int yarn = 0;       ///< yarn / carrier index (0 = main yarn)
  uint8_t roles = 0;  ///< BoundaryRole flags

  int corners() const { return corner_count(type); }
};

/// A stitch mesh: vertex positions (mm) and stitches.
struct StitchMesh {
  std::vector<Vec3> vertices;
  std::vector<Stitch> stitches;

  int num_vertices() const { return static_cast<int>(vertices.size()); }
  int num_stitches() const { return static_cast<int>(stitches.size()); }
};

/// The apex vertex of a shaping stitch, or -1 for a Knit stitch.
inline int apex_vertex(const Stitch& s) {
  const int k = apex_corner(s.type);
  return k < 0 ? -1 : s.v[k];
}

/// The vertices of a stitch's bottom edge (its two bottom corners; the apex
/// for an Increase, whose bottom side has collapsed).
std::vector<int> bottom_vertices(const Stitch& s);
/// The vertices of a stitch's top edge (the apex for a Decrease).
std::vector<int> top_vertices(const Stitch& s);

/// Centroid of a stitch's corners.
Vec3 stitch_centroid(const StitchMesh& mesh, int stitch);

/// Counts of stitches by type, indexed by StitchType.
std::array<int, kNumStitchTypes> count_stitch_types(const StitchMesh& mesh);

/// Drops the vertices no stitch uses, keeping the order of the others (in
/// place). Returns the number dropped.
int remove_unused_vertices(StitchMesh& mesh);

}  // namespace knitforge
