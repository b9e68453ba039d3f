#pragma once
/// \file poisson_reconstruct.h
/// A watertight mesh from an oriented point cloud by Poisson
/// surface reconstruction (Kazhdan, Bolitho & Hoppe 2006; the seed's [85]),
/// with CGAL's implementation (CGAL::Poisson_reconstruction_function: the
/// implicit function solved on a refined 3D Delaunay triangulation by
/// Eigen's conjugate gradients; its median value at the points contoured
/// by CGAL's surface mesher). The implementation, the only file that
/// includes CGAL here, is poisson_reconstruct_cgal.cpp.
///
/// The surface closes the holes the cameras did not see (the sides of a
/// body between the front and back views) smoothly; what it puts there is
/// a guess, and the distance to the true surface says how good.
///
/// Deterministic: CGAL's mesher starts from random points, drawn from its
/// default generator reseeded (0) on every call, and the mesh is returned
/// in a canonical order (vertices sorted by position, faces sorted).
///
/// Cost: measured on this 2-core machine (docs/bodies.md, Depth cameras)
/// about 4 s for the 72k fused points of a body at 4 mm voxels, under 1 s
/// for 8k at 15 mm. Refused beyond max_points.

#include "knitforge/body/fuse_point_clouds.h"
#include "knitforge/geometry/tri_mesh.h"

namespace knitforge {

/// Options of poisson_reconstruct() (CGAL's defaults of its example).
struct PoissonOptions {
  /// Size parameter (mm); 0: the points' average spacing (mean distance to
  /// their 6 nearest neighbours).
  double spacing_mm = 0.0;
  double angle_deg = 20.0;   ///< smallest facet angle of the output
  double radius = 30.0;      ///< largest surface Delaunay ball radius, times the spacing
  double distance = 0.375;   ///< largest distance facet-surface, times the spacing
  /// Refuse more points than this (voxel-average them first, fuse_point_clouds()).
  double max_points = 300000;
};

/// Result of poisson_reconstruct().
struct PoissonResult {
  TriMesh mesh;             ///< closed (unless the surface leaves the mesher's sphere), consistently oriented
  double spacing_mm = 0.0;  ///< the spacing used
};

/// Reconstructs a surface from `cloud` (file comment).
/// \throw InvalidInput for fewer than 10 points, mismatched normals, a
///        non-finite point or normal, more points than max_points (with the
///        count and the remedy); SolverError when CGAL's solver or mesher
///        fails.
PoissonResult poisson_reconstruct(const OrientedPoints& cloud, const PoissonOptions& options = {});

}  // namespace knitforge
