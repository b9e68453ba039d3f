#pragma once
/// \file lift_map_to_surface.h
/// The stitch mesh of a rasterised pattern placed on the 3D target (seed
/// §2.3.2, last paragraph: "convert a 2D knitting map to a 3D stitch mesh and
/// align it with the target shape"): the map's stitch mesh topology
/// (map_to_stitch_mesh_topology()) has its vertices in the flat map layout;
/// each vertex is moved to its point of the pattern (RasterizedPattern::
/// origin + layout position), located in the 2D pattern triangles, and
/// mapped to 3D with the same barycentric coordinates on the cut mesh.
/// Points outside the pattern (collapsed dart wedges, row extensions) take
/// the closest pattern point.
#include <vector>
#include "knitforge/core/knit_params.h"
#include "knitforge/core/stitch_mesh.h"
#include "knitforge/design/flatten/rasterize_pattern.h"
#include "knitforge/geometry/tri_mesh.h"

namespace knitforge {

/// 3D positions (mm) of 2D pattern points: each point is located in the
/// pattern uv of mesh (closest point when outside) and mapped with its
/// barycentric coordinates.
/// \throw InvalidInput when uv has the wrong size or the mesh has no
///        non-degenerate pattern triangle.
std::vector<Vec3> pattern_points_to_surface(const TriMesh& mesh, const std::vector<Vec2>& uv,
                                            const std::vector<Vec2>& points);

/// The stitch mesh of `raster.map` with its vertices on the surface.
/// \throw InvalidInput as map_to_stitch_mesh_topology() and
///        pattern_points_to_surface().
StitchMesh lift_map_to_surface(const RasterizedPattern& raster, const TriMesh& mesh,
                               const std::vector<Vec2>& uv, const KnitParams& params);

}  // namespace knitforge
