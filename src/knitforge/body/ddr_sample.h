#pragma once
/// \file ddr_sample.h
/// Training and test data of the single-image reconstruction (seed §5.4),
/// rendered by our own code from our body model: a picture (RGB with simple
/// shading), the 18 keypoint heatmaps (body_keypoints.h) and the true
/// dual-depth representation (render_dual_depth.h) of one body seen from
/// one direction. No download: bodies, poses, clothes colours, lights and
/// backgrounds are drawn at random from a seed.
///
/// The camera follows the seed's set-up (§5.4.5) scaled to the image size
/// s: a square s x s image, focal length 800 s / 256 px (800 px at 256),
/// the camera 6 m from the centre of the body's bounding box, looking at it
/// horizontally; the body turned about the vertical axis by the azimuth.
///
/// Normalisation (§5.4.4): a depth z (mm) is stored as (z - z_pelvis) /
/// 1000 mm, z_pelvis the z-depth of the pelvis centre (the midpoint of the
/// hips), so one unit is one metre and a body within ±1 m of its pelvis
/// lies in [-1, +1]; background pixels are 0 in both channels ("background
/// centring"). Images are channel-major (c * s * s + v * s + u).

#include <array>
#include <cstdint>
#include <random>
#include <vector>

#include "knitforge/body/body_keypoints.h"
#include "knitforge/body/body_model.h"
#include "knitforge/body/depth_image.h"
#include "knitforge/evaluate/rigid_align.h"
#include "knitforge/geometry/tri_mesh.h"
#include "knitforge/render/render_mesh.h"

namespace knitforge {

/// Millimetres per normalised depth unit.
inline constexpr double kDdrDepthUnitMm = 1000.0;
/// The camera's distance to the body's centre (mm).
inline constexpr double kDdrCameraDistanceMm = 6000.0;

/// The body model the samples are drawn from: our generated body at a 30 mm
/// edge (about 3k vertices: a 256-pixel image sees ~7 mm per pixel, so a
/// finer mesh adds nothing), built once per process.
const BodyModel& ddr_body_model();

/// Intrinsics of the s x s camera (file comment).
/// \throw InvalidInput for a size outside 16..1024.
DepthCamera ddr_camera(int size);

/// World-to-camera transform of a horizontal camera kDdrCameraDistanceMm
/// from `centre`, on the body's front side (-y) turned by `azimuth_rad`
/// about the vertical (+z) axis: camera x to the right, y down (world -z),
/// z forward.
RigidTransform ddr_world_to_camera(const Vec3& centre, double azimuth_rad);

/// Options of the synthetic scenes.
struct DdrSceneOptions {
  int size = 64;                 ///< image size s (pixels)
  double max_azimuth_deg = 90;   ///< azimuths are drawn in ±this (0: the body faces the camera)
  double heatmap_sigma_px = 0;   ///< Gaussian of a keypoint (0: 1.5 s / 64 px)
};

/// One rendered sample.
struct DdrSample {
  int size = 0;
  std::vector<float> rgb;          ///< 3 x s x s, in [0, 1]
  std::vector<float> heatmaps;     ///< 18 x s x s, in [0, 1]
  std::vector<float> ddr;          ///< 2 x s x s: I_min, I_max normalised; background 0
  std::vector<uint8_t> foreground; ///< s x s: 1 where the body is seen
  KeypointPixels keypoints_px = zero_keypoint_pixels();  ///< (u, v) pixels
  std::array<Vec3, kNumBodyKeypoints> keypoints_mm;   ///< camera frame
  Vec3 pelvis_mm = Vec3::Zero();                      ///< camera frame
  DepthCamera camera;
  RigidTransform world_to_camera;
  TriMesh body;                    ///< the posed body, world frame (mm)
};

/// A random body of `model`: each shape parameter uniform within ±120 mm
/// for the stature, ±20 mm for the head and neck girths, ±70 mm for the
/// other girths and ±50 mm for the other lengths (our model's parameters are
/// measurements in mm); ±1 for a parameter of another name (an SMPL beta).
/// The pose is near the a-pose: arms lowered 15-80° from the T, elbows bent
/// 0-70°, hips and knees within a walking range, a little spine and neck
/// turn.
BodyParams random_ddr_body(const BodyModel& model, std::mt19937_64& rng);

/// Renders `params` seen at `azimuth_rad`; clothes colours, light and
/// background drawn from `appearance_seed`.
/// \throw InvalidInput as validate_body_params() and ddr_camera().
DdrSample render_ddr_sample(const BodyModel& model, const BodyKeypointRig& rig, const BodyParams& params,
                            double azimuth_rad, const DdrSceneOptions& options, uint64_t appearance_seed);

/// The seed of training sample i (0-based: i + 1) and of held-out test
/// sample i (2^40 + i): the two sets never share a body.
uint64_t ddr_train_seed(int i);
uint64_t ddr_test_seed(int i);

/// The sample number `seed`: a random body, azimuth and appearance.
DdrSample synthetic_ddr_sample(const BodyModel& model, const BodyKeypointRig& rig, uint64_t seed,
                               const DdrSceneOptions& options);

/// 18 heatmaps (18 x s x s): a Gaussian of peak 1 and `sigma_px` at each
/// present keypoint; a missing keypoint's channel is 0.
std::vector<float> keypoint_heatmaps(const std::array<Vec2, kNumBodyKeypoints>& keypoints_px,
                                     const std::array<bool, kNumBodyKeypoints>& present, int size, double sigma_px);

/// The 19-channel input of the view-based refinement network (§5.4.4): the
/// points (camera frame, mm) turned by `angle_rad` about the vertical
/// through `pelvis_mm` (turn_about_vertical()) and splatted into a min-depth
/// image, normalised as the DDR (background 0), then the 18 heatmaps of the
/// keypoints turned the same way.
std::vector<float> ddr_view_input(const std::vector<Vec3>& points_mm,
                                  const std::array<Vec3, kNumBodyKeypoints>& keypoints_mm,
                                  const std::array<bool, kNumBodyKeypoints>& present, const Vec3& pelvis_mm,
                                  const DepthCamera& camera, double angle_rad, double sigma_px);

/// What the refinement network should output for `sample` turned by
/// `angle_rad`: the true min-depth of the body seen that way, normalised
/// (1 x s x s, background 0); `foreground` (optional) receives its mask.
std::vector<float> ddr_view_truth(const DdrSample& sample, double angle_rad, std::vector<uint8_t>* foreground = nullptr);

/// The heatmap Gaussian's sigma (pixels) of an s x s image: 1.5 s / 64, or
/// the option when set.
double ddr_heatmap_sigma(const DdrSceneOptions& options);

/// A picture as the networks take it: `image` scaled to s x s by area
/// averaging (box filter), channel-major floats in [0, 1]; `scale`
/// receives s / image width (multiply pixel coordinates by it).
/// \throw InvalidInput when the image is not square within 2 % (crop it
///        around the person first) or smaller than s.
std::vector<float> ddr_picture(const RgbImage& image, int size, double* scale = nullptr);

/// The sample's picture as an 8-bit image (s x s).
RgbImage ddr_picture_image(const DdrSample& sample);

/// A DDR (2 x s x s, normalised) as a picture for people: I_min on the
/// left, I_max on the right, grey 128 at the pelvis depth, lighter nearer
/// (one grey level per 4 mm, clamped), background black.
RgbImage ddr_depth_picture(const std::vector<float>& ddr, int size);

}  // namespace knitforge
