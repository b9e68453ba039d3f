// Style transfer (body/transfer_garment.h, seed eq. 5.13) on the small test
// body (test_bodies.h): identity, rigid motions, an offset garment.
#include "knitforge/body/transfer_garment.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "knitforge/body/axis_angle.h"
#include "knitforge/body/skin_body.h"
#include "knitforge/evaluate/surface_distance.h"
#include "knitforge/geometry/mesh_measures.h"
#include "knitforge/util/errors.h"
#include "test_bodies.h"

namespace knitforge {
namespace {

TriMesh body(const BodyModel& m, double stretch, double inflate, double bend) {
  BodyParams p = zero_params(m);
  p.shape << stretch, inflate;
  p.joint_rotations[1] = {0.0, 0.0, bend};
  p.joint_rotations[0] = {0.1, 0.0, 0.0};
  p.translation_mm = {3.0, -2.0, 1.0};
  return posed_mesh(m, pose_body(m, p));
}

// A garment: the body's middle rings (x in [20, 80] at rest) moved out by d
// along the vertex normals, with the body's faces between them.
TriMesh offset_garment(const BodyModel& m, const TriMesh& b, double d) {
  const std::vector<Vec3> n = vertex_normals(b);
  TriMesh g;
  std::vector<int> map(b.vertices.size(), -1);
  for (size_t i = 0; i < b.vertices.size(); ++i) {
    const double x = m.template_vertices[i].x();
    if (x < 20.0 - 1e-9 || x > 80.0 + 1e-9) continue;
    map[i] = g.num_vertices();
    g.vertices.push_back(b.vertices[i] + d * n[i]);
  }
  for (const auto& f : b.faces)
    if (map[static_cast<size_t>(f[0])] >= 0 && map[static_cast<size_t>(f[1])] >= 0 && map[static_cast<size_t>(f[2])] >= 0)
      g.faces.push_back({map[static_cast<size_t>(f[0])], map[static_cast<size_t>(f[1])], map[static_cast<size_t>(f[2])]});
  return g;
}

TEST(TransferGarment, ToTheSameBodyIsTheIdentity) {
  const BodyModel m = test::tube_body_model(false);
  const TriMesh a = body(m, 0.2, 0.1, 0.3);
  const TriMesh g = offset_garment(m, a, 4.0);
  const TriMesh out = transfer_garment(g, a, a);
  ASSERT_EQ(out.vertices.size(), g.vertices.size());
  EXPECT_EQ(out.faces, g.faces);
  for (size_t i = 0; i < g.vertices.size(); ++i) EXPECT_LT((out.vertices[i] - g.vertices[i]).norm(), 1e-9) << i;
}

TEST(TransferGarment, ARigidMotionOfTheBodyMovesTheGarmentRigidly) {
  const BodyModel m = test::tube_body_model(false);
  const TriMesh a = body(m, 0.0, 0.3, -0.4);
  TriMesh g = offset_garment(m, a, 6.0);
  g.vertices.push_back({50.0, 40.0, -10.0});  // also a point far from the body
  const Mat3 R = rotation_from_axis_angle({0.4, -1.1, 0.7});
  const Vec3 t(120.0, -35.0, 8.0);
  TriMesh b = a;
  for (Vec3& v : b.vertices) v = R * v + t;
  const TriMesh out = transfer_garment(g, a, b);
  for (size_t i = 0; i < g.vertices.size(); ++i)
    EXPECT_LT((out.vertices[i] - (R * g.vertices[i] + t)).norm(), 1e-9) << i;
}

TEST(TransferGarment, AnOffsetGarmentKeepsItsDistanceToTheOtherBody) {
  const BodyModel m = test::tube_body_model(false);
  const TriMesh a = body(m, 0.0, 0.0, 0.0);
  const TriMesh b = body(m, 0.6, 1.2, 0.5);  // longer, thicker, bent at the middle joint
  const double d = 3.0;
  const TriMesh g = offset_garment(m, a, d);
  const std::vector<double> before = distances_to_surface(a, g.vertices);
  const TriMesh out = transfer_garment(g, a, b);
  const std::vector<double> after = distances_to_surface(b, out.vertices);
  double mean = 0.0, worst = 0.0, moved = 0.0;
  for (size_t i = 0; i < after.size(); ++i) {
    mean += after[i] / static_cast<double>(after.size());
    worst = std::max(worst, std::abs(after[i] - d));
    moved = std::max(moved, (out.vertices[i] - g.vertices[i]).norm());
  }
  std::printf("offset %.1f mm: on A %.2f..%.2f mm; on B mean %.2f mm, largest deviation %.2f mm; moved up to %.1f mm\n",
              d, *std::min_element(before.begin(), before.end()), *std::max_element(before.begin(), before.end()),
              mean, worst, moved);
  EXPECT_GT(moved, 10.0);  // B is really another body
  EXPECT_NEAR(mean, d, 0.3);
  EXPECT_LT(worst, 1.0);
}

TEST(TransferGarment, RejectsBodiesOfAnotherTopology) {
  const BodyModel m = test::tube_body_model(false);
  const TriMesh a = body(m, 0.0, 0.0, 0.0);
  TriMesh b = a;
  b.faces.pop_back();
  const TriMesh g = offset_garment(m, a, 2.0);
  EXPECT_THROW(transfer_garment(g, a, b), InvalidInput);
  EXPECT_THROW(rig_garment(TriMesh{}, g.vertices), InvalidInput);
  TriMesh bad = g;
  bad.vertices[0].x() = std::nan("");
  EXPECT_THROW(transfer_garment(bad, a, a), InvalidInput);
}

}  // namespace
}  // namespace knitforge
