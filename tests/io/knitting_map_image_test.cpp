#include "knitforge/io/knitting_map_image.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <memory>

#include <png.h>

#include "io/io_test_util.h"
#include "knitforge/io/colours.h"

namespace knitforge {

// For readable failure messages.
void PrintTo(const Rgb& c, std::ostream* o) { *o << "(" << int(c.r) << ", " << int(c.g) << ", " << int(c.b) << ")"; }

namespace {

using test::TempDir;

struct Picture {
  int width = 0, height = 0;
  std::vector<uint8_t> rgb;
  Rgb at(int x, int y) const {
    const uint8_t* p = &rgb[(static_cast<size_t>(y) * width + x) * 3];
    return {p[0], p[1], p[2]};
  }
};

Picture read_png(const std::string& path) {
  Picture pic;
  png_image image{};
  image.version = PNG_IMAGE_VERSION;
  if (!png_image_begin_read_from_file(&image, path.c_str())) {
    ADD_FAILURE() << "libpng cannot read " << path << ": " << image.message;
    return pic;
  }
  image.format = PNG_FORMAT_RGB;
  pic.width = static_cast<int>(image.width);
  pic.height = static_cast<int>(image.height);
  pic.rgb.resize(PNG_IMAGE_SIZE(image));
  if (!png_image_finish_read(&image, nullptr, pic.rgb.data(), 0, nullptr)) {
    ADD_FAILURE() << "libpng cannot decode " << path << ": " << image.message;
  }
  return pic;
}

// Row 0 (left to right): K L R I D; row 1 (right to left): K K(yarn 2) C . K.
KnittingMap test_map() {
  KnittingMap m(2, 5, CellType::Knit);
  m.at(0, 1) = CellType::ShortRowLeft;
  m.at(0, 2) = CellType::ShortRowRight;
  m.at(0, 3) = CellType::Increase;
  m.at(0, 4) = CellType::Decrease;
  m.at(1, 2) = CellType::Collapsed;
  m.at(1, 3) = CellType::Empty;
  m.set_yarn(1, 1, 2);
  return m;
}

TEST(KnittingMapImage, PngHasTheDocumentedGeometryAndColours) {
  TempDir dir;
  const KnittingMap m = test_map();
  const int s = 10;
  write_knitting_map_image(dir.path("map.png"), m, {.cell_size = s});
  const Picture pic = read_png(dir.path("map.png"));
  ASSERT_EQ(pic.width, 5 * s + 1);
  ASSERT_EQ(pic.height, 2 * s + 1);
  // Cell (r, c) occupies x in [c*s, (c+1)*s], y in [(rows-1-r)*s, ...].
  auto px = [&](int r, int c, int dx, int dy) { return pic.at(c * s + dx, (1 - r) * s + dy); };
  const Rgb light{166, 206, 227}, dark{31, 120, 180}, grey{170, 170, 170}, white{255, 255, 255};
  EXPECT_EQ(px(0, 0, 5, 5), light);
  EXPECT_EQ(px(1, 0, 5, 5), dark);
  EXPECT_EQ(px(1, 4, 5, 5), dark);
  EXPECT_EQ(px(1, 2, 5, 5), grey);
  EXPECT_EQ(px(1, 3, 5, 5), white);
  EXPECT_EQ(px(1, 1, 5, 5), mix(dark, yarn_colour(2), 0.45));
  EXPECT_NE(px(1, 1, 5, 5), dark);
  EXPECT_EQ(px(0, 0, 0, 0), (Rgb{150, 150, 150}));  // grid line
  EXPECT_EQ(px(0, 0, s, 5), (Rgb{150, 150, 150}));
  // Glyphs: the centre and the side opposite the apex carry the type colour;
  // the corners on the apex side keep the background.
  const Rgb srl = stitch_type_colour(StitchType::ShortRowLeft), srr = stitch_type_colour(StitchType::ShortRowRight),
            inc = stitch_type_colour(StitchType::Increase), dec = stitch_type_colour(StitchType::Decrease);
  EXPECT_EQ(px(0, 1, 5, 5), srl);
  EXPECT_EQ(px(0, 1, 7, 5), srl);  // near the base (right)
  EXPECT_EQ(px(0, 1, 1, 1), light);  // apex side (left) corners
  EXPECT_EQ(px(0, 1, 1, 8), light);
  EXPECT_EQ(px(0, 2, 5, 5), srr);
  EXPECT_EQ(px(0, 2, 2, 5), srr);
  EXPECT_EQ(px(0, 2, 8, 1), light);
  EXPECT_EQ(px(0, 2, 8, 8), light);
  EXPECT_EQ(px(0, 3, 5, 5), inc);
  EXPECT_EQ(px(0, 3, 5, 2), inc);    // base at the top
  EXPECT_EQ(px(0, 3, 1, 8), light);  // apex at the bottom
  EXPECT_EQ(px(0, 3, 8, 8), light);
  EXPECT_EQ(px(0, 4, 5, 5), dec);
  EXPECT_EQ(px(0, 4, 5, 7), dec);
  EXPECT_EQ(px(0, 4, 1, 1), light);
  EXPECT_EQ(px(0, 4, 8, 1), light);
}

TEST(KnittingMapImage, SvgHasOneRectanglePerCellGlyphsLabelsAndLegend) {
  KnittingMap m(23, 31, CellType::Knit);
  m.at(3, 4) = CellType::ShortRowLeft;
  m.at(5, 6) = CellType::Increase;
  m.at(7, 8) = CellType::Collapsed;
  m.set_yarn(1, 1, 3);
  const std::string svg = knitting_map_svg(m);
  auto count = [&](const std::string& needle) {
    size_t n = 0;
    for (size_t p = svg.find(needle); p != std::string::npos; p = svg.find(needle, p + 1)) ++n;
    return n;
  };
  EXPECT_EQ(count("<rect class=\"cell\""), 23u * 31u);
  EXPECT_EQ(count("<polygon class=\"glyph\""), 2u);
  EXPECT_EQ(count("class=\"course-label\""), 3u);  // 0, 10, 20
  EXPECT_EQ(count("class=\"wale-label\""), 4u);    // 0, 10, 20, 30
  EXPECT_EQ(count("class=\"legend-swatch\""), 9u);  // 8 cell kinds + yarn 3
  EXPECT_CONTAINS(svg, ">yarn 3</text>");
  EXPECT_EQ(svg.rfind("</svg>\n"), svg.size() - 7);
}

TEST(KnittingMapImage, OptionsAndMapsAreChecked) {
  TempDir dir;
  const KnittingMap m = test_map();
  EXPECT_CONTAINS(test::invalid_input([&] { write_knitting_map_image(dir.path("m.jpg"), m); }),
                  "unknown picture format '.jpg'");
  EXPECT_CONTAINS(test::invalid_input([&] { write_knitting_map_png(dir.path("m.png"), m, {.cell_size = 3}); }),
                  "cell size 3");
  KnittingMap bad = m;
  bad.direction.pop_back();
  EXPECT_CONTAINS(test::invalid_input([&] { write_knitting_map_svg(dir.path("m.svg"), bad); }), "wrong size");
  EXPECT_CONTAINS(test::invalid_input([&] {
                    write_knitting_map_png(dir.path("m.png"), KnittingMap(3000, 3000), {.cell_size = 20});
                  }),
                  "too large");
  EXPECT_EQ(dir.num_files(), 0u);
  // The same map gives the same bytes.
  write_knitting_map_image(dir.path("a.png"), m);
  write_knitting_map_image(dir.path("b.png"), m);
  EXPECT_EQ(dir.read("a.png"), dir.read("b.png"));
  write_knitting_map_image(dir.path("a.svg"), m);
  EXPECT_EQ(dir.read("a.svg"), knitting_map_svg(m));
}

}  // namespace
}  // namespace knitforge

