#pragma once
/// \file loop_tessellation.h
/// Graph-based tessellation of the band between two closed polyline loops
/// (seed §2.C.2, Fig. 2.12, eq. 2.6; a simplified Fuchs et al. 1977): the
/// loops A = (a_0..a_{m-1}) and B = (b_0..b_{n-1}) are cut open at a start
/// bridge a_{i0} b_{j0} and the band is filled with triangles of two kinds,
///  - A-advance: a_i a_{i+1} b_j (adds the bridge a_{i+1} b_j),
///  - B-advance: a_i b_{j+1} b_j (adds the bridge a_i b_{j+1}),
/// chosen by a shortest path through the grid of bridges (i, j) from
/// (i0, j0) to (i0 + m, j0 + n), solved by dynamic programming. The cost of a
/// tessellation is the sum of the costs of its m + n distinct bridges (seed:
/// the bridge lengths) or, optionally, the sum of the triangle areas.
///
/// Start alignment: every tessellation contains a bridge at each loop
/// vertex, so fixing vertex 0 of the longer loop and trying every start on
/// the shorter loop finds the global optimum; this is done while the work
/// (shorter² x longer) stays within `max_exhaustive_work`, otherwise the
/// seed's rule is used (start at the shortest bridge, argmin |a_i - b_j|).
///
/// Orientation: both loops must run in the same direction (seed). Every
/// triangle traverses A's edges forwards (a_i -> a_{i+1}) and B's edges
/// backwards (b_{j+1} -> b_j), and the bridges it shares with its
/// neighbours in opposite directions, so the band is an oriented annulus. To
/// glue the band to a mesh whose boundary loop L runs with the mesh on its
/// left, pass A = reverse(L).

#include <array>
#include <span>
#include <vector>

#include "knitforge/geometry/vec.h"

namespace knitforge {

/// What a tessellation minimises.
enum class LoopTessellationCost {
  BridgeLength,  ///< sum of the bridge lengths (seed eq. 2.6), default
  TriangleArea,  ///< sum of the triangle areas (a minimal-area band)
};

/// Options of loop_tessellation().
struct LoopTessellationOptions {
  LoopTessellationCost cost = LoopTessellationCost::BridgeLength;
  /// Try every start alignment while (shorter loop size)² x (longer loop
  /// size) is at most this; above it, use the seed's shortest-bridge rule.
  double max_exhaustive_work = 5.0e7;
};

/// A band between two loops. Triangle vertex indices: 0..m-1 are a_0..a_{m-1},
/// m..m+n-1 are b_0..b_{n-1}.
struct LoopTessellation {
  std::vector<std::array<int, 3>> triangles;  ///< m + n triangles
  double cost = 0.0;                          ///< the minimised objective (mm or mm²)
  int start_a = 0;                            ///< start bridge a_{start_a} b_{start_b}
  int start_b = 0;
  bool exhaustive = true;  ///< every start alignment was tried
};

/// The optimal band between loops a and b (see the file comment).
/// \pre a.size() >= 3, b.size() >= 3, finite coordinates.
/// \throw InvalidInput when a loop is too short or a coordinate is not finite.
LoopTessellation loop_tessellation(std::span<const Vec3> a, std::span<const Vec3> b,
                                   const LoopTessellationOptions& options = {});

/// The cost (as defined by `cost`) of a given band `triangles` between a and b
/// (indices as in LoopTessellation): the sum over its distinct bridges of
/// their lengths, or the sum of its triangle areas. Used to compare
/// tessellations.
double loop_tessellation_cost(std::span<const Vec3> a, std::span<const Vec3> b,
                              const std::vector<std::array<int, 3>>& triangles,
                              LoopTessellationCost cost = LoopTessellationCost::BridgeLength);

}  // namespace knitforge
