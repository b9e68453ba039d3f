#include "knitforge/body/fuse_point_clouds.h"

#include <gtest/gtest.h>

#include <cmath>

#include "geometry/test_meshes.h"
#include "knitforge/body/render_depth_image.h"
#include "knitforge/body/synthetic_depth_scenes.h"
#include "knitforge/util/errors.h"

using namespace knitforge;

namespace {

DepthCamera camera() {
  DepthCamera c;
  c.width = 80;
  c.height = 60;
  c.K << 600.0, 0.0, 39.5, 0.0, 600.0, 29.5, 0.0, 0.0, 1.0;  // 1.7-2.5 mm per pixel at 1-1.5 m
  return c;
}

TriMesh tilted_plane(const Vec3& n, const Vec3& p0) {
  const Vec3 e1 = n.unitOrthogonal(), e2 = n.cross(e1);
  return {{p0 - 4000 * e1 - 4000 * e2, p0 + 4000 * e1 - 4000 * e2, p0 + 4000 * e1 + 4000 * e2, p0 - 4000 * e1 + 4000 * e2},
          {{0, 1, 2}, {0, 2, 3}}};
}


}  // namespace

TEST(FusePointClouds, NormalsOfAPlaneAreItsNormalTowardsTheCamera) {
  const Vec3 n = Vec3(0.3, 0.2, -1.0).normalized();  // faces the camera
  const DepthCamera cam = camera();
  const DepthImage img = render_depth_image(tilted_plane(n, Vec3(0, 0, 1500)), cam, {});
  const OrientedPoints op = depth_to_oriented_points(img, cam, {});
  // Every pixel measured; every point has at least 6 of the 24 neighbours
  // (a corner pixel has 8).
  EXPECT_EQ(op.points.size(), static_cast<size_t>(cam.width * cam.height));
  for (const Vec3& m : op.normals) EXPECT_LT((m - n).norm(), 1e-9);
  // Seen from the back (the same plane, the normal flipped): still towards the camera.
  const OrientedPoints back = depth_to_oriented_points(render_depth_image(tilted_plane(-n, Vec3(0, 0, 1500)), cam, {}), cam, {});
  for (const Vec3& m : back.normals) EXPECT_LT((m - n).norm(), 1e-9);
}

TEST(FusePointClouds, LonePixelsAndDepthEdgesAreNotSmoothedOver) {
  const DepthCamera cam = camera();
  DepthImage img = render_depth_image(tilted_plane(-Vec3::UnitZ(), Vec3(0, 0, 1000)), cam, {});
  // A square 300 mm nearer on the left half: a depth edge.
  for (int v = 0; v < cam.height; ++v)
    for (int u = 0; u < 40; ++u) img.depth_mm[static_cast<size_t>(v * cam.width + u)] = 700.0;
  // A flying pixel far in front of its neighbours.
  img.depth_mm[static_cast<size_t>(30 * cam.width + 60)] = 400.0;
  const OrientedPoints op = depth_to_oriented_points(img, cam, {});
  EXPECT_EQ(op.points.size(), static_cast<size_t>(cam.width * cam.height - 1));
  // Both sides of the edge keep the fronto-parallel normal: neighbours across
  // the 300 mm step are ignored.
  for (const Vec3& m : op.normals) EXPECT_LT((m + Vec3::UnitZ()).norm(), 1e-9);
  for (const Vec3& p : op.points) EXPECT_GT(p.z(), 650.0);
}

TEST(FusePointClouds, CameraTwosPointsLandOnCameraOnesAndVoxelsBoundTheCount) {
  // A sphere between the rig's cameras, seen by both, fused with the true
  // calibration: every fused point on the sphere (in camera 1's frame).
  const DepthRig rig = seed_depth_rig();
  const Vec3 centre(0.0, 0.0, 1000.0);
  const double radius = 250.0;
  TriMesh sphere = test::uv_sphere_mesh(1.0, 180, 90);
  for (Vec3& v : sphere.vertices) v = centre + radius * v;
  OrientedPoints views[2];
  for (int cam = 0; cam < 2; ++cam) {
    const DepthCamera& c = cam == 0 ? rig.camera1 : rig.camera2;
    views[cam] = depth_to_oriented_points(
        render_depth_image(sphere, c, cam == 0 ? rig.world_to_camera1 : rig.world_to_camera2), c, {});
  }
  const RigidTransform T = camera2_to_camera1(rig);
  const OrientedPoints fused = fuse_point_clouds(views[0], views[1], T, {4.0});
  const Vec3 c1 = rig.world_to_camera1.apply(centre);
  ASSERT_GT(fused.points.size(), 5000u);
  EXPECT_LT(fused.points.size(), views[0].points.size() + views[1].points.size());
  double worst = 0.0, worst_normal = 0.0;
  for (size_t i = 0; i < fused.points.size(); ++i) {
    // The sphere is a mesh of 2-degree facets: flat faces up to
    // R (1 - cos(1.4 degrees)) ~ 0.08 mm inside the true sphere.
    worst = std::max(worst, std::abs((fused.points[i] - c1).norm() - radius));
    worst_normal = std::max(worst_normal, (fused.normals[i] - (fused.points[i] - c1).normalized()).norm());
  }
  EXPECT_LT(worst, 0.5);
  EXPECT_LT(worst_normal, 0.1);  // outward, within ~6 degrees (the voxel average of faceted normals)
  // A coarser grid, fewer points.
  EXPECT_LT(fuse_point_clouds(views[0], views[1], T, {12.0}).points.size(), fused.points.size() / 4);
  EXPECT_THROW(fuse_point_clouds(views[0], views[1], T, {0.0}), InvalidInput);
}
