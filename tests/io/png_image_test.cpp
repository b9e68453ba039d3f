#include "knitforge/io/png_image.h"

#include <gtest/gtest.h>

#include "io/io_test_util.h"

namespace knitforge {
namespace {

using test::TempDir;

TEST(Png, RoundTripIsExact) {
  TempDir dir;
  RgbImage img;
  img.width = 7;
  img.height = 5;
  for (int i = 0; i < 7 * 5 * 3; ++i) img.pixels.push_back(static_cast<uint8_t>(i * 37 % 256));
  write_png(dir.path("a.png"), img);
  EXPECT_EQ(dir.read("a.png").substr(1, 3), "PNG");
  const RgbImage back = read_png(dir.path("a.png"));
  EXPECT_EQ(back.width, 7);
  EXPECT_EQ(back.height, 5);
  EXPECT_EQ(back.pixels, img.pixels);
  EXPECT_EQ(back.at(1, 0), (RenderColour{111, 148, 185}));
}

TEST(Png, BadInput) {
  TempDir dir;
  RgbImage img;
  img.width = 2;
  img.height = 2;
  img.pixels.resize(11);
  EXPECT_CONTAINS(test::invalid_input([&] { write_png(dir.path("b.png"), img); }), "11 pixel bytes");
  img.width = 0;
  test::invalid_input([&] { write_png(dir.path("b.png"), img); });
  EXPECT_EQ(dir.num_files(), 0u);
  const std::string p = dir.write("c.png", "not a png at all");
  EXPECT_CONTAINS(test::io_error([&] { read_png(p); }), "not a PNG");
  RgbImage ok{1, 1, {1, 2, 3}};
  write_png(dir.path("d.png"), ok);
  const std::string data = dir.read("d.png");
  const std::string cut = dir.write("e.png", data.substr(0, data.size() / 2));
  EXPECT_CONTAINS(test::io_error([&] { read_png(cut); }), "e.png");
  test::io_error([&] { read_png(dir.path("missing.png")); });
}

}  // namespace
}  // namespace knitforge
