#pragma once
/// \file calibrate_depth_cameras.h
/// Calibration of two depth cameras facing each other from a flat board
/// (seed §5.3.1, eq. 5.2/5.3): the rigid motion (R | t) that takes points
/// in camera 2's frame to camera 1's, x_1 = R x_2 + t.
///
/// The board (flat, uniform thickness c) is held between the cameras in
/// k >= 3 poses, no two parallel; each camera sees one side. In pose i the
/// cameras see the planes n_{j,i} . (x - p_{j,i}) = 0 (j = 1, 2; unit
/// normals pointing out of the board, towards the camera that sees it, in
/// that camera's frame). Both describe the board's mid-plane through
/// p^_{j,i} = p_{j,i} - (c/2) n_{j,i}, with opposite normals, so
///
///   eq. 5.2  R [n_{2,1} ... n_{2,k}] = -[n_{1,1} ... n_{1,k}]
///
/// solved in the least-squares sense over all 3 x 3 matrices,
/// R_ls = -N1 N2^T (N2 N2^T)^-1, then projected to the nearest rotation
/// (SVD R_ls = U S V^T, R = U diag(1, 1, det(U V^T)) V^T), as the seed;
///
///   eq. 5.3  n_{1,i} . (R p^_{2,i} + t - p^_{1,i}) = 0,  i = 1..k,
///
/// the k x 3 linear least-squares problem N1^T t = (n_{1,i} . (p^_{1,i} -
/// R p^_{2,i}))_i for t. Both are exact for noiseless planes. Both need the
/// normals to span 3D: a board tilted about one axis only leaves the
/// rotation about it and the translation along it open (refused).
///
/// calibrate_from_depth_images() finds the planes first, by RANSAC
/// (ransac_plane.h) in each camera's points of the board.

#include <span>
#include <string>
#include <vector>

#include "knitforge/body/depth_image.h"
#include "knitforge/body/ransac_plane.h"
#include "knitforge/evaluate/rigid_align.h"

namespace knitforge {

/// The two sides of the board in one pose, each in its camera's frame (mm).
struct BoardPlanes {
  Vec3 normal1 = Vec3::UnitZ();  ///< unit, out of the board towards camera 1
  Vec3 point1 = Vec3::Zero();    ///< a point of the side camera 1 sees
  Vec3 normal2 = Vec3::UnitZ();  ///< unit, out of the board towards camera 2
  Vec3 point2 = Vec3::Zero();    ///< a point of the side camera 2 sees
};

/// Eq. 5.2: R_ls by least squares, then the nearest rotation (file comment).
/// \pre normals1.size() == normals2.size() >= 3, unit normals spanning 3D.
/// \throw InvalidInput for fewer than 3 pairs, mismatched counts, or normals
///        that do not span 3D (N2 N2^T singular to 1e-9).
Mat3 rotation_from_board_normals(std::span<const Vec3> normals1, std::span<const Vec3> normals2);

/// Eq. 5.3: t by linear least squares, given R and the board thickness.
/// \throw InvalidInput when the normals n_{1,i} do not span 3D.
Vec3 translation_from_board_planes(const Mat3& R, std::span<const BoardPlanes> planes, double thickness_mm);

/// Options of calibrate_depth_cameras().
struct DepthCalibrationOptions {
  double thickness_mm = 0.0;    ///< c, the board's thickness (mm, >= 0)
  /// Refuse pose pairs whose normals (in camera 1) are closer than this
  /// (the seed: "can not be parallel with any of the previous poses").
  double min_pose_angle_deg = 5.0;
  /// Refuse normals that nearly lie in one plane: the smallest eigenvalue
  /// of (1/k) N1 N1^T below this (0.003: the normals' rms angle out of
  /// one plane about 3 degrees; tilt the board about two different axes).
  double min_spread = 0.003;
};

/// Result of calibrate_depth_cameras().
struct DepthCalibration {
  RigidTransform camera2_to_camera1;  ///< x_1 = R x_2 + t (mm)
  int poses = 0;
  double thickness_mm = 0.0;
  /// Per pose: the angle between -n_{1,i} and R n_{2,i} (degrees) and the
  /// distance between the two mid-planes (camera 2's mapped by (R | t)) at
  /// camera 1's board point (mm): the residuals of eq. 5.2 and 5.3.
  std::vector<double> normal_residual_deg;
  std::vector<double> plane_residual_mm;
  /// Smallest eigenvalue of (1/k) N1 N1^T (1/3 for three orthogonal
  /// normals, 0 for normals in one plane).
  double spread = 0.0;
};

/// Eq. 5.2 then eq. 5.3 on k pose pairs (file comment).
/// \throw InvalidInput for fewer than 3 poses ("k >= 3"), a non-unit or
///        non-finite normal, a negative thickness, two poses closer than
///        min_pose_angle_deg (naming them), normals not spread over 3D.
DepthCalibration calibrate_depth_cameras(std::span<const BoardPlanes> planes, const DepthCalibrationOptions& options);

/// One board pose as the two cameras saw it.
struct BoardCapture {
  DepthImage image1;
  DepthImage image2;
  std::string name;  ///< for messages (e.g. the file names)
};

/// Result of calibrate_from_depth_images(): the calibration and the planes.
struct DepthImageCalibration {
  DepthCalibration calibration;
  std::vector<BoardPlanes> planes;
  std::vector<RansacPlane> detected1, detected2;  ///< per pose (inlier lists dropped)
};

/// Finds the board in each image (ransac_plane() on its points within
/// `range`; the board must be the largest plane there), then
/// calibrate_depth_cameras().
/// \throw InvalidInput as those, naming the pose and the camera when no
///        plane is found.
DepthImageCalibration calibrate_from_depth_images(std::span<const BoardCapture> captures, const DepthCamera& camera1,
                                                  const DepthCamera& camera2, const DepthRange& range,
                                                  const RansacPlaneOptions& ransac,
                                                  const DepthCalibrationOptions& options);

/// Rotation angle of R2^T R1 (degrees): how far two rotations are apart.
double rotation_angle_between_deg(const Mat3& R1, const Mat3& R2);

}  // namespace knitforge
