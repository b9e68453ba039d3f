#include "knitforge/body/axis_angle.h"

#include <algorithm>
#include <cmath>

#include <Eigen/SVD>

namespace knitforge {

Mat3 skew(const Vec3& a) {
  Mat3 m;
  m << 0.0, -a.z(), a.y(), a.z(), 0.0, -a.x(), -a.y(), a.x(), 0.0;
  return m;
}

Mat3 rotation_from_axis_angle(const Vec3& w) {
  const double t2 = w.squaredNorm();
  const Mat3 K = skew(w);
  double a, b;  // R = I + a K + b K^2
  if (t2 < 1e-12) {
    a = 1.0 - t2 / 6.0;
    b = 0.5 - t2 / 24.0;
  } else {
    const double t = std::sqrt(t2);
    a = std::sin(t) / t;
    b = (1.0 - std::cos(t)) / t2;
  }
  return Mat3::Identity() + a * K + b * K * K;
}

double rotation_angle(const Mat3& R) {
  const double c = std::clamp(0.5 * (R.trace() - 1.0), -1.0, 1.0);
  // atan2 of the sine (from the skew part) and the cosine: accurate at 0 and pi.
  const Vec3 s(R(2, 1) - R(1, 2), R(0, 2) - R(2, 0), R(1, 0) - R(0, 1));
  return std::atan2(0.5 * s.norm(), c);
}

Vec3 axis_angle_from_rotation(const Mat3& R) {
  const Vec3 s(R(2, 1) - R(1, 2), R(0, 2) - R(2, 0), R(1, 0) - R(0, 1));  // 2 sin(t) axis
  const double sin_t = 0.5 * s.norm();
  const double cos_t = std::clamp(0.5 * (R.trace() - 1.0), -1.0, 1.0);
  const double t = std::atan2(sin_t, cos_t);
  if (t < 1e-6) return 0.5 * s;  // sin t ~ t
  if (t < 3.14159265358979323846 - 1e-3) return s * (t / (2.0 * sin_t));
  // Near pi: the axis from the symmetric part, R + R^T = 2 cos t I + 2 (1 - cos t) a a^T.
  const Mat3 S = 0.5 * (R + R.transpose()) - cos_t * Mat3::Identity();
  int k = 0;
  S.diagonal().maxCoeff(&k);
  Vec3 a = S.col(k) / std::sqrt(std::max(S(k, k), 1e-300));
  a.normalize();
  if (a.dot(s) < 0.0) a = -a;  // the sign the skew part still carries
  return a * t;
}

Mat3 nearest_rotation(const Mat3& M) {
  Eigen::JacobiSVD<Mat3> svd(M, Eigen::ComputeFullU | Eigen::ComputeFullV);
  Mat3 D = Mat3::Identity();
  D(2, 2) = (svd.matrixU() * svd.matrixV().transpose()).determinant() < 0.0 ? -1.0 : 1.0;
  return svd.matrixU() * D * svd.matrixV().transpose();
}

}  // namespace knitforge
