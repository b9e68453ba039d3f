#pragma once
/// \file fuse_point_clouds.h
/// The points of the two depth cameras merged into one oriented point cloud
/// in camera 1's frame (seed §5.3: "two frames of point clouds can be merged
/// together using the calibrated transformation matrix"), ready for Poisson
/// reconstruction (poisson_reconstruct.h).
///
/// 1. Per camera, depth_to_oriented_points(): each measured pixel's point
///    (depth_image.h) with a normal from its image neighbourhood: the
///    least-squares plane (smallest principal direction) of the points of
///    the (2r+1)^2 pixels around it that lie within max_gap_mm of it (so a
///    depth edge does not bend the normal), oriented towards the camera
///    that saw it. A point with fewer than min_neighbours such neighbours
///    (a flying pixel, a lone outlier) is dropped.
/// 2. fuse_point_clouds(): camera 2's points and normals mapped by the
///    calibration (R | t), then both clouds averaged on a voxel grid (one
///    point per occupied voxel: the mean position, the normalised sum of
///    the normals), which evens out the density where the views overlap and
///    bounds the point count. Deterministic: voxels in lexicographic order.

#include <vector>

#include "knitforge/body/depth_image.h"
#include "knitforge/evaluate/rigid_align.h"

namespace knitforge {

/// Points (mm) with unit normals, one per point.
struct OrientedPoints {
  std::vector<Vec3> points;
  std::vector<Vec3> normals;
};

/// Options of depth_to_oriented_points().
struct DepthNormalOptions {
  int radius_px = 2;          ///< r: the window is (2r + 1) x (2r + 1) pixels
  double max_gap_mm = 15.0;   ///< neighbours farther than this from the point are ignored
  int min_neighbours = 6;     ///< fewer (the point itself not counted): the point is dropped
};

/// Step 1 (file comment), in the camera's frame.
/// \throw InvalidInput when the image's size is not the camera's or an
///        option is out of range (radius 1..10, gap > 0, neighbours >= 2).
OrientedPoints depth_to_oriented_points(const DepthImage& image, const DepthCamera& camera, const DepthRange& range,
                                        const DepthNormalOptions& options = {});

/// Options of fuse_point_clouds().
struct FusePointOptions {
  double voxel_mm = 4.0;  ///< edge of the averaging grid's cells (mm, > 0)
};

/// Step 2 (file comment): cloud1 (camera 1's frame) and cloud2 (camera 2's
/// frame) in camera 1's frame.
/// \throw InvalidInput for mismatched points/normals, a non-positive voxel,
///        or a grid index that would overflow (voxel too small for the extent).
OrientedPoints fuse_point_clouds(const OrientedPoints& cloud1, const OrientedPoints& cloud2,
                                 const RigidTransform& camera2_to_camera1, const FusePointOptions& options = {});

}  // namespace knitforge
