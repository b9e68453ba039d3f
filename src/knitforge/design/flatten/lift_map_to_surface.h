#pragma once
/// \file lift_map_to_surface.h
/// The stitch mesh of a rasterised pattern placed on the 3D target (seed
/// §2.3.2, last paragraph: "convert a 2D knitting map to a 3D stitch mesh and
/// align it with the target shape"): the map's stitch mesh topology
/// (map_to_stitch_mesh_topology()); each stitch corner has its point of the
/// pattern (its grid corner at RasterizedPattern::origin + column sw,
/// pattern row sh, the pattern row from cell_pattern_row, so a band's
/// stitches lie at their pattern rows; an apex at the middle of the two grid
/// corners it merges), located in the 2D pattern triangles and mapped to 3D
/// with the same barycentric coordinates on the cut mesh. Points outside the
/// pattern (long rows, row extensions, corners next to a dart's wedge) are
/// mapped by the closest pattern triangle's affine map extended to them
/// (OutsidePattern::Extend: clamping them to the closest boundary point
/// collapsed whole stitches of the long rows and row ends to zero area, which
/// a simulation of the design cannot start from). A vertex goes to the mean
/// of its stitch corners' 3D points. Averaging in 3D, not in the pattern,
/// is what closes a dart: the vertex merged across a dart's Collapsed wedge
/// has its corners on the wedge's two legs, which the cut mesh maps to the
/// same seam, while the middle of the wedge lifts to a point on one leg far
/// from both (before 2026-12-02 that stretched the stitches along the
/// hemisphere's darts to up to 5.3 times their size).
#include <array>
#include <vector>
#include "knitforge/core/knit_params.h"
#include "knitforge/core/stitch_mesh.h"
#include "knitforge/design/flatten/rasterize_pattern.h"
#include "knitforge/geometry/tri_mesh.h"

namespace knitforge {

/// What pattern_points_to_surface() does with a point outside the pattern.
enum class OutsidePattern {
  Closest,  ///< the 3D point of the closest pattern point (on the boundary)
  /// the closest pattern triangle's affine map extended to the point (off
  /// the surface, in that triangle's plane): distinct points outside stay
  /// distinct instead of collapsing onto the boundary
  Extend,
};

/// 3D positions (mm) of 2D pattern points: each point is located in the
/// pattern uv of mesh and mapped with its barycentric coordinates; a point
/// outside is mapped as `outside` says.
/// \throw InvalidInput when uv has the wrong size or the mesh has no
///        non-degenerate pattern triangle.
std::vector<Vec3> pattern_points_to_surface(const TriMesh& mesh, const std::vector<Vec2>& uv,
                                            const std::vector<Vec2>& points,
                                            OutsidePattern outside = OutsidePattern::Closest);

/// Per stitch of sm (the topology of raster.map), its corners' pattern
/// points (mm; corners() entries used), as in the file comment.
/// \throw InvalidInput when a stitch's course / wale lies outside the map.
std::vector<std::array<Vec2, 4>> stitch_corner_pattern_points(const RasterizedPattern& raster,
                                                               const StitchMesh& sm, const KnitParams& params);

/// The stitch mesh of `raster.map` with its vertices on the surface.
/// \throw InvalidInput as map_to_stitch_mesh_topology() and
///        pattern_points_to_surface().
StitchMesh lift_map_to_surface(const RasterizedPattern& raster, const TriMesh& mesh,
                               const std::vector<Vec2>& uv, const KnitParams& params);

}  // namespace knitforge
