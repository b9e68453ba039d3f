#include "knitforge/render/vector_drawing.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "knitforge/render/yarn_tubes.h"
#include "knitforge/util/errors.h"
#include "render/render_test_util.h"

namespace knitforge {
namespace {

constexpr double kPi = std::numbers::pi;

// Orthographic camera on +z looking down -z; 1 NDC unit = height / 2 mm.
Camera top_camera(double height) {
  Camera c;
  c.eye = {0, 0, 10};
  c.target = {0, 0, 0};
  c.up = {0, 1, 0};
  c.orthographic = true;
  c.ortho_height = height;
  return c;
}

double visible_length(const VectorDrawing& d, int mesh, double scale) {
  double len = 0.0;
  for (const auto& e : d.edges) {
    if (e.mesh == mesh) len += (e.b - e.a).norm() * scale;
  }
  return len;
}

double signed_area(const std::vector<Vec2>& ring) {
  double a = 0.0;
  for (size_t i = 0; i < ring.size(); ++i) {
    const Vec2& p = ring[i];
    const Vec2& q = ring[(i + 1) % ring.size()];
    a += p.x() * q.y() - q.x() * p.y();
  }
  return 0.5 * a;
}

// Filled area (mm^2) of the regions showing `mesh`.
double region_area(const VectorDrawing& d, int mesh, double scale) {
  double a = 0.0;
  for (const auto& r : d.regions) {
    if (r.mesh != mesh) continue;
    for (const auto& ring : r.rings) a += signed_area(ring) * scale * scale;  // holes are clockwise
  }
  return a;
}

TEST(VectorDrawing, SingleQuadHasFourVisibleEdgesAndOneRegion) {
  const RenderMesh quad = test::rectangle_mesh(-1, -0.5, 2, 1.5, 0, {255, 0, 0});
  const VectorDrawing d = vector_drawing(std::span(&quad, 1), top_camera(8));
  EXPECT_EQ(d.front_faces, 2);
  EXPECT_EQ(d.contour_segments, 4);
  EXPECT_EQ(d.edges.size(), 4u);
  EXPECT_EQ(d.hidden_edges, 0);
  for (const auto& e : d.edges) EXPECT_TRUE(e.boundary);
  EXPECT_NEAR(visible_length(d, 0, 4.0), 2 * (3 + 2), 1e-12);
  ASSERT_EQ(d.regions.size(), 1u);
  EXPECT_EQ(d.regions[0].colour, (RenderColour{255, 0, 0}));
  EXPECT_NEAR(region_area(d, 0, 4.0), 6.0, 1e-12);
}

TEST(VectorDrawing, BackFacingQuadDrawsNothing) {
  const RenderMesh quad = test::rectangle_mesh(-1, -1, 1, 1, 0, {255, 0, 0}, /*flip=*/true);
  const VectorDrawing d = vector_drawing(std::span(&quad, 1), top_camera(8));
  EXPECT_EQ(d.front_faces, 0);
  EXPECT_TRUE(d.edges.empty());
  EXPECT_TRUE(d.regions.empty());
}

TEST(VectorDrawing, PerspectiveQuadStillHasFourEdges) {
  const RenderMesh quad = test::rectangle_mesh(-1, -1, 1, 1, 0, {0, 0, 255});
  Camera c;
  c.eye = {0.3, -0.2, 6};
  c.target = {0, 0, 0};
  const VectorDrawing d = vector_drawing(std::span(&quad, 1), c);
  EXPECT_EQ(d.edges.size(), 4u);
  ASSERT_EQ(d.regions.size(), 1u);
  EXPECT_EQ(d.regions[0].colour, (RenderColour{0, 0, 255}));
}

// A unit sphere in front of a 4 x 4 square whose right side x = 2 passes
// through the sphere's centre: the sphere hides the part |y| < 1 of that side.
TEST(VectorDrawing, SphereInFrontOfAPlaneHidesPartOfTheBoundary) {
  const int seg = 64;
  std::vector<RenderMesh> scene;
  scene.push_back(test::uv_sphere({2, 0, 0}, 1.0, seg, 32, {200, 50, 50}));
  scene.push_back(test::rectangle_mesh(-2, -2, 2, 2, -3, {50, 50, 200}));
  const VectorDrawing d = vector_drawing(scene, top_camera(8));
  const double scale = 4.0;
  // the silhouette is the equator polygon (a vertex ring on z = 0), all visible
  const double polygon = seg * 2.0 * std::sin(kPi / seg);
  EXPECT_NEAR(visible_length(d, 0, scale), polygon, 1e-9);
  // the polygon has vertices at (2, +-1): exactly 2 mm of the square's side is hidden
  EXPECT_NEAR(visible_length(d, 1, scale), 16.0 - 2.0, 1e-9);
  EXPECT_GT(d.hidden_edges, 0);
  for (const auto& e : d.edges) {
    if (e.mesh != 1) continue;
    const Vec2 m = 0.5 * (e.a + e.b) * scale;
    EXPECT_FALSE(std::abs(m.x() - 2.0) < 1e-9 && std::abs(m.y()) < 1.0) << "hidden side drawn at y=" << m.y();
  }
  // regions: the whole sphere disc in red, the square minus the half disc in blue
  const double disc = 0.5 * seg * std::sin(2 * kPi / seg);
  EXPECT_NEAR(region_area(d, 0, scale), disc, 1e-9);
  EXPECT_NEAR(region_area(d, 1, scale), 16.0 - 0.5 * disc, 1e-9);
  for (const auto& r : d.regions) EXPECT_EQ(r.colour, scene[static_cast<size_t>(r.mesh)].colour);
}

TEST(VectorDrawing, TwoCrossingTubesHideTheBackTubeUnderTheFront) {
  TubeOptions o;
  o.plies = 16;
  o.vertices_per_ply = 1;
  o.ply_depth = 0.0;
  o.twist_per_mm = 0.0;
  o.capped = false;
  const double r = 0.5;
  const std::vector<Vec3> a = {{-3, 0, 0}, {3, 0, 0}};
  const std::vector<Vec3> b = {{0, -3, -2}, {0, 3, -2}};
  std::vector<RenderMesh> scene = {yarn_tube(a, o, r, {255, 0, 0}), yarn_tube(b, o, r, {0, 0, 255})};
  const VectorDrawing d = vector_drawing(scene, top_camera(10));
  const double scale = 5.0;
  // front tube: two 6 mm silhouettes + two end arcs projecting to 2r segments
  EXPECT_NEAR(visible_length(d, 0, scale), 2 * 6.0 + 2 * 2 * r, 1e-9);
  // back tube: its silhouettes lose 2r each where the front tube crosses
  EXPECT_NEAR(visible_length(d, 1, scale), 2 * (6.0 - 2 * r) + 2 * 2 * r, 1e-9);
  for (const auto& e : d.edges) {
    if (e.mesh != 1) continue;
    const Vec2 m = 0.5 * (e.a + e.b) * scale;
    EXPECT_GE(std::abs(m.y()), r - 1e-9) << "back tube drawn under the front tube at y=" << m.y();
  }
  // the crossing square is red (front tube), the back tube shows on both sides
  EXPECT_NEAR(region_area(d, 0, scale), 6.0 * 2 * r, 1e-9);
  EXPECT_NEAR(region_area(d, 1, scale), (6.0 - 2 * r) * 2 * r, 1e-9);
}

TEST(VectorDrawing, SvgHasRegionsAndStrokes) {
  const RenderMesh quad = test::rectangle_mesh(-1, -1, 1, 1, 0, {255, 0, 0});
  const VectorDrawing d = vector_drawing(std::span(&quad, 1), top_camera(4));
  SvgOptions o;
  o.width = 200;
  const std::string svg = vector_drawing_svg(d, o);
  EXPECT_NE(svg.find("width=\"200\" height=\"200\""), std::string::npos);
  EXPECT_NE(svg.find("fill=\"#ff0000\""), std::string::npos);
  // the quad spans NDC [-0.5, 0.5]: pixels 50..150
  EXPECT_NE(svg.find("50.000 150.000"), std::string::npos) << svg;
  EXPECT_NE(svg.find("150.000 50.000"), std::string::npos) << svg;
  o.width = 0;
  EXPECT_THROW(vector_drawing_svg(d, o), InvalidInput);
}

TEST(VectorDrawing, RejectsBadCameraAndMesh) {
  RenderMesh quad = test::rectangle_mesh(-1, -1, 1, 1, 0, {255, 0, 0});
  Camera c = top_camera(4);
  c.target = c.eye;
  EXPECT_THROW(vector_drawing(std::span(&quad, 1), c), InvalidInput);
  quad.mesh.faces[0][1] = 7;
  EXPECT_THROW(vector_drawing(std::span(&quad, 1), top_camera(4)), InvalidInput);
}

}  // namespace
}  // namespace knitforge
