#include "knitforge/body/depth_image.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <random>
#include <string>

#include <unistd.h>

#include "knitforge/io/png_image.h"
#include "knitforge/util/errors.h"

using namespace knitforge;

namespace {

std::string temp_path(const std::string& name) {
  return (std::filesystem::temp_directory_path() /
          (std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()) + "_" +
           std::to_string(::getpid()) + "_" + name))
      .string();
}

DepthCamera small_camera(double unit = 1.0) {
  DepthCamera c;
  c.width = 7;
  c.height = 5;
  c.K << 300.0, 0.0, 3.0, 0.0, 310.0, 2.0, 0.0, 0.0, 1.0;
  c.depth_unit_mm = unit;
  return c;
}

template <class F>
std::string message_of(F&& f) {
  try {
    f();
  } catch (const std::exception& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST(DepthImage, SixteenBitPngRoundTripsExactlyInDepthUnits) {
  for (double unit : {1.0, 0.25}) {
    const DepthCamera cam = small_camera(unit);
    DepthImage img{cam.width, cam.height, std::vector<double>(35)};
    for (size_t i = 0; i < img.depth_mm.size(); ++i) img.depth_mm[i] = unit * static_cast<double>((i * 1877) % 65536);
    img.depth_mm[3] = 0.0;                 // no measurement
    img.depth_mm[4] = 65535.0 * unit;      // the deepest storable
    const std::string path = temp_path("depth.png");
    write_depth_image(path, img, cam);
    const DepthImage back = read_depth_image(path, cam);
    EXPECT_EQ(back.width, 7);
    EXPECT_EQ(back.height, 5);
    EXPECT_EQ(back.depth_mm, img.depth_mm);
    std::filesystem::remove(path);
  }
}

TEST(DepthImage, DepthsAreRoundedToTheUnitAndAPositiveDepthStaysMeasured) {
  const DepthCamera cam = small_camera(1.0);
  DepthImage img{cam.width, cam.height, std::vector<double>(35, 1000.4)};
  img.depth_mm[0] = 0.2;  // would round to 0 = no measurement
  img.depth_mm[1] = 999.6;
  const std::string path = temp_path("depth.png");
  write_depth_image(path, img, cam);
  const DepthImage back = read_depth_image(path, cam);
  EXPECT_EQ(back.depth_mm[0], 1.0);
  EXPECT_EQ(back.depth_mm[1], 1000.0);
  EXPECT_EQ(back.depth_mm[2], 1000.0);
  std::filesystem::remove(path);
}

TEST(DepthImage, BadImagesAreRefusedWithAClearMessage) {
  const DepthCamera cam = small_camera();
  const std::string path = temp_path("rgb.png");
  write_png(path, RgbImage{7, 5, std::vector<uint8_t>(7 * 5 * 3, 100)});
  const std::string m = message_of([&] { read_depth_image(path, cam); });
  EXPECT_NE(m.find("8-bit RGB PNG"), std::string::npos) << m;
  EXPECT_NE(m.find("16-bit greyscale"), std::string::npos) << m;
  EXPECT_THROW(read_depth_image(path, cam), IOError);
  // The wrong camera for the image's size.
  DepthImage img{7, 5, std::vector<double>(35, 500.0)};
  write_depth_image(path, img, cam);
  DepthCamera other = cam;
  other.width = 8;
  const std::string m2 = message_of([&] { read_depth_image(path, other); });
  EXPECT_NE(m2.find("7x5 depth image"), std::string::npos) << m2;
  EXPECT_NE(m2.find("8x5 camera"), std::string::npos) << m2;
  // Deeper than 65535 units: refused, nothing written.
  std::filesystem::remove(path);
  img.depth_mm[9] = 70000.0;
  const std::string m3 = message_of([&] { write_depth_image(path, img, cam); });
  EXPECT_NE(m3.find("pixel (2, 1)"), std::string::npos) << m3;
  EXPECT_FALSE(std::filesystem::exists(path));
  EXPECT_THROW(read_depth_image(temp_path("missing.png"), cam), IOError);
}

TEST(DepthImage, IntrinsicsJsonRoundTripsAndNamesMissingOrBadFields) {
  const DepthCamera cam = small_camera(0.5);
  const DepthCamera back = depth_camera_from_json(depth_camera_to_json(cam), "cam.json");
  EXPECT_EQ(back.width, cam.width);
  EXPECT_EQ(back.height, cam.height);
  EXPECT_EQ(back.K, cam.K);
  EXPECT_EQ(back.depth_unit_mm, 0.5);
  nlohmann::json j = depth_camera_to_json(cam);
  j.erase("K");
  EXPECT_NE(message_of([&] { depth_camera_from_json(j, "cam.json"); }).find("cam.json: missing \"K\""),
            std::string::npos);
  j = depth_camera_to_json(cam);
  j["fx"] = 300;
  EXPECT_NE(message_of([&] { depth_camera_from_json(j, "cam.json"); }).find("unknown key \"fx\""), std::string::npos);
  j = depth_camera_to_json(cam);
  j["width"] = 12.5;
  EXPECT_NE(message_of([&] { depth_camera_from_json(j, "cam.json"); }).find("cam.json: width"), std::string::npos);
  j = depth_camera_to_json(cam);
  j["K"][0][0] = -300;
  EXPECT_NE(message_of([&] { depth_camera_from_json(j, "cam.json"); }).find("fx, fy > 0"), std::string::npos);
  j = depth_camera_to_json(cam);
  j["depth_unit_mm"] = 0;
  EXPECT_THROW(depth_camera_from_json(j, "cam.json"), InvalidInput);
  // Defaults: 1 mm units when not given.
  j.erase("depth_unit_mm");
  EXPECT_EQ(depth_camera_from_json(j, "cam.json").depth_unit_mm, 1.0);
}

TEST(DepthImage, BackProjectionInvertsTheProjection) {
  DepthCamera cam = small_camera();
  cam.K(0, 1) = 1.5;  // with skew
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-400.0, 400.0), z(300.0, 4000.0);
  for (int i = 0; i < 200; ++i) {
    const Vec3 x(u(rng), u(rng), z(rng));
    const Vec3 p = cam.K * x;
    const Vec3 back = back_project(cam, p.x() / p.z(), p.y() / p.z(), x.z());
    EXPECT_LT((back - x).norm(), 1e-9 * x.norm());
  }
}

TEST(DepthImage, PointsOfTheMeasuredPixelsInRangeInPixelOrder) {
  const DepthCamera cam = small_camera();
  DepthImage img{7, 5, std::vector<double>(35, 0.0)};
  img.depth_mm[2 * 7 + 3] = 1000.0;  // the principal point (3, 2)
  img.depth_mm[4 * 7 + 6] = 2000.0;
  img.depth_mm[0] = 5000.0;
  std::vector<int> pixels;
  const std::vector<Vec3> pts = depth_to_points(img, cam, {0.0, 3000.0}, &pixels);
  ASSERT_EQ(pts.size(), 2u);
  EXPECT_EQ(pixels, (std::vector<int>{17, 34}));
  EXPECT_LT((pts[0] - Vec3(0.0, 0.0, 1000.0)).norm(), 1e-12);
  EXPECT_NEAR(pts[1].x(), 2000.0 * 3.0 / 300.0, 1e-12);
  EXPECT_NEAR(pts[1].y(), 2000.0 * 2.0 / 310.0, 1e-12);
  EXPECT_EQ(depth_to_points(img, cam).size(), 3u);
}
