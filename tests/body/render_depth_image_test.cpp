#include "knitforge/body/render_depth_image.h"

#include <gtest/gtest.h>

#include "knitforge/body/synthetic_depth_scenes.h"
#include "knitforge/util/errors.h"

using namespace knitforge;

namespace {

DepthCamera camera() {
  DepthCamera c;
  c.width = 64;
  c.height = 48;
  c.K << 50.0, 0.0, 31.5, 0.0, 50.0, 23.5, 0.0, 0.0, 1.0;
  return c;
}

// A square of side 2 * half at the given corners' plane: two triangles.
TriMesh quad(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) { return {{a, b, c, d}, {{0, 1, 2}, {0, 2, 3}}}; }

}  // namespace

TEST(RenderDepthImage, AFrontoParallelPlaneHasItsDistanceEverywhere) {
  const TriMesh wall = quad({-5000, -5000, 1234}, {5000, -5000, 1234}, {5000, 5000, 1234}, {-5000, 5000, 1234});
  const DepthImage img = render_depth_image(wall, camera(), {});
  for (double z : img.depth_mm) EXPECT_NEAR(z, 1234.0, 1e-9);
}

TEST(RenderDepthImage, ATiltedPlaneIsHitExactlyAtEveryPixel) {
  // Perspective-correct: back-projected pixels lie on the plane.
  const Vec3 n = Vec3(0.3, -0.2, 1.0).normalized();
  const Vec3 p0(50, -20, 1500);
  const Vec3 e1 = n.cross(Vec3::UnitX()).normalized(), e2 = n.cross(e1);
  const TriMesh plane = quad(p0 - 3000 * e1 - 3000 * e2, p0 + 3000 * e1 - 3000 * e2, p0 + 3000 * e1 + 3000 * e2,
                             p0 - 3000 * e1 + 3000 * e2);
  const DepthCamera cam = camera();
  const DepthImage img = render_depth_image(plane, cam, {});
  int seen = 0;
  for (int v = 0; v < cam.height; ++v)
    for (int u = 0; u < cam.width; ++u) {
      ASSERT_GT(img.at(u, v), 0.0);
      EXPECT_NEAR(n.dot(back_project(cam, u, v, img.at(u, v)) - p0), 0.0, 1e-9);
      ++seen;
    }
  EXPECT_EQ(seen, cam.width * cam.height);
}

TEST(RenderDepthImage, TheNearestSurfaceWinsAndTheCameraPoseIsApplied) {
  TriMesh scene = quad({-100, -100, 1000}, {100, -100, 1000}, {100, 100, 1000}, {-100, 100, 1000});
  const TriMesh far = quad({-5000, -5000, 3000}, {5000, -5000, 3000}, {5000, 5000, 3000}, {-5000, 5000, 3000});
  for (const Vec3& v : far.vertices) scene.vertices.push_back(v);
  scene.faces.push_back({4, 5, 6});
  scene.faces.push_back({4, 6, 7});
  const DepthCamera cam = camera();
  const DepthImage img = render_depth_image(scene, cam, {});
  EXPECT_NEAR(img.at(31, 23), 1000.0, 1e-9);  // the near square covers the centre
  EXPECT_NEAR(img.at(0, 0), 3000.0, 1e-9);    // the far wall elsewhere
  // Moving the camera 500 mm forwards (world z): x_c = x - (0, 0, 500).
  const DepthImage moved = render_depth_image(scene, cam, {Mat3::Identity(), Vec3(0, 0, -500)});
  EXPECT_NEAR(moved.at(31, 23), 500.0, 1e-9);
}

TEST(RenderDepthImage, RefusesAVertexBehindTheCamera) {
  const TriMesh bad = quad({-100, -100, 1000}, {100, -100, -5}, {100, 100, 1000}, {-100, 100, 1000});
  try {
    render_depth_image(bad, camera(), {});
    FAIL();
  } catch (const InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find("face 0"), std::string::npos) << e.what();
  }
}

TEST(RenderDepthImage, TheRigSeesTheBoardFromBothSides) {
  const DepthRig rig = seed_depth_rig();
  const TriMesh board = board_mesh({}, {Mat3::Identity(), Vec3(0, 0, 900)});
  for (int cam = 1; cam <= 2; ++cam) {
    const DepthImage img = render_depth_image(board, cam == 1 ? rig.camera1 : rig.camera2,
                                              cam == 1 ? rig.world_to_camera1 : rig.world_to_camera2);
    int n = 0;
    for (double z : img.depth_mm) n += z > 0.0 ? 1 : 0;
    // 600 x 450 mm at about 1 m, f = 280 px: about 169 x 127 pixels.
    EXPECT_GT(n, 17000) << "camera " << cam;
    EXPECT_LT(n, 26000) << "camera " << cam;
  }
}
