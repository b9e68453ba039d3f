#pragma once
/// \file tube_crown.h
/// Closed tubes (docs/tubes.md, "Closed tubes"; issue #15 item 4): a
/// surface with ONE boundary loop (a disk: a beanie, a sock's toe, a
/// mitten's top) is knitted in the round from its rim to its crown, where
/// the tube is closed by a seam across the top.
///
/// The crown is the point farthest from the rim (the exact geodesic
/// distance d from the rim, geometry/geodesic_distance.h). Why geodesic
/// distance and not a harmonic field with a point value: a harmonic
/// function cannot be pinned at one vertex (its level sets shrink to a
/// logarithmic spike there), while d is the distance a knitter walks from
/// the rim, and its maximum is where the rounds run out. The small cap
/// d > max d - rho (rho = crown_length / 2 pi: the circle of the last
/// round's length) is cut off exactly along that level
/// (clip_mesh_by_field.h), which leaves an annulus: the tube route's field
/// (tube_field.h, harmonic, 0 on the rim and 1 on the crown ring, no
/// interior critical point) then gives rounds that each go once round the
/// crown, and the last round is the crown ring, about crown_length long.
/// The cut-off cap (about pi rho^2, some 140 mm² for 12 stitches of 3.5 mm)
/// is what the closing seam gathers.
///
/// One crown only: when the superlevel set {d >= t} falls into several
/// pieces for a t between half the largest distance and max d - rho (two
/// peaks: a mitten with its thumb, a two-toed sock), the surface is refused
/// with the number of crowns and what to do.

#include <string>

#include "knitforge/geometry/tri_mesh.h"

namespace knitforge {

/// A disk cut open at its crown.
struct TubeCrown {
  TriMesh annulus;          ///< the surface without the crown cap: two boundary loops
  Vec3 crown;               ///< the vertex farthest from the rim (mm)
  double rim_to_crown = 0;  ///< its geodesic distance from the rim (mm)
  double cap_radius = 0;    ///< rho: the geodesic depth of the cap cut off (mm)
  double cap_area = 0;      ///< area cut off (mm^2)
};

/// Cuts the crown cap of `disk` (see the file comment); `crown_length` (mm)
/// is the length the last round should have (crown stitches x sw).
/// \throw InvalidInput when `disk` is not one manifold piece with one
///        boundary loop and genus 0, it is too small for the cap (the crown
///        lies within 2 rho of the rim), or it has several crowns (the
///        message counts them and says what to do).
TubeCrown cut_crown(const TriMesh& disk, double crown_length, const std::string& what);

}  // namespace knitforge
