// The data of the single-image reconstruction: dual-depth rendering, the
// keypoints, the synthetic samples, their way back to 3D and the errors.
#include "knitforge/body/ddr_sample.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "knitforge/body/ddr_geometry.h"
#include "knitforge/body/generated_body.h"
#include "knitforge/body/render_dual_depth.h"
#include "knitforge/body/skin_body.h"
#include "knitforge/evaluate/surface_distance.h"
#include "knitforge/util/errors.h"

using namespace knitforge;

namespace {

// A closed axis-aligned cube of half-side a centred at c (outward faces).
TriMesh cube(const Vec3& c, double a) {
  TriMesh m;
  for (int i = 0; i < 8; ++i) m.vertices.push_back(c + a * Vec3(i & 1 ? 1 : -1, i & 2 ? 1 : -1, i & 4 ? 1 : -1));
  m.faces = {{0, 2, 1}, {1, 2, 3}, {4, 5, 6}, {5, 7, 6}, {0, 1, 4}, {1, 5, 4},
             {2, 6, 3}, {3, 6, 7}, {0, 4, 2}, {2, 4, 6}, {1, 3, 5}, {3, 7, 5}};
  return m;
}

const BodyModel& coarse_body() { return ddr_body_model(); }

}  // namespace

TEST(RenderDualDepth, ACubeHasItsFrontAndBackFaceDepths) {
  const DepthCamera cam = ddr_camera(32);
  const TriMesh box = cube({0, 0, 3000}, 200);
  const DualDepthImage dd = render_dual_depth(box, cam, {});
  int covered = 0;
  for (int i = 0; i < 32 * 32; ++i) {
    if (!dd.covered(i)) continue;
    ++covered;
    EXPECT_NEAR(dd.min_mm[static_cast<size_t>(i)], 2800.0, 1e-6);
    // Rays inside the back face's (smaller) projection leave through it; the others through a side.
    const double du = std::abs(i % 32 - cam.K(0, 2)), dv = std::abs(i / 32 - cam.K(1, 2));
    const double back_half_px = cam.K(0, 0) * 200.0 / 3200.0;
    if (std::max(du, dv) < back_half_px - 0.01)
      EXPECT_NEAR(dd.max_mm[static_cast<size_t>(i)], 3200.0, 1e-6);
    else
      EXPECT_LE(dd.max_mm[static_cast<size_t>(i)], 3200.0 + 1e-6);
    EXPECT_GT(dd.max_mm[static_cast<size_t>(i)], 2800.0);
  }
  // The front face (400 mm at 2800 mm, f = 100 px) spans ~14 px: ~200 pixels.
  EXPECT_GT(covered, 150);
  EXPECT_LT(covered, 260);
}

TEST(BodyKeypoints, FaceLandmarksSitOnTheFrontAndSidesOfTheHead) {
  const BodyModel& model = coarse_body();
  const BodyKeypointRig rig = body_keypoint_rig(model);
  const PosedBody rest = pose_body(model, zero_params(model));
  const auto k = body_keypoints(rig, rest);
  const Vec3 head = rest.joints[static_cast<size_t>(model.joint_index("head"))];
  EXPECT_LT(k[0].y(), head.y() - 40);        // the nose in front (-y)
  EXPECT_GT(k[15].x(), k[14].x() + 30);      // left eye (+x) left of the right eye
  EXPECT_LT(k[14].y(), head.y() - 30);       // eyes in front too
  EXPECT_GT(k[17].x(), head.x() + 40);       // left ear out to +x
  EXPECT_LT(k[16].x(), head.x() - 40);
  EXPECT_NEAR(keypoint_pelvis(k).x(), 0.5 * (k[8].x() + k[11].x()), 1e-12);
  EXPECT_GT(k[5].x(), k[2].x());             // left shoulder at +x
}

TEST(BodyKeypoints, AModelWithoutTheJointsIsRefused) {
  BodyModel model = coarse_body();
  model.joint_names[static_cast<size_t>(model.joint_index("left_knee"))] = "knee_l";
  EXPECT_THROW(body_keypoint_rig(model), InvalidInput);
}

