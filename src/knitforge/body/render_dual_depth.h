#pragma once
/// \file render_dual_depth.h
/// The dual-depth representation of the seed (§5.4.3): per pixel, the
/// nearest and the farthest depth of a mesh along the pixel's ray
/// (I_min, I_max). I_min is what a depth camera sees; I_max is the surface
/// a camera behind the body would see through the same pixels. Together
/// they cover about twice the surface of a single depth image (the seed
/// measures ~70 % of a body); surfaces tangent to the rays and parts hidden
/// from both sides are missed.

#include <vector>

#include "knitforge/body/depth_image.h"
#include "knitforge/evaluate/rigid_align.h"
#include "knitforge/geometry/tri_mesh.h"

namespace knitforge {

/// Two depth channels and the face seen first, row-major (pixel v * width + u).
struct DualDepthImage {
  int width = 0;
  int height = 0;
  std::vector<double> min_mm;  ///< nearest hit's z-depth (0: the ray misses)
  std::vector<double> max_mm;  ///< farthest hit's z-depth (0: the ray misses)
  std::vector<int> min_face;   ///< the face of the nearest hit (-1: none)

  bool covered(int pixel) const { return min_face[static_cast<size_t>(pixel)] >= 0; }
};

/// Renders the dual depth of `scene` (mm, world frame) seen by `camera`
/// placed by `world_to_camera` (x_c = R x + t), with the rasteriser of
/// rasterize_mesh.h.
/// \throw InvalidInput as rasterize_mesh() (a vertex nearer than near_mm).
DualDepthImage render_dual_depth(const TriMesh& scene, const DepthCamera& camera,
                                 const RigidTransform& world_to_camera, double near_mm = 10.0);

}  // namespace knitforge
