// 3D keypoints from rays (body/triangulate_rays.h, seed eq. 5.14-5.16) and
// the keypoints file (body/keypoint_views.h).
#include "knitforge/body/triangulate_rays.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>
#include <random>

#include "knitforge/body/axis_angle.h"
#include "knitforge/body/keypoint_views.h"
#include "knitforge/util/errors.h"

namespace knitforge {
namespace {

// A camera at `eye` looking at `target` (z up), focal 800 px, 640 x 480.
PinholeCamera look_at(const Vec3& eye, const Vec3& target) {
  const Vec3 z = (target - eye).normalized();
  const Vec3 x = z.cross(Vec3::UnitZ()).normalized();  // image right
  const Vec3 y = z.cross(x);                           // image down
  PinholeCamera c;
  c.R.row(0) = x.transpose();
  c.R.row(1) = y.transpose();
  c.R.row(2) = z.transpose();
  c.t = -c.R * eye;
  c.K << 800, 0, 320, 0, 800, 240, 0, 0, 1;
  return c;
}

// n cameras on an arc (`span` radians, centred on -y: in front of the
// body) of a circle of radius 3 m around it, 1.2 m high.
std::vector<PinholeCamera> ring(int n, double span = 2.0 * std::numbers::pi) {
  std::vector<PinholeCamera> cams;
  for (int i = 0; i < n; ++i) {
    const double a = -0.5 * std::numbers::pi + span * ((i + 0.5) / n - 0.5);
    cams.push_back(look_at({3000.0 * std::cos(a), 3000.0 * std::sin(a), 1200.0}, {0, 0, 1000}));
  }
  return cams;
}

TEST(TriangulateRays, TwoNoiselessRaysGiveThePointExactly) {
  const Vec3 x(123.0, -45.0, 1310.0);
  for (int n : {2, 3, 7}) {
    std::vector<Ray> rays;
    for (const PinholeCamera& c : ring(n, std::numbers::pi)) rays.push_back(camera_ray(c, project_to_pixel(c, x)));
    const RayPoint p = triangulate_rays(rays);
    EXPECT_LT((p.point - x).norm(), 1e-8) << n << " rays";
    EXPECT_LT(p.rms_distance_mm, 1e-8);
    EXPECT_GT(p.conditioning, 1e-3);
  }
  // Two rays by hand: the x axis through (0, 0, 5) and the y axis direction through (2, 0, 0).
  const std::vector<Ray> rays = {{{-7, 0, 5}, {3, 0, 0}}, {{2, 9, 5}, {0, -1, 0}}};
  const RayPoint p = triangulate_rays(rays);
  EXPECT_LT((p.point - Vec3(2, 0, 5)).norm(), 1e-12);
}

TEST(TriangulateRays, ThePixelOfThePointIsOnItsRay) {
  const PinholeCamera c = look_at({2500, -1800, 900}, {0, 0, 1000});
  const Vec3 x(-80, 30, 1500);
  const Vec2 px = project_to_pixel(c, x);
  const Ray r = camera_ray(c, px);
  EXPECT_NEAR(r.direction.norm(), 1.0, 1e-12);
  EXPECT_LT(r.direction.cross(x - r.origin).norm(), 1e-9);
  EXPECT_LT((r.origin - Vec3(2500, -1800, 900)).norm(), 1e-9);
  EXPECT_GT(r.direction.dot(x - r.origin), 0.0);
}

TEST(TriangulateRays, ErrorFallsWithTheNumberOfViews) {
  // 1 pixel of Gaussian noise (focal 800 px at 3 m: about 3.75 mm at the
  // body), 300 random points of a body's size per n; the cameras spread
  // over the half circle in front (two cameras 90 degrees apart; opposite
  // cameras would look along one line and not fix the depth along it).
  std::mt19937 rng(5);
  std::normal_distribution<double> noise(0.0, 1.0);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<double> err;
  std::printf("views  mean error (mm)  rms ray distance (mm)\n");
  for (int n : {2, 3, 4, 6, 8, 12}) {
    const std::vector<PinholeCamera> cams = ring(n, std::numbers::pi);
    double sum = 0.0, ray = 0.0;
    const int trials = 300;
    for (int k = 0; k < trials; ++k) {
      const Vec3 x(300.0 * u(rng), 200.0 * u(rng), 1000.0 + 800.0 * u(rng));
      std::vector<Ray> rays;
      for (const PinholeCamera& c : cams) rays.push_back(camera_ray(c, project_to_pixel(c, x) + Vec2(noise(rng), noise(rng))));
      const RayPoint p = triangulate_rays(rays);
      sum += (p.point - x).norm();
      ray += p.rms_distance_mm;
    }
    err.push_back(sum / trials);
    std::printf("%5d  %15.2f  %21.2f\n", n, sum / trials, ray / trials);
  }
  EXPECT_LT(err.front(), 8.0);
  EXPECT_LT(err.back(), 0.5 * err.front());
  for (size_t i = 1; i < err.size(); ++i) EXPECT_LT(err[i], err[i - 1] * 1.05) << i;
}

TEST(TriangulateRays, RejectsTooFewOrParallelRays) {
  const std::vector<Ray> one = {{{0, 0, 0}, {1, 0, 0}}};
  EXPECT_THROW(triangulate_rays(one), InvalidInput);
  const std::vector<Ray> parallel = {{{0, 0, 0}, {1, 0, 0}}, {{0, 5, 0}, {2, 0, 0}}};
  EXPECT_THROW(triangulate_rays(parallel), InvalidInput);
  const std::vector<Ray> zero = {{{0, 0, 0}, {0, 0, 0}}, {{0, 5, 0}, {2, 0, 0}}};
  EXPECT_THROW(triangulate_rays(zero), InvalidInput);
  PinholeCamera c;
  c.K.setZero();
  EXPECT_THROW(camera_ray(c, {1, 1}), InvalidInput);
}

TEST(KeypointViews, ReadsTheFileAndTriangulatesWhatTwoViewsSee) {
  const std::vector<PinholeCamera> cams = ring(3);
  const Vec3 shoulder(180, 0, 1420), elbow(420, 10, 1200);
  nlohmann::json j;
  j["units"] = "cm";
  for (size_t i = 0; i < cams.size(); ++i) {
    nlohmann::json c;
    c["name"] = "cam" + std::to_string(i);
    for (int r = 0; r < 3; ++r) {
      c["K"].push_back({cams[i].K(r, 0), cams[i].K(r, 1), cams[i].K(r, 2)});
      c["R"].push_back({cams[i].R(r, 0), cams[i].R(r, 1), cams[i].R(r, 2)});
    }
    c["t"] = {cams[i].t.x() / 10.0, cams[i].t.y() / 10.0, cams[i].t.z() / 10.0};
    const Vec2 a = project_to_pixel(cams[i], shoulder);
    c["keypoints"]["left_shoulder"] = {a.x(), a.y()};
    if (i == 0) {
      const Vec2 b = project_to_pixel(cams[i], elbow);
      c["keypoints"]["left_elbow"] = {b.x(), b.y()};
    }
    j["cameras"].push_back(c);
  }
  const std::vector<KeypointView> views = keypoint_views_from_json(j, "k.json");
  ASSERT_EQ(views.size(), 3u);
  EXPECT_EQ(views[1].name, "cam1");
  const TriangulatedKeypoints tk = triangulate_keypoints(views);
  ASSERT_EQ(tk.points.count("left_shoulder"), 1u);
  EXPECT_LT((tk.points.at("left_shoulder").point_mm - shoulder).norm(), 1e-6);
  EXPECT_EQ(tk.points.at("left_shoulder").views, 3);
  ASSERT_EQ(tk.skipped.size(), 1u);  // the elbow, seen once
  EXPECT_EQ(tk.skipped[0], "left_elbow");

  nlohmann::json bad = j;
  bad["cameras"][1]["R"][0] = {2, 0, 0};
  try {
    keypoint_views_from_json(bad, "k.json");
    FAIL();
  } catch (const InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find("camera 1"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("rotation"), std::string::npos) << e.what();
  }
  bad = j;
  bad["cameras"][0].erase("K");
  EXPECT_THROW(keypoint_views_from_json(bad, "k.json"), InvalidInput);
  bad = j;
  bad["units"] = "furlong";
  EXPECT_THROW(keypoint_views_from_json(bad, "k.json"), InvalidInput);
  bad = j;
  bad["cameras"][2]["keypoints"]["left_shoulder"] = {1, "x"};
  EXPECT_THROW(keypoint_views_from_json(bad, "k.json"), InvalidInput);
}

}  // namespace
}  // namespace knitforge
