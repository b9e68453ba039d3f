#pragma once
/// \file render_depth_image.h
/// Synthetic depth images: what a depth camera (depth_image.h) would measure
/// of a triangle mesh, without noise. Used to make calibration and fusion
/// data with known answers (synthetic_depth_scenes.h, `knitforge body
/// render-depth`).
///
/// A z-buffer rasteriser: each face is projected into the image; every
/// pixel centre inside it (edges inclusive) gets the face's z-depth at that
/// pixel, the nearest face winning. For a planar triangle 1/z is an affine
/// function of (u, v), so the depth is the exact z of the ray's hit
/// (perspective-correct interpolation of 1/z), up to rounding.

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
