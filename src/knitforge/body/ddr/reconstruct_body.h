#pragma once
/// \file reconstruct_body.h
/// A body from a single picture (seed §5.4.4): the DDR predicted from the
/// picture and its 18 keypoints, its foreground pixels back to 3D, the
/// view-based refinement from four more views (±45°, ±135° about the
/// vertical through the pelvis), all points fused and meshed by Poisson
/// reconstruction (body/poisson_reconstruct.h).
///
/// The picture must be taken as the training images were (ddr_sample.h): the
/// whole body standing upright in the middle, seen horizontally from about
/// 6 m with a focal length of 800 px per 256 px of image (a telephoto view;
/// the body about 7/8 of the image's height). The metric scale comes from
/// that assumption: the pelvis (the midpoint of the hip keypoints) is put
/// at 6 m.
///
/// The output frame is camera_to_body_frame() (ddr_geometry.h): origin at
/// the pelvis, x to the picture's right, y away from the camera, z up.

#include <array>
#include <functional>
#include <vector>

#include "knitforge/body/body_keypoints.h"
#include "knitforge/body/fuse_point_clouds.h"
#include "knitforge/body/ddr/ddr_model.h"
#include "knitforge/evaluate/rigid_align.h"
#include "knitforge/geometry/tri_mesh.h"

namespace knitforge {

/// A picture at the model's size and its keypoints.
struct ReconstructInput {
  std::vector<float> rgb;                             ///< 3 x s x s in [0, 1]
  KeypointPixels keypoints_px = zero_keypoint_pixels();  ///< (u, v) in the s x s picture
  std::array<bool, kNumBodyKeypoints> present{};      ///< false: not detected
};

/// Options of reconstruct_body().
struct ReconstructOptions {
  bool refine = true;   ///< the four refinement views (false: the DDR's points only)
  uint64_t seed = 1;    ///< the dropout noise (the result is deterministic for a seed)
};

/// Result of reconstruct_body().
struct ReconstructedBody {
  std::vector<float> ddr;           ///< the predicted DDR (2 x s x s, normalised)
  OrientedPoints points;            ///< fused points, output frame (mm)
  TriMesh mesh;                     ///< the Poisson surface, output frame (mm)
  RigidTransform camera_to_body;    ///< camera frame -> output frame
  int ddr_points = 0;               ///< points from the DDR itself
  int view_points = 0;              ///< points added by the refinement views
};

/// The refined min-depth (1 x s x s, normalised) of one view, from the
/// refinement network's 19-channel input and the view's angle.
using ViewPredictor = std::function<std::vector<float>(const std::vector<float>& input, double angle_rad)>;

/// The 3D half of reconstruct_body(): the DDR's points, the four views'
/// points when `view` is set, fused and meshed. Exposed so that it can be
/// run on true DDRs and views (a test of the geometry without a network).
/// \throw InvalidInput / SolverError as reconstruct_body().
ReconstructedBody body_from_ddr(const std::vector<float>& ddr, const ReconstructInput& input, int size,
                                const ViewPredictor& view);

/// Reconstructs (file comment).
/// \throw InvalidInput when the picture's size is not the model's, a hip
///        keypoint is missing, or too few foreground pixels are predicted
///        (not a body seen as the model expects); SolverError from Poisson.
ReconstructedBody reconstruct_body(DdrModel& model, const ReconstructInput& input, const ReconstructOptions& options);

}  // namespace knitforge
