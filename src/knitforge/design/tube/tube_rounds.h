#pragma once
/// \file tube_rounds.h
/// The rounds of a tube (docs/tubes.md, "Design"): the closed isocurves of
/// the tube field (tube_field.h) at the round levels, as closed polylines
/// on the surface, all oriented the knitting way and all starting at the
/// seam.
///
/// Orientation: a round runs to the right of a stitch seen from outside
/// (the side the surface normal points to) with later rounds above, i.e.
/// along grad u x n. Round 0 is the start loop (Halfedges::boundary_loops()
/// keeps the surface on its left, which is that direction at the start rim);
/// every later round is turned to agree with the one before it (the
/// vector areas sum p_i x p_(i+1) of two neighbouring rounds point the
/// same way), the end loop included.
///
/// Seam: round 0 starts at its vertex of smallest x (then y, z); every later
/// round at its point nearest to the start of the round before it, so the
/// seam (and the left fold of the flattened tube) follows the tube.

#include <optional>
#include <vector>

#include "knitforge/design/tube/tube_field.h"
#include "knitforge/geometry/tri_mesh.h"
#include "knitforge/geometry/vec.h"

namespace knitforge {

/// One closed round: points in knitting order from the seam (the closing
/// segment back to points[0] is implied).
struct RoundCurve {
  std::vector<Vec3> points;
  double length = 0.0;  ///< mm, closing segment included
};

/// The rounds at `levels` (levels.front() = 0 is the start loop,
/// levels.back() = 1 the end loop). With `start`, round 0 starts at its
/// point nearest to it instead of at its smallest x (the short-row route
/// moves the seam to the inside of a bend, tube_short_rows.h).
/// \throw InvalidInput when a level is not one closed loop (names it).
std::vector<RoundCurve> tube_round_curves(const TriMesh& mesh, const TubeField& field,
                                          const std::vector<double>& levels,
                                          const std::optional<Vec3>& start = std::nullopt);

/// The point at arc length f * length from the round's start (f in [0, 1],
/// taken modulo 1).
Vec3 round_point_at(const RoundCurve& round, double f);

/// `count` points on the closed round: `front` of them evenly spaced (by arc
/// length) on the first half of the round, from its start, the others on the
/// second half. points()[0] is the round's start; point i begins interval i.
/// \pre 1 <= front < count, round.points.size() >= 2.
std::vector<Vec3> sample_round(const RoundCurve& round, int count, int front);

}  // namespace knitforge
