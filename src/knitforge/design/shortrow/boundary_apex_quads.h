#pragma once
/// \file boundary_apex_quads.h
/// First post-processing operator of seed §3.2.3 (Fig. 3.5(a)): short-row-end
/// triangles whose apex lies on the boundary of the patch become quads —
/// the machine knits regular stitches there, since a "short row" that
/// reaches the edge is not short.
///
/// Around a boundary apex p, a maximal run of short-row-end triangles of one
/// type that follow each other across edges through p (a fan) with far-side
/// chain q_0 .. q_k (bottom to top) becomes k quads; p is split into copies
/// p_0 .. p_k, so that quad i has the corners q_i, q_{i+1} on the wale side
/// and p_i, p_{i+1} on the boundary side. The copy at the end of the fan
/// where p still meets other stitches (by an edge) keeps p's index; the
/// others are new vertices at p + (q_i - q_keep), i.e. the chain translated
/// through p. The quads keep the triangles' courses and directions.
/// Fans whose two ends both meet other stitches are left as they are (the
/// knittability checker reports them as boundary-apex).

#include "knitforge/core/stitch_mesh.h"

namespace knitforge {

/// Counts of boundary_apex_quads().
struct BoundaryApexQuadStats {
  int fans = 0;        ///< fans turned into quads
  int triangles = 0;   ///< triangles turned into quads
  int left_alone = 0;  ///< fans left as triangles (see the file comment)
};

/// Replaces boundary-apex fans of short-row-end triangles by quads, in place.
/// \throw TopologyError when the mesh is not an oriented manifold.
BoundaryApexQuadStats boundary_apex_quads(StitchMesh& mesh);

}  // namespace knitforge