TEST(DdrSample, TheTrueDdrBackProjectsOntoTheBody) {
  const BodyModel& model = coarse_body();
  const DdrSample s = synthetic_ddr_sample(model, body_keypoint_rig(model), 7, {.size = 48});
  const size_t plane = 48 * 48;
  int fg = 0;
  for (size_t i = 0; i < plane; ++i) {
    if (!s.foreground[i]) {
      EXPECT_EQ(s.ddr[i], 0.0f);
      EXPECT_EQ(s.ddr[plane + i], 0.0f);
      continue;
    }
    ++fg;
    EXPECT_LE(s.ddr[i], s.ddr[plane + i]);
    EXPECT_GT(s.ddr[i], -1.0f);
    EXPECT_LT(s.ddr[plane + i], 1.0f);
  }
  EXPECT_GT(fg, 150);
  // Every point of both channels lies on the body (exact ray hits: float rounding of 1 m units only).
  const OrientedPoints pts = ddr_oriented_points(s.ddr, s.camera, s.pelvis_mm.z());
  ASSERT_GT(pts.points.size(), static_cast<size_t>(fg));
  std::vector<Vec3> world;
  const Mat3 Rt = s.world_to_camera.rotation.transpose();
  for (const Vec3& p : pts.points) world.push_back(Rt * (p - s.world_to_camera.translation));
  for (double d : distances_to_surface(s.body, world)) EXPECT_LT(d, 0.5);
}

TEST(DdrSample, ThePelvisLiesBetweenFrontAndBackAndHeatmapsPeakAtKeypoints) {
  const BodyModel& model = coarse_body();
  const DdrSample s = synthetic_ddr_sample(model, body_keypoint_rig(model), 3, {.size = 64});
  const Vec3 p = s.camera.K * s.pelvis_mm;
  const int u = static_cast<int>(std::lround(p.x() / p.z())), v = static_cast<int>(std::lround(p.y() / p.z()));
  const size_t i = static_cast<size_t>(v * 64 + u);
  ASSERT_TRUE(s.foreground[i]);
  EXPECT_LT(s.ddr[i], 0.0f);
  EXPECT_GT(s.ddr[64 * 64 + i], 0.0f);
  for (size_t k = 0; k < kNumBodyKeypoints; ++k) {
    const Vec2 q = s.keypoints_px[k];
    const int ku = static_cast<int>(std::lround(q.x())), kv = static_cast<int>(std::lround(q.y()));
    if (ku < 0 || kv < 0 || ku >= 64 || kv >= 64) continue;
    const float peak = s.heatmaps[k * 64 * 64 + static_cast<size_t>(kv * 64 + ku)];
    EXPECT_GT(peak, 0.75f) << body_keypoint_names()[k];
    float elsewhere = 0.0f;  // 10 px away the Gaussian (sigma 1.5 px) is gone
    for (int y = 0; y < 64; ++y)
      for (int x = 0; x < 64; ++x)
        if (std::hypot(x - q.x(), y - q.y()) > 10) elsewhere = std::max(elsewhere, s.heatmaps[k * 64 * 64 + static_cast<size_t>(y * 64 + x)]);
    EXPECT_LT(elsewhere, 1e-6f);
  }
}

TEST(DdrSample, AKeypointFarOutsideThePictureLeavesItsHeatmapEmpty) {
  KeypointPixels px = zero_keypoint_pixels();
  px[0] = Vec2(1e12, 5.0);   // beyond any int
  px[1] = Vec2(-40.0, 8.0);  // its Gaussian misses the 16-pixel picture
  px[2] = Vec2(8.0, 8.0);
  std::array<bool, kNumBodyKeypoints> present{};
  present[0] = present[1] = present[2] = true;
  const std::vector<float> maps = keypoint_heatmaps(px, present, 16, 1.5);
  const auto sum = [&](size_t k) {
    double s = 0.0;
    for (size_t i = 0; i < 256; ++i) s += maps[k * 256 + i];
    return s;
  };
  EXPECT_EQ(sum(0), 0.0);
  EXPECT_EQ(sum(1), 0.0);
  EXPECT_FLOAT_EQ(maps[2 * 256 + 8 * 16 + 8], 1.0f);
}

