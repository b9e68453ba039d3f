#pragma once
/// \file stitch_mesh_to_yarn.h
/// Stitch mesh -> yarn model (seed §1.3.3): a canonical polyline per stitch
/// type is deformed into each stitch face and the pieces are joined in
/// knitting order into one continuous polyline per yarn.
///
/// Canonical frame. Each canonical yarn is designed in the stitch's unit
/// frame: x across the stitch (0 = left side, 1 = right side), y up the wale
/// (0 = bottom side, 1 = top side), z out of the fabric towards its front
/// (technical face) in units of the yarn radius. A regular (Knit) loop
/// enters at the left side at sinker level (y = 0.04, behind), dips behind
/// the head of the loop below, its two legs rise in front of that head
/// (z = +1), its head reaches y = 1.3 above the top side behind the next
/// course's legs (z = -1), and it leaves at the right side, so neighbouring
/// loops and courses interlock. The loop of a stitch knitted right to left
/// is the mirror image (x -> 1 - x): it enters on the right and leaves on
/// the left, so the yarn always runs in knitting order.
///
/// Shaping stitches reuse the loop inside a quad whose collapsed side is
/// their apex (stitch.h): a short-row end's loop is squeezed into the apex,
/// so the yarn runs into the apex and comes back out of it into the next
/// course (the turn of a short row); an increase's loop grows out of its
/// bottom apex (a wale splits off) and a decrease's loop closes into its
/// top apex (two wales merge). The canonical points of a triangle are stored
/// in its canonical triangle (canonical_corners) and deformed with
/// barycentric coordinates, which makes the collapse exact.
///
/// Boundary roles change the loop: cast-on loops have no loop below to dip
/// behind (their feet stay in the fabric plane); bind-off loops close just
/// above the top side, leaning into the next stitch of the chain; an outside
/// increase has a flat foot on its open side; an outside decrease's head
/// leans towards its inner neighbour (it is moved onto that needle).
///
/// Deformation (seed eq. 1.2): T(p) = sum_i w_i(x, y) t_i + z * r * n, with
/// w bilinear for quads (corners BL, BR, TR, TL at (0,0), (1,0), (1,1),
/// (0,1)) and barycentric for triangles, t_i the stitch's corner positions,
/// n the unit facet normal (CCW corners in the stitch frame, so n points to
/// the front) and r the yarn radius. T(s_i) = t_i for the canonical corners.

#include <array>
#include <span>

#include "knitforge/core/knit_params.h"
#include "knitforge/core/stitch_mesh.h"
#include "knitforge/core/yarn_model.h"

namespace knitforge {

struct YarnOptions {
  /// Yarn radius (mm): scales the out-of-plane offsets of the canonical
  /// loops. 0 = automatic, 0.12 * KnitParams::stitch_width (0.42 mm for the
  /// default 3.5 mm stitch).
  double yarn_radius = 0.0;
};

/// One canonical yarn point: position in the stitch type's canonical frame
/// (x, y as in the file comment; for triangles inside/around the canonical
/// triangle) and z in yarn radii.
using CanonicalPoint = Vec3;

/// The canonical corners s_i of a stitch type in its unit frame, in the
/// stitch's corner order (stitch.h): Knit (0,0) (1,0) (1,1) (0,1);
/// ShortRowLeft A=(0,0.5) (1,0) (1,1); ShortRowRight (0,0) A=(1,0.5) (0,1);
/// Increase A=(0.5,0) (1,1) (0,1); Decrease (0,0) (1,0) A=(0.5,1).
/// Returns corner_count(t) entries.
std::span<const Vec2> canonical_corners(StitchType t);

/// Deforms a canonical point into stitch `s` of `mesh` (eq. 1.2): bilinear
/// (quads) or barycentric (triangles) interpolation of the corners plus
/// p.z() * yarn_radius along the unit facet normal.
/// \pre 0 <= s < mesh.num_stitches(), corner indices valid.
Vec3 deform_canonical_point(const StitchMesh& mesh, int s, const CanonicalPoint& p, double yarn_radius);

/// The yarn model of a stitch mesh.
///
/// Stitches are put in the global knitting order (StitchAdjacency::next_stitch
/// from the first stitch, the one without a previous stitch); each yarn id's
/// stitches, in that order, become one polyline: every stitch contributes
/// one contiguous run of vertices tagged with its index, and the last stitch
/// of each yarn also contributes the exit point. Yarns are listed by
/// ascending id. Where a course ends and the yarn turns up into the next,
/// the turning stitch adds a point halfway up its exit side (the selvedge
/// loop; at a short-row end that side is the apex). Consecutive stitches of
/// one yarn that are not mesh
/// neighbours (the yarn was idle in between) are joined by a straight segment.
///
/// Tubes (docs/tubes.md): when every stitch has a predecessor (every course
/// a round, so the order cannot start from adjacency), or stitch 0 has one
/// (the cast-on is a round) and the walk from the stitch without one does
/// not reach every stitch (a tube with short rows: a wedge's first short row
/// has no predecessor by adjacency), the stitches are taken in index order,
/// which is the knitting order of a tube's stitch mesh
/// (map_to_stitch_mesh_topology(), the tube design route); each stitch must
/// then touch the next one.
///
/// \pre the mesh is knittable in one stroke (check_knittability reports no
///      between-row-continuity violation).
/// \throw TopologyError when the mesh is not a manifold stitch mesh or its
///        knitting order does not visit every stitch exactly once (naming the
///        stitch where it breaks).
/// \throw InvalidInput when stitch sizes or the yarn radius are not positive
///        and finite, or a stitch has a negative yarn index.
/// Cost: linear; about 15 vertices per stitch.
YarnModel stitch_mesh_to_yarn(const StitchMesh& mesh, const KnitParams& params, const YarnOptions& opt = {});

}  // namespace knitforge
