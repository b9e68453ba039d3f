#pragma once
/// \file study_depth_calibration.h
/// How well the dual-camera calibration (calibrate_depth_cameras.h, seed
/// eq. 5.2/5.3) recovers a known rig, against the depth noise and the
/// number k of board poses: the seed's rig (synthetic_depth_scenes.h), the
/// board in k random poses, both cameras' depth images rendered, noised and
/// rounded to the cameras' depth units (what a 16-bit PNG stores), the
/// planes found by RANSAC, the calibration compared with the truth.
/// `knitforge body calibrate-study` prints it as a table (docs/bodies.md,
/// the quality bar: rotation < 0.5°, translation < 5 mm at 1 mm
/// noise).

#include <span>
#include <vector>

#include "knitforge/body/calibrate_depth_cameras.h"
#include "knitforge/body/synthetic_depth_scenes.h"

namespace knitforge {

/// The captures (camera 1's and camera 2's depth image) of the board in
/// each of `poses`, each image with `noise` (seed noise.seed + 2i for
/// camera 1's image of pose i, + 2i + 1 for camera 2's), then every depth
/// rounded to the camera's depth unit (a positive depth never to 0), as
/// `body render-depth` writes them.
std::vector<BoardCapture> synthetic_board_captures(const DepthRig& rig, std::span<const RigidTransform> poses,
                                                   const BoardSize& board, const DepthNoise& noise);

/// Options of study_depth_calibration().
struct DepthCalibrationStudyOptions {
  std::vector<double> noise_mm = {0.0, 1.0, 3.0};  ///< depth noise sigmas (mm, >= 0), one row group each
  std::vector<int> poses = {3, 6, 10};             ///< k, board poses per calibration (3..100)
  int runs = 4;                                    ///< random pose sets per (noise, k), 1..1000
  double outlier_fraction = 0.0;                   ///< pixels replaced by random depths (DepthNoise)
  BoardSize board;                                 ///< the board (default 600 x 450 x 10 mm)
  double distance_mm = 2000.0;                     ///< between the cameras (seed_depth_rig())
  RansacPlaneOptions ransac;                       ///< plane detection (body calibrate's defaults)
  unsigned seed = 1;                               ///< poses: seed + 1000 k + run; noise: the same
};

/// One (noise, k) cell of the study.
struct DepthCalibrationStudyRow {
  double noise_mm = 0.0;
  int poses = 0;
  int runs = 0;                      ///< calibrations that succeeded
  int failed = 0;                    ///< calibrations refused (no plane found, poses too close)
  double rotation_mean_deg = 0.0;    ///< angle of R_found^T R_true, over the successful runs
  double rotation_max_deg = 0.0;
  double translation_mean_mm = 0.0;  ///< |t_found - t_true|
  double translation_max_mm = 0.0;
};

/// Runs the study (file comment): one row per noise and k, in the order
/// given (noise outer). Deterministic for a seed.
/// \throw InvalidInput for an empty list, a negative or non-finite noise, k
///        outside 3..100, runs outside 1..1000, or a bad board size; a
///        calibration that refuses its captures (InvalidInput: no plane
///        found, poses too close) is counted in `failed`.
std::vector<DepthCalibrationStudyRow> study_depth_calibration(const DepthCalibrationStudyOptions& options);

}  // namespace knitforge
