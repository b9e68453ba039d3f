#pragma once
/// \file apex_spacing.h
/// How far apart the shaping stitches' apexes are (seed §3.2.3): apex
/// diffusion exists to scatter short-row ends instead of letting them line
/// up, so the distance from each apex to its nearest other apex is the
/// direct measure of what it does. Works on any stitch mesh.
///
/// An apex is the apex corner (apex_corner() of core/stitch.h) of a
/// shaping stitch (short-row end, increase, decrease); a vertex that is the
/// apex of several stitches (the two ends of a turning short row meet there)
/// counts once. Distances are straight-line (3D, mm).

#include <vector>

#include "knitforge/core/stitch_mesh.h"
#include "knitforge/evaluate/scalar_stats.h"

namespace knitforge {

struct ApexSpacing {
  std::vector<int> apexes;       ///< apex vertices, increasing
  std::vector<double> nearest;   ///< per apex: distance to the nearest other apex (mm)
  ScalarStats stats;             ///< of `nearest` (count 0 with fewer than two apexes)
};

/// Nearest-neighbour distances between the apexes of `mesh`'s shaping
/// stitches. With fewer than two apexes, `nearest` is empty.
/// \throw TopologyError when a shaping stitch's apex vertex is out of range;
///        InvalidInput when an apex position is not finite.
ApexSpacing apex_spacing(const StitchMesh& mesh);

}  // namespace knitforge
