#include "knitforge/render/raster_preview.h"

#include <gtest/gtest.h>

#include <cmath>
#include <set>

#include "knitforge/util/errors.h"
#include "render/render_test_util.h"

namespace knitforge {
namespace {

Camera top_camera(double height) {
  Camera c;
  c.eye = {0, 0, 10};
  c.target = {0, 0, 0};
  c.orthographic = true;
  c.ortho_height = height;
  return c;
}

RasterOptions flat(int w, int h) {
  RasterOptions o;
  o.width = w;
  o.height = h;
  o.shading = false;
  return o;
}

struct Box {
  int x0 = 1 << 30, y0 = 1 << 30, x1 = -1, y1 = -1, count = 0;
};
Box pixels_of(const RgbImage& img, RenderColour c) {
  Box b;
  for (int y = 0; y < img.height; ++y) {
    for (int x = 0; x < img.width; ++x) {
      if (img.at(x, y) != c) continue;
      b.x0 = std::min(b.x0, x);
      b.y0 = std::min(b.y0, y);
      b.x1 = std::max(b.x1, x);
      b.y1 = std::max(b.y1, y);
      ++b.count;
    }
  }
  return b;
}

TEST(Rasterize, QuadFacingTheCameraFillsItsPixelRectangle) {
  // 100 x 100 px over 10 x 10 mm: pixel column = 10 x + 50, row = 50 - 10 y
  const RenderMesh quad = test::rectangle_mesh(-2, -1, 3, 4, 0, {255, 0, 0});
  const RgbImage img = rasterize(std::span(&quad, 1), top_camera(10), flat(100, 100));
  ASSERT_EQ(img.width, 100);
  ASSERT_EQ(img.pixels.size(), 30000u);
  const Box b = pixels_of(img, {255, 0, 0});
  EXPECT_NEAR(b.x0, 30, 1);
  EXPECT_NEAR(b.x1, 79, 1);
  EXPECT_NEAR(b.y0, 10, 1);
  EXPECT_NEAR(b.y1, 59, 1);
  EXPECT_EQ(b.count, (b.x1 - b.x0 + 1) * (b.y1 - b.y0 + 1));  // solid
  EXPECT_EQ(img.at(0, 0), (RenderColour{255, 255, 255}));
}

TEST(Rasterize, NearerTriangleWinsInEitherOrder) {
  std::vector<RenderMesh> scene = {test::rectangle_mesh(-3, -3, 1, 1, -1, {255, 0, 0}),
                                   test::rectangle_mesh(-1, -1, 3, 3, 1, {0, 255, 0})};
  for (int order = 0; order < 2; ++order) {
    const RgbImage img = rasterize(scene, top_camera(10), flat(100, 100));
    // overlap [-1, 1]^2 -> pixels 40..59: green (the z = 1 quad is nearer)
    for (int y = 41; y <= 58; ++y) {
      for (int x = 41; x <= 58; ++x) ASSERT_EQ(img.at(x, y), (RenderColour{0, 255, 0})) << x << "," << y;
    }
    EXPECT_EQ(img.at(25, 75), (RenderColour{255, 0, 0}));
    std::swap(scene[0], scene[1]);
  }
}

TEST(Rasterize, BackFacesAreCulledUnlessAsked) {
  const RenderMesh back = test::rectangle_mesh(-1, -1, 1, 1, 0, {0, 0, 255}, /*flip=*/true);
  RasterOptions o = flat(50, 50);
  EXPECT_EQ(pixels_of(rasterize(std::span(&back, 1), top_camera(10), o), {0, 0, 255}).count, 0);
  o.cull_back_faces = false;
  EXPECT_EQ(pixels_of(rasterize(std::span(&back, 1), top_camera(10), o), {0, 0, 255}).count, 100);
}

TEST(Rasterize, LambertShadingDependsOnTheNormal) {
  RenderMesh quad = test::rectangle_mesh(-1, -1, 1, 1, 0, {200, 200, 200});
  RasterOptions o = flat(20, 20);
  o.shading = true;
  o.ambient = 0.25;
  o.light = {0, 0, 1};
  const RgbImage lit = rasterize(std::span(&quad, 1), top_camera(4), o);
  EXPECT_EQ(lit.at(10, 10), (RenderColour{200, 200, 200}));  // n . l = 1
  quad.normals.assign(4, Vec3(1, 0, 0));                     // n . l = 0: ambient only
  const RgbImage dark = rasterize(std::span(&quad, 1), top_camera(4), o);
  EXPECT_EQ(dark.at(10, 10), (RenderColour{50, 50, 50}));
}

TEST(Rasterize, PerspectiveMakesFartherObjectsSmaller) {
  Camera c;
  c.eye = {0, 0, 10};
  c.target = {0, 0, 0};
  const RenderMesh near_quad = test::rectangle_mesh(-1, -1, 1, 1, 0, {255, 0, 0});
  const RenderMesh far_quad = test::rectangle_mesh(-1, -1, 1, 1, -10, {255, 0, 0});
  const Box a = pixels_of(rasterize(std::span(&near_quad, 1), c, flat(400, 400)), {255, 0, 0});
  const Box b = pixels_of(rasterize(std::span(&far_quad, 1), c, flat(400, 400)), {255, 0, 0});
  // 2 mm at 10 mm with a 30 degree field of view: 2 / (10 tan 15deg) of 2 NDC units
  const double expected = 400 * 0.5 * 2.0 / (10.0 * std::tan(15.0 * 3.14159265358979 / 180.0));
  EXPECT_NEAR(a.x1 - a.x0 + 1, expected, 1.0);
  EXPECT_NEAR(b.x1 - b.x0 + 1, expected / 2, 1.0);  // twice the distance, half the size
  EXPECT_NEAR((a.x0 + a.x1) / 2.0, 199.5, 1.0);
}

TEST(Rasterize, EdgeLinesOutlineTheQuad) {
  RenderMesh quad = test::rectangle_mesh(-2, -2, 2, 2, 0, {255, 0, 0});
  quad.lines = {{0, 1}, {1, 2}, {2, 3}, {3, 0}};
  RasterOptions o = flat(100, 100);
  o.edges = true;
  o.edge_colour = {0, 0, 0};
  const RgbImage img = rasterize(std::span(&quad, 1), top_camera(10), o);
  const Box e = pixels_of(img, {0, 0, 0});
  EXPECT_NEAR(e.x0, 30, 1);
  EXPECT_NEAR(e.x1, 70, 1);
  EXPECT_EQ(img.at(50, 50), (RenderColour{255, 0, 0}));  // no diagonal
  EXPECT_GT(e.count, 150);
}

TEST(Rasterize, RejectsBadOptions) {
  const RenderMesh quad = test::rectangle_mesh(-1, -1, 1, 1, 0, {255, 0, 0});
  RasterOptions o = flat(0, 10);
  EXPECT_THROW(rasterize(std::span(&quad, 1), top_camera(4), o), InvalidInput);
  o = flat(10, 10);
  o.ambient = 2;
  EXPECT_THROW(rasterize(std::span(&quad, 1), top_camera(4), o), InvalidInput);
}

TEST(StitchMeshRenderMesh, ColoursByCourseAndMarksShaping) {
  // two knit stitches in course 0, one knit and one short-row end in course 1
  StitchMesh sm;
  sm.vertices = {{0, 0, 0}, {1, 0, 0}, {2, 0, 0}, {0, 1, 0}, {1, 1, 0}, {2, 1, 0}, {0, 2, 0}, {1, 2, 0}};
  Stitch a;
  a.v = {0, 1, 4, 3};
  a.course = 0;
  Stitch b = a;
  b.v = {1, 2, 5, 4};
  Stitch c = a;
  c.v = {3, 4, 7, 6};
  c.course = 1;
  Stitch d;
  d.type = StitchType::ShortRowRight;  // BL A TL
  d.v = {4, 5, 7};
  d.course = 1;
  sm.stitches = {a, b, c, d};
  StitchColourOptions o;
  const RenderMesh m = stitch_mesh_render_mesh(sm, o);
  ASSERT_EQ(m.mesh.num_faces(), 7);
  ASSERT_EQ(m.face_colours.size(), 7u);
  EXPECT_EQ(m.face_colours[0], o.course_colours[0]);
  EXPECT_EQ(m.face_colours[3], o.course_colours[0]);
  EXPECT_EQ(m.face_colours[4], o.course_colours[1]);
  EXPECT_EQ(m.face_colours[6], o.type_colours[static_cast<int>(StitchType::ShortRowRight)]);
  EXPECT_EQ(m.lines.size(), 11u);  // unique stitch edges
  ASSERT_EQ(m.normals.size(), sm.vertices.size());
  EXPECT_NEAR(m.normals[4].z(), 1.0, 1e-12);
  sm.stitches[1].v[2] = 99;
  EXPECT_THROW(stitch_mesh_render_mesh(sm), InvalidInput);
}

}  // namespace
}  // namespace knitforge
