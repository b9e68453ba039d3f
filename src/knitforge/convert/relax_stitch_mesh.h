#pragma once
/// \file relax_stitch_mesh.h
/// Relaxed (rest) shape of a stitch mesh: every stitch as close as possible,
/// by a rigid motion, to the ideal shape of its type (seed §1.3.2, eq. 1.1),
/// solved with Shape-Up (geometry/shape_up.h).
///
/// Ideal shapes (in the stitch frame, w = stitch_width, h = stitch_height):
///  - Knit: the w x h rectangle BL(0,0) BR(w,0) TR(w,h) TL(0,h);
///  - ShortRowLeft: the quad with its left side collapsed to the middle of
///    that side: A(0,h/2) BR(w,0) TR(w,h); ShortRowRight: BL(0,0) A(w,h/2) TL(0,h);
///  - Increase: bottom side collapsed to its middle: A(w/2,0) TR(w,h) TL(0,h);
///    Decrease: BL(0,0) BR(w,0) A(w/2,h).
/// Each stitch is weighted by the area of its ideal shape (seed eq. 1.1).
///
/// The z warm-up: Shape-Up treats x, y and z independently, so a flat start
/// stays flat (seed Fig. 1.5c). With `warm_up > 0` the start positions are
/// first displaced in z by a smooth bump over the fabric's xy bounding box,
/// z += warm_up * D * (1 - u^2)(1 - v^2) with u, v in [-1, 1] across the box
/// and D its diagonal, so shaped fabrics relax to 3D (Fig. 1.5d-e). A mesh
/// without shaping stitches gets no warm-up: its flat layout from
/// map_to_stitch_mesh_topology() already has zero energy (the exact
/// rows*h x cols*w rectangle), while quads may hinge along whole courses or
/// wales at no cost, so a bumped start would not necessarily come back flat.
///
/// The ideal shapes do not tile exactly around shaping stitches (a short-row
/// end's bottom side is sqrt(w^2 + h^2/4), its neighbour's top side w), so
/// the relaxed edges there differ from ideal by up to ~15%; elsewhere by much
/// less (docs/convert.md gives measured numbers).

#include <vector>

#include "knitforge/core/knit_params.h"
#include "knitforge/core/stitch_mesh.h"

namespace knitforge {

struct RelaxOptions {
  int max_iterations = 60;  ///< Shape-Up iterations (linear solves) at most
  /// Stop when the relative energy decrease of one iteration is below this.
  double tolerance = 1e-6;
  /// Anderson acceleration depth of Shape-Up (0 = plain local/global steps).
  int anderson_depth = 5;
  /// z warm-up amplitude as a fraction of the xy bounding-box diagonal;
  /// 0 switches the warm-up off (relax from the mesh's geometry as it is).
  double warm_up = 0.1;
  /// Bending stiffness (0 = none, the seed's eq. 1.1 alone). With a weight
  /// b > 0, every two stitches that share an edge also form a hinge
  /// polygon whose target is their two ideal shapes laid flat side by side
  /// (joined along the shared edge), weighted b x their mean ideal area: a
  /// fold of angle theta at the shared edge then costs about b theta^2 per
  /// pair, a discrete bending energy. Without it the rest shape of a shaped
  /// fabric is not unique: quads hinge along whole courses or wales at no
  /// cost, and long relaxations drift along such folds.
  double bending = 0.0;
};

struct RelaxResult {
  StitchMesh mesh;              ///< the input with relaxed vertex positions (mm)
  /// eq. 1.1 energy (mm^4): energy[0] at the start (after the warm-up),
  /// energy[k] after k iterations; non-increasing.
  std::vector<double> energy;
  int iterations = 0;           ///< iterations run
  bool converged = false;       ///< tolerance reached before max_iterations
};

/// The ideal corner positions of a stitch type in its own frame (z = 0),
/// corner order as in core/stitch.h; corner_count(type) entries.
///
/// A Knit stitch is the w x h rectangle. The shaping stitches are the
/// isosceles triangles of seed §3.2.3 / §3.3: every side a triangle shares
/// with a neighbour keeps the neighbour's length, so a short-row end has the
/// two course sides of length w meeting at the apex over its wale side of
/// length h (edges w, w, h), and an increase / decrease has its two wale
/// sides of length h meeting at the apex over its course side of length w
/// (edges h, h, w). When h <= w / 2 an increase/decrease cannot have legs of
/// length h; its apex then lies on the opposite side (a flat triangle is
/// avoided by keeping a height of h / 2).
std::vector<Vec3> ideal_stitch_shape(StitchType type, const KnitParams& params);

/// Relaxes `mesh` from its current vertex positions (after the optional
/// warm-up) and returns the relaxed mesh with the energy history.
/// The smallest vertex index of each connected part is held fixed (for
/// meshes from map_to_stitch_mesh_topology(): the first corner of stitch 0,
/// the bottom-left corner of the fabric), so a flat rectangle stays in place.
/// \pre mesh is an oriented manifold stitch mesh (StitchAdjacency accepts it);
///      params lengths > 0.
/// \throw InvalidInput for an empty mesh, non-finite vertex positions, bad
///        params or options; TopologyError for invalid stitches (vertex index
///        out of range, repeated corner); SolverError if the solve fails.
RelaxResult relax_stitch_mesh(const StitchMesh& mesh, const KnitParams& params,
                              const RelaxOptions& options = {});

}  // namespace knitforge
