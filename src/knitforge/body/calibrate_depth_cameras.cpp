#include "knitforge/body/calibrate_depth_cameras.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include <Eigen/Eigenvalues>
#include <Eigen/SVD>
#include <fmt/core.h>

#include "knitforge/util/errors.h"

namespace knitforge {

namespace {

constexpr double kDeg = 180.0 / std::numbers::pi;

double angle_deg(const Vec3& a, const Vec3& b) { return std::atan2(a.cross(b).norm(), a.dot(b)) * kDeg; }

// Smallest eigenvalue of (1/k) sum n n^T.
double spread_of(std::span<const Vec3> normals) {
  Mat3 S = Mat3::Zero();
  for (const Vec3& n : normals) S += n * n.transpose();
  S /= static_cast<double>(normals.size());
  return Eigen::SelfAdjointEigenSolver<Mat3>(S, Eigen::EigenvaluesOnly).eigenvalues()(0);
}

}  // namespace

Mat3 rotation_from_board_normals(std::span<const Vec3> normals1, std::span<const Vec3> normals2) {
  if (normals1.size() != normals2.size() || normals1.size() < 3)
    throw InvalidInput(fmt::format("eq. 5.2: {} and {} normals; it needs the same number k >= 3 from both cameras",
                                   normals1.size(), normals2.size()));
  const auto k = static_cast<Eigen::Index>(normals1.size());
  Eigen::Matrix<double, 3, Eigen::Dynamic> N1(3, k), N2(3, k);
  for (Eigen::Index i = 0; i < k; ++i) {
    N1.col(i) = normals1[static_cast<size_t>(i)];
    N2.col(i) = normals2[static_cast<size_t>(i)];
  }
  const Mat3 G = N2 * N2.transpose();
  if (!(spread_of(normals2) > 1e-9))
    throw InvalidInput("eq. 5.2: the board normals do not span 3D (all in one plane); tilt the board about two axes");
  // Transposed: G R^T = -(N2 N1^T), i.e. R_ls = -N1 N2^T G^-1.
  const Mat3 R_ls = G.ldlt().solve(-(N2 * N1.transpose())).transpose();
  const Eigen::JacobiSVD<Mat3> svd(R_ls, Eigen::ComputeFullU | Eigen::ComputeFullV);
  Mat3 D = Mat3::Identity();
  D(2, 2) = (svd.matrixU() * svd.matrixV().transpose()).determinant() < 0.0 ? -1.0 : 1.0;
  return svd.matrixU() * D * svd.matrixV().transpose();
}

Vec3 translation_from_board_planes(const Mat3& R, std::span<const BoardPlanes> planes, double thickness_mm) {
  const auto k = static_cast<Eigen::Index>(planes.size());
  Eigen::MatrixXd A(k, 3);
  Eigen::VectorXd b(k);
  std::vector<Vec3> n1(planes.size());
  for (Eigen::Index i = 0; i < k; ++i) {
    const BoardPlanes& p = planes[static_cast<size_t>(i)];
    const Vec3 mid1 = p.point1 - 0.5 * thickness_mm * p.normal1;
    const Vec3 mid2 = p.point2 - 0.5 * thickness_mm * p.normal2;
    A.row(i) = p.normal1.transpose();
    b(i) = p.normal1.dot(mid1 - R * mid2);
    n1[static_cast<size_t>(i)] = p.normal1;
  }
  if (k < 3 || !(spread_of(n1) > 1e-9))
    throw InvalidInput("eq. 5.3: the board normals do not span 3D; the translation along their common plane's normal "
                       "is not determined (tilt the board about two axes)");
  // Normal equations of a 3-column problem (k small).
  return (A.transpose() * A).ldlt().solve(A.transpose() * b);
}

DepthCalibration calibrate_depth_cameras(std::span<const BoardPlanes> planes, const DepthCalibrationOptions& o) {
  const size_t k = planes.size();
  if (k < 3)
    throw InvalidInput(fmt::format("calibration: {} board pose{}; eq. 5.2/5.3 need k >= 3 poses, no two parallel "
                                   "(capture the board tilted differently {} more time{})",
                                   k, k == 1 ? "" : "s", 3 - k, 3 - k == 1 ? "" : "s"));
  if (!(o.thickness_mm >= 0.0) || !std::isfinite(o.thickness_mm))
    throw InvalidInput(fmt::format("calibration: board thickness {} mm must be a finite number >= 0", o.thickness_mm));
  std::vector<Vec3> n1(k), n2(k);
  for (size_t i = 0; i < k; ++i) {
    for (const Vec3* n : {&planes[i].normal1, &planes[i].normal2, &planes[i].point1, &planes[i].point2})
      if (!n->allFinite()) throw InvalidInput(fmt::format("calibration: pose {}: a plane is not finite", i + 1));
    if (std::abs(planes[i].normal1.norm() - 1.0) > 1e-6 || std::abs(planes[i].normal2.norm() - 1.0) > 1e-6)
      throw InvalidInput(fmt::format("calibration: pose {}: plane normals must be unit vectors", i + 1));
    n1[i] = planes[i].normal1;
    n2[i] = planes[i].normal2;
  }
  for (size_t i = 0; i < k; ++i)
    for (size_t j = 0; j < i; ++j) {
      const double a = angle_deg(n1[i], n1[j]);
      if (a < o.min_pose_angle_deg)
        throw InvalidInput(fmt::format("calibration: poses {} and {} are {:.1f}° apart (nearly parallel; at least "
                                       "{:g}° needed): tilt the board differently in each pose",
                                       j + 1, i + 1, a, o.min_pose_angle_deg));
    }
  DepthCalibration c;
  c.poses = static_cast<int>(k);
  c.thickness_mm = o.thickness_mm;
  c.spread = spread_of(n1);
  if (c.spread < o.min_spread)
    throw InvalidInput(fmt::format("calibration: the board normals lie nearly in one plane (spread {:.4f}, at least "
                                   "{:g} needed): the board was tilted about one axis only; tilt it about a second "
                                   "axis (e.g. top towards a camera, then a side) in some poses",
                                   c.spread, o.min_spread));
  const Mat3 R = rotation_from_board_normals(n1, n2);
  const Vec3 t = translation_from_board_planes(R, planes, o.thickness_mm);
  c.camera2_to_camera1 = {R, t};
  for (const BoardPlanes& p : planes) {
    c.normal_residual_deg.push_back(angle_deg(-p.normal1, R * p.normal2));
    const Vec3 mid1 = p.point1 - 0.5 * o.thickness_mm * p.normal1;
    const Vec3 mid2 = R * (p.point2 - 0.5 * o.thickness_mm * p.normal2) + t;
    // Distance of camera 1's mid-plane point from camera 2's mapped mid-plane.
    c.plane_residual_mm.push_back(std::abs((R * p.normal2).dot(mid1 - mid2)));
  }
  return c;
}

DepthImageCalibration calibrate_from_depth_images(std::span<const BoardCapture> captures, const DepthCamera& camera1,
                                                  const DepthCamera& camera2, const DepthRange& range,
                                                  const RansacPlaneOptions& ransac,
                                                  const DepthCalibrationOptions& options) {
  DepthImageCalibration out;
  for (size_t i = 0; i < captures.size(); ++i) {
    const BoardCapture& cap = captures[i];
    RansacPlane found[2];
    for (int cam = 0; cam < 2; ++cam) {
      const std::vector<Vec3> pts =
          depth_to_points(cam == 0 ? cap.image1 : cap.image2, cam == 0 ? camera1 : camera2, range);
      try {
        found[cam] = ransac_plane(pts, ransac);
      } catch (const InvalidInput& e) {
        throw InvalidInput(fmt::format("pose {} ({}), camera {}: {}", i + 1, cap.name, cam + 1, e.what()));
      }
      found[cam].inliers.clear();
      found[cam].inliers.shrink_to_fit();
    }
    out.planes.push_back({found[0].normal, found[0].point, found[1].normal, found[1].point});
    out.detected1.push_back(found[0]);
    out.detected2.push_back(found[1]);
  }
  out.calibration = calibrate_depth_cameras(out.planes, options);
  return out;
}

double rotation_angle_between_deg(const Mat3& R1, const Mat3& R2) {
  // Through the quaternion (atan2): precise for small angles, unlike acos of the trace.
  return Eigen::AngleAxisd(Eigen::Quaterniond(R2.transpose() * R1).normalized()).angle() * kDeg;
}

}  // namespace knitforge
