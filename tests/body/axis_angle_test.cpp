// Axis-angle rotations (body/axis_angle.h).
#include "knitforge/body/axis_angle.h"

#include <gtest/gtest.h>

#include <numbers>
#include <random>

namespace knitforge {
namespace {

constexpr double kPi = std::numbers::pi;

TEST(AxisAngle, SkewIsTheCrossProduct) {
  const Vec3 a(0.3, -1.2, 2.0), b(-0.7, 0.4, 1.1);
  EXPECT_LT((skew(a) * b - a.cross(b)).norm(), 1e-15);
}

TEST(AxisAngle, RotationIsOrthonormalAndTurnsByItsAngleAboutItsAxis) {
  const Vec3 axis = Vec3(1, 2, -0.5).normalized();
  const double angle = 1.1;
  const Mat3 R = rotation_from_axis_angle(angle * axis);
  EXPECT_LT((R.transpose() * R - Mat3::Identity()).norm(), 1e-14);
  EXPECT_NEAR(R.determinant(), 1.0, 1e-14);
  EXPECT_LT((R * axis - axis).norm(), 1e-14);
  // A vector perpendicular to the axis turns by `angle`, right-handed.
  const Vec3 p = axis.cross(Vec3::UnitX()).normalized();
  const Vec3 q = R * p;
  EXPECT_NEAR(std::acos(std::clamp(p.dot(q), -1.0, 1.0)), angle, 1e-12);
  EXPECT_GT(p.cross(q).dot(axis), 0.0);
  EXPECT_NEAR(rotation_angle(R), angle, 1e-12);
  // A quarter turn about z sends x to y.
  EXPECT_LT((rotation_from_axis_angle({0, 0, kPi / 2}) * Vec3::UnitX() - Vec3::UnitY()).norm(), 1e-15);
}

TEST(AxisAngle, TinyAnglesMatchTheSeries) {
  const Vec3 w(1e-8, -2e-8, 3e-8);
  const Mat3 R = rotation_from_axis_angle(w);
  EXPECT_LT((R - (Mat3::Identity() + skew(w) + 0.5 * skew(w) * skew(w))).norm(), 1e-15);
  EXPECT_LT((axis_angle_from_rotation(R) - w).norm(), 1e-20 + 1e-12 * w.norm());
  EXPECT_EQ(axis_angle_from_rotation(Mat3::Identity()), Vec3::Zero());
}

TEST(AxisAngle, RoundTripsOverAllAnglesIncludingNearPi) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int it = 0; it < 200; ++it) {
    const Vec3 axis = Vec3(u(rng), u(rng), u(rng)).normalized();
    // Angles spread over (0, pi), a quarter of them within 1e-4 of pi.
    const double angle = it % 4 == 0 ? kPi - 1e-4 * (0.5 + 0.5 * u(rng)) : kPi * (0.5 + 0.5 * u(rng));
    const Vec3 w = angle * axis;
    const Mat3 R = rotation_from_axis_angle(w);
    const Vec3 back = axis_angle_from_rotation(R);
    EXPECT_LT((rotation_from_axis_angle(back) - R).norm(), 1e-9) << "angle " << angle;
    EXPECT_LE(back.norm(), kPi + 1e-12);
    EXPECT_LT((back - w).norm(), 1e-7) << "angle " << angle;
  }
  // Exactly pi: either sign of the axis is the same rotation.
  const Mat3 Rpi = rotation_from_axis_angle(kPi * Vec3::UnitY());
  const Vec3 b = axis_angle_from_rotation(Rpi);
  EXPECT_NEAR(b.norm(), kPi, 1e-12);
  EXPECT_LT((rotation_from_axis_angle(b) - Rpi).norm(), 1e-12);
}

TEST(AxisAngle, NearestRotationOfAPerturbedRotationAndOfAReflection) {
  const Mat3 R = rotation_from_axis_angle({0.4, -0.2, 0.9});
  Mat3 M = 2.5 * R;  // scaled: polar factor is R
  EXPECT_LT((nearest_rotation(M) - R).norm(), 1e-12);
  Mat3 S = Mat3::Identity();
  S(2, 2) = -1.0;  // a reflection: the nearest rotation has det +1
  const Mat3 N = nearest_rotation(S);
  EXPECT_NEAR(N.determinant(), 1.0, 1e-12);
  EXPECT_LT((N.transpose() * N - Mat3::Identity()).norm(), 1e-12);
}

}  // namespace
}  // namespace knitforge
