#include "knitforge/render/camera.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "knitforge/util/errors.h"

namespace knitforge {
namespace {

TEST(Camera, PerspectiveNdcOfKnownPoints) {
  Camera c;
  c.eye = {0, 0, 10};
  c.target = {0, 0, 0};
  c.fov_y_degrees = 90.0;  // tan(45 deg) = 1
  c.aspect = 2.0;
  const ViewTransform t = view_transform(c);
  const Vec3 a = t.to_ndc({2, 5, 5});  // 5 mm in front of the eye
  EXPECT_NEAR(a.x(), 2.0 / 5.0 / 2.0, 1e-12);
  EXPECT_NEAR(a.y(), 1.0, 1e-12);
  EXPECT_NEAR(a.z(), -1.0 / 5.0, 1e-12);
  EXPECT_LT(t.to_ndc({0, 0, 5}).z(), t.to_ndc({0, 0, 0}).z());  // nearer = smaller depth
  EXPECT_FALSE(t.in_front({0, 0, 11}));
}

TEST(Camera, OrthographicNdcOfKnownPoints) {
  Camera c;
  c.eye = {0, 0, 10};
  c.target = {0, 0, 0};
  c.up = {1, 0, 0};  // image up = +x, image right = forward x up = -y
  c.orthographic = true;
  c.ortho_height = 4.0;
  const ViewTransform t = view_transform(c);
  const Vec3 a = t.to_ndc({1, 1, 3});
  EXPECT_NEAR(a.y(), 0.5, 1e-12);
  EXPECT_NEAR(a.x(), -0.5, 1e-12);
  EXPECT_NEAR(a.z(), 7.0, 1e-12);
  EXPECT_TRUE(t.in_front({0, 0, 50}));
}

TEST(Camera, FramingKeepsEveryCornerInside) {
  const std::vector<Vec3> pts = {{-10, 3, 0}, {40, -7, 2}, {5, 20, -4}};
  for (bool ortho : {false, true}) {
    for (double aspect : {0.5, 1.0, 2.5}) {
      const Camera c = frame_points(pts, aspect, ortho);
      const ViewTransform t = view_transform(c);
      double extent = 0.0;
      for (int k = 0; k < 8; ++k) {
        const Vec3 p(k & 1 ? 40 : -10, k & 2 ? 20 : -7, k & 4 ? 2 : -4);
        ASSERT_TRUE(t.in_front(p));
        const Vec3 q = t.to_ndc(p);
        EXPECT_LE(std::abs(q.x()), 1.0 / 1.05 + 1e-9);
        EXPECT_LE(std::abs(q.y()), 1.0 / 1.05 + 1e-9);
        extent = std::max({extent, std::abs(q.x()), std::abs(q.y())});
      }
      EXPECT_GT(extent, 0.9 / 1.05) << "framing too loose";  // tight in at least one direction
    }
  }
}

TEST(Camera, RejectsBadCameras) {
  Camera c;
  c.target = c.eye;
  EXPECT_THROW(view_transform(c), InvalidInput);
  c = Camera{};
  c.up = {0, 0, 1};  // parallel to the view direction
  EXPECT_THROW(view_transform(c), InvalidInput);
  c = Camera{};
  c.fov_y_degrees = 180;
  EXPECT_THROW(view_transform(c), InvalidInput);
  c = Camera{};
  c.orthographic = true;
  c.ortho_height = 0;
  EXPECT_THROW(view_transform(c), InvalidInput);
  EXPECT_THROW(frame_points({}, 1.0), InvalidInput);
}

}  // namespace
}  // namespace knitforge
