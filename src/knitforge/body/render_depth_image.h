#pragma once
/// \file render_depth_image.h
/// Synthetic depth images: what a depth camera (depth_image.h) would measure
/// of a triangle mesh, without noise. Used to make calibration and fusion
/// data with known answers (synthetic_depth_scenes.h, `knitforge body
/// render-depth`).
///
/// A z-buffer (rasterize_mesh.h): each pixel gets the depth of its nearest
/// fragment, the exact z of the pixel ray's first hit up to rounding.

#include "knitforge/body/depth_image.h"
#include "knitforge/evaluate/rigid_align.h"
#include "knitforge/geometry/tri_mesh.h"

namespace knitforge {

/// Renders `scene` (mm, world frame) seen by `camera` placed by
/// `world_to_camera` (x_c = R x + t). Pixels that see nothing are 0.
/// Faces behind the camera are not clipped: every vertex must lie at least
/// `near_mm` in front of it.
/// \throw InvalidInput naming the face when one has a vertex nearer than
///        near_mm (or behind the camera), or a non-finite vertex.
DepthImage render_depth_image(const TriMesh& scene, const DepthCamera& camera, const RigidTransform& world_to_camera,
                              double near_mm = 10.0);

}  // namespace knitforge