namespace knitforge {
namespace {

KnittingMap tube_2x4() {
  KnittingMap m(2, 4, CellType::Knit);
  m.direction = {1, 1};
  m.seam = {0, 1};
  return m;
}

TEST(KnittingMapImage, TubeShowsTheFoldAndEachRoundsSeam) {
  test::TempDir dir;
  const int s = 10;
  write_knitting_map_image(dir.path("t.png"), tube_2x4(), {.cell_size = s});
  const Picture pic = read_png(dir.path("t.png"));
  const Rgb fold{20, 20, 20}, seam{215, 25, 28}, light{166, 206, 227};
  // the fold between columns 1 and 2, the whole height
  EXPECT_EQ(pic.at(2 * s, 3), fold);
  EXPECT_EQ(pic.at(2 * s, 2 * s - 3), fold);
  // row 1 (top) starts at line 1, row 0 (bottom) at line 0
  EXPECT_EQ(pic.at(1 * s, 3), seam);
  EXPECT_EQ(pic.at(0, s + 3), seam);
  EXPECT_EQ(pic.at(1 * s, s + 3), Rgb({150, 150, 150}));  // plain grid line where row 0 has no seam
  EXPECT_EQ(pic.at(5, 5), light);
  const std::string svg = knitting_map_svg(tube_2x4());
  auto count = [&](const std::string& what) {
    int n = 0;
    for (size_t i = svg.find(what); i != std::string::npos; i = svg.find(what, i + 1)) ++n;
    return n;
  };
  EXPECT_EQ(count("class=\"fold\""), 1);
  EXPECT_EQ(count("class=\"seam\""), 2);
  EXPECT_EQ(count(">front</text>"), 1);
  EXPECT_EQ(count(">back</text>"), 1);
  // a sheet draws none of it
  KnittingMap sheet = tube_2x4();
  sheet.seam.clear();
  EXPECT_EQ(knitting_map_svg(sheet).find("class=\"seam\""), std::string::npos);
}

}  // namespace
}  // namespace knitforge
