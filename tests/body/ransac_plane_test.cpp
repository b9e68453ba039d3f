#include "knitforge/body/ransac_plane.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

#include "knitforge/util/errors.h"

using namespace knitforge;

namespace {

// `n_plane` points on the plane through p with normal n (a 600 mm square),
// with Gaussian noise sigma along n, then `n_out` points uniform in a box.
std::vector<Vec3> plane_with_outliers(const Vec3& n, const Vec3& p, int n_plane, int n_out, double sigma,
                                      unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-300.0, 300.0), box(-1000.0, 1000.0);
  std::normal_distribution<double> g(0.0, 1.0);
  const Vec3 e1 = n.unitOrthogonal(), e2 = n.cross(e1);
  std::vector<Vec3> pts;
  for (int i = 0; i < n_plane; ++i) pts.push_back(p + u(rng) * e1 + u(rng) * e2 + sigma * g(rng) * n);
  for (int i = 0; i < n_out; ++i) pts.push_back(p + Vec3(box(rng), box(rng), box(rng)));
  return pts;
}

double angle_deg(const Vec3& a, const Vec3& b) { return std::atan2(a.cross(b).norm(), a.dot(b)) * 180.0 / std::numbers::pi; }

}  // namespace

TEST(RansacPlane, ANoiselessPlaneAmongOutliersIsFoundExactly) {
  const Vec3 n = Vec3(0.2, -0.4, -1.0).normalized();  // faces the origin
  const Vec3 p(30, -50, 1200);
  const std::vector<Vec3> pts = plane_with_outliers(n, p, 3000, 2000, 0.0, 7);
  RansacPlaneOptions o;
  o.inlier_distance_mm = 1e-6;
  const RansacPlane plane = ransac_plane(pts, o);
  EXPECT_LT(angle_deg(plane.normal, n), 1e-9);
  EXPECT_NEAR(n.dot(plane.point - p), 0.0, 1e-9);
  // Exactly the plane's points (an outlier within 1e-6 mm has probability ~0).
  ASSERT_EQ(plane.inliers.size(), 3000u);
  for (int i = 0; i < 3000; ++i) EXPECT_EQ(plane.inliers[static_cast<size_t>(i)], i);
  EXPECT_NEAR(plane.inlier_fraction, 0.6, 1e-12);
  EXPECT_LT(plane.rms_mm, 1e-9);
}

TEST(RansacPlane, TheNormalFacesTheOrigin) {
  const Vec3 n = Vec3(0.1, 0.1, 1.0).normalized();  // pointing away from the origin
  const std::vector<Vec3> pts = plane_with_outliers(n, Vec3(0, 0, 800), 500, 0, 0.0, 1);
  const RansacPlane plane = ransac_plane(pts);
  EXPECT_LT(angle_deg(plane.normal, -n), 1e-9);
  EXPECT_LT(plane.normal.dot(plane.point), 0.0);
}

TEST(RansacPlane, WithOneMillimetreNoiseTheNormalIsWithinAHundredthOfADegree) {
  const Vec3 n = Vec3(-0.3, 0.1, -1.0).normalized();
  const std::vector<Vec3> pts = plane_with_outliers(n, Vec3(0, 0, 1000), 20000, 5000, 1.0, 11);
  const RansacPlane plane = ransac_plane(pts);
  // sigma / (extent * sqrt(N)) ~ 1 / (170 * 141) rad: about 0.002 degrees.
  EXPECT_LT(angle_deg(plane.normal, n), 0.01);
  EXPECT_NEAR(plane.rms_mm, 1.0, 0.05);
  EXPECT_GT(plane.inlier_fraction, 0.79);
  // Deterministic for a seed.
  const RansacPlane again = ransac_plane(pts);
  EXPECT_EQ(again.normal, plane.normal);
  EXPECT_EQ(again.inliers, plane.inliers);
}

TEST(RansacPlane, NoPlaneInAScatterIsReportedAsSuch) {
  const std::vector<Vec3> pts = plane_with_outliers(Vec3::UnitZ(), Vec3(0, 0, 1000), 0, 5000, 0.0, 3);
  try {
    ransac_plane(pts);
    FAIL() << "a plane in a uniform scatter";
  } catch (const InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find("no plane found"), std::string::npos) << e.what();
  }
  EXPECT_THROW(ransac_plane(std::vector<Vec3>{Vec3::Zero(), Vec3::UnitX()}), InvalidInput);
  EXPECT_THROW(fit_plane(std::vector<Vec3>{Vec3::Zero(), Vec3::UnitX(), 2.0 * Vec3::UnitX()}), InvalidInput);
}