TEST(DdrSample, SamplesAreDeterministicAndDiffer) {
  const BodyModel& model = coarse_body();
  const BodyKeypointRig rig = body_keypoint_rig(model);
  const DdrSample a = synthetic_ddr_sample(model, rig, 11, {.size = 32});
  const DdrSample b = synthetic_ddr_sample(model, rig, 11, {.size = 32});
  const DdrSample c = synthetic_ddr_sample(model, rig, 12, {.size = 32});
  EXPECT_EQ(a.ddr, b.ddr);
  EXPECT_EQ(a.rgb, b.rgb);
  EXPECT_NE(a.ddr, c.ddr);
}

TEST(DdrGeometry, TurningAboutTheVerticalKeepsThePivotAndHeights) {
  const Vec3 pivot(10, -20, 6000);
  const RigidTransform t = turn_about_vertical(pivot, 0.7);
  EXPECT_NEAR((t.apply(pivot) - pivot).norm(), 0.0, 1e-9);
  const Vec3 x(300, 450, 5800);
  EXPECT_NEAR(t.apply(x).y(), x.y(), 1e-9);
  EXPECT_NEAR((t.apply(x) - pivot).norm(), (x - pivot).norm(), 1e-9);
  // A quarter turn sends a point in front of the pivot (-z) to its side.
  const RigidTransform q = turn_about_vertical(pivot, std::numbers::pi / 2);
  EXPECT_NEAR(std::abs(q.apply(pivot - Vec3(0, 0, 100)).x() - pivot.x()), 100.0, 1e-9);
}

TEST(DdrGeometry, SplattingKeepsTheNearestPoint) {
  const DepthCamera cam = ddr_camera(32);
  const DepthImage img = splat_min_depth({{0, 0, 3000}, {0, 0, 2500}, {1e5, 0, 10}}, cam, {});
  const size_t centre = static_cast<size_t>(std::lround(cam.K(1, 2)) * 32 + std::lround(cam.K(0, 2)));
  EXPECT_DOUBLE_EQ(img.depth_mm[centre], 2500.0);
  int set = 0;
  for (double d : img.depth_mm) set += d > 0;
  EXPECT_EQ(set, 1);  // the third point falls outside the image
}

TEST(DdrErrors, MatchTheSeedsDefinitions) {
  const int s = 8;
  std::vector<float> truth(2 * s * s, 0.0f), pred(2 * s * s, 0.0f);
  std::vector<uint8_t> fg(s * s, 0);
  for (int v = 2; v < 6; ++v)
    for (int u = 2; u < 6; ++u) fg[static_cast<size_t>(v * s + u)] = 1;
  EXPECT_EQ(ddr_errors(pred, truth, fg, s).ei, 0.0);
  // A constant 2 cm offset on both channels: EP = 2 cm, no gradient error.
  for (size_t i = 0; i < pred.size(); ++i) pred[i] = 0.02f;
  DdrErrors e = ddr_errors(pred, truth, fg, s);
  EXPECT_EQ(e.foreground, 16);
  EXPECT_NEAR(e.ei, 32 * 0.02, 1e-6);
  EXPECT_NEAR(e.ep_cm, 2.0, 1e-4);
  EXPECT_NEAR(e.eg, 0.0, 1e-6);
  // A ramp along u in channel 0: each foreground pixel with a right neighbour adds its slope.
  for (int v = 0; v < s; ++v)
    for (int u = 0; u < s; ++u) pred[static_cast<size_t>(v * s + u)] = 0.01f * u;
  for (size_t i = s * s; i < pred.size(); ++i) pred[i] = 0.0f;
  e = ddr_errors(pred, truth, fg, s);
  EXPECT_NEAR(e.eg, 12 * 0.01, 1e-5);  // 4 rows x 3 right neighbours
  EXPECT_THROW(ddr_errors(pred, truth, std::vector<uint8_t>(5), s), InvalidInput);
}
