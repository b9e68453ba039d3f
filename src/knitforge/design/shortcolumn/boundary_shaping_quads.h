#pragma once
/// \file boundary_shaping_quads.h
/// The first post-processing operator of seed §3.2.3 / §3.3.4 (L1425:
/// "when their apex vertices are located at the boundary of a patch, they
/// need to convert into quadrangles to reflect the real stitch that can be
/// formed at the boundary") for the short-column stitches: an Increase or
/// Decrease whose apex lies on the fabric's boundary (a short column forked
/// from a wale that no later strip covers on that side, e.g. next to the
/// last wale) becomes a regular stitch at the edge of its course, i.e. an
/// outside increase or decrease (the row is one stitch longer or shorter
/// than its neighbour there).
///
/// The apex A keeps its index on the side where the triangle has a
/// neighbour across an edge at A; the other corner is a new vertex A* = A +
/// (the triangle's far edge), so the quad is a parallelogram on that edge:
/// Increase (A, TR, TL) -> Knit (A, A*, TR, TL) with A* = A + TR - TL (or
/// (A*, A, TR, TL), A* = A + TL - TR, when only its right side has a
/// neighbour); Decrease (BL, BR, A) -> Knit (BL, BR, A*, A), A* = A + BR - BL
/// (or (BL, BR, A, A*), A* = A + BL - BR). A triangle with neighbours on both
/// sides of A (the boundary passes A between other stitches: a short column
/// that ends (starts) where the fabric ends above (below) it) gets A split in
/// two, A - e/4 for the stitches on its left and A + e/4 for those on its
/// right (e its far edge, left to right), and becomes the quad between them:
/// a wale that ends (starts) at the fabric's edge.

#include "knitforge/core/stitch_mesh.h"

namespace knitforge {

/// Counts of boundary_shaping_quads().
struct BoundaryShapingQuadStats {
  int increases = 0;   ///< Increase triangles made quads
  int decreases = 0;   ///< Decrease triangles made quads
  int split_apexes = 0;  ///< of those, with neighbours on both sides (apex split)
};

/// Converts boundary-apex Increase / Decrease triangles to quads, in place.
/// \throw TopologyError when the mesh is not an oriented manifold.
BoundaryShapingQuadStats boundary_shaping_quads(StitchMesh& mesh);

}  // namespace knitforge
