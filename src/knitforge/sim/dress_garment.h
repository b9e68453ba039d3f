#pragma once
/// \file dress_garment.h
/// Dressing a body (docs/sim.md, "Dressing a body"). A garment designed on
/// the body's own surface (a design command run on a region of the body,
/// `body region`) has its stitch mesh on that surface, partly inside the
/// body's facets; the contact barrier needs every free vertex strictly
/// outside the body at the start. dress_garment() moves such vertices out:
/// a vertex inside the body, on it, or closer than `clearance_mm` goes to
/// its closest body point c plus clearance_mm along the outward direction
/// there: (p - c) / |p - c| for a vertex outside, the body's angle-weighted
/// pseudo-normal at c (geometry/pseudo_normals.h) for one inside or on it.
/// Outward is where the body's face normals point (a body of `body make`,
/// a scan: its outside; a closed body's inside is then exact), or, for a
/// closed body whose faces point inwards (negative enclosed volume), where
/// they do not. A vertex
/// moved out in a concave place (an armpit, the crook of an elbow) may come
/// near another part: up to kDressPasses passes, after which every vertex
/// moved must lie outside and at least half the clearance from the body.
///
/// Only the start positions move; the garment's rest shape (its stitches'
/// sizes, or the mesh as given) is the model's own, so a garment moved out
/// by a millimetre starts that much stretched and relaxes.

#include <vector>

#include "knitforge/geometry/vec.h"
#include "knitforge/sim/kinematic_body.h"

namespace knitforge {

inline constexpr int kDressPasses = 4;

struct DressOptions {
  double clearance_mm = 1.0;   ///< > 0
  /// A vertex deeper inside the body than this is refused: the garment is
  /// not where the body is (> 0).
  double max_depth_mm = 20.0;
};

struct DressResult {
  std::vector<Vec3> positions;  ///< the garment's vertices, moved out
  int moved = 0;                ///< vertices moved
  int inside = 0;               ///< of them, inside the body (or on it) before
  double largest_move_mm = 0.0;
  double deepest_mm = 0.0;      ///< deepest vertex inside before (0: none)
  int passes = 0;               ///< passes that moved a vertex
};

/// Moves `garment`'s vertices out of `body` (see the file comment); the
/// vertices in `skip` (pins: held where they are) stay.
/// \throw InvalidInput for options out of range, an empty body, a
///        non-finite vertex, an index of `skip` out of range, a vertex deeper than max_depth_mm (naming
///        it and its depth), or a vertex still within half the clearance
///        after the passes (naming it).
DressResult dress_garment(const KinematicBody& body, const std::vector<Vec3>& garment, const std::vector<int>& skip,
                          const DressOptions& options = {});

/// The vertices of `points` that lie inside `body` (its closest point's
/// pseudo-normal points away from them), with their depth (mm), deepest
/// first; for a closed body (is_closed_mesh()) only, else empty: an open
/// body (a plate) has no inside. `skip`: vertices not tested.
/// \throw InvalidInput for a non-finite point or an index of `skip` out of
///        range.
struct InsidePoint {
  int vertex = 0;
  double depth_mm = 0.0;
};
std::vector<InsidePoint> points_inside_body(const KinematicBody& body, const std::vector<Vec3>& points,
                                            const std::vector<int>& skip = {});

}  // namespace knitforge
