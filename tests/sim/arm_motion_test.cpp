// The built-in arm and sleeve (arm_motion.h): the elbow angle is what the
// motion says at every frame, the capsules are closed and outward, the
// forearm turns rigidly about the elbow, and the sleeve fits with its
// clearance.
#include "knitforge/sim/arm_motion.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "knitforge/util/errors.h"

namespace knitforge {
namespace {

constexpr double kPi = std::numbers::pi;

double signed_volume(const TriMesh& m, int first_face, int last_face) {
  double v = 0;
  for (int f = first_face; f < last_face; ++f) {
    const auto& t = m.faces[f];
    v += m.vertices[t[0]].dot(m.vertices[t[1]].cross(m.vertices[t[2]])) / 6.0;
  }
  return v;
}

TEST(ArmMotion, ElbowAngleFollowsTheSmoothBend) {
  const ArmMotionParams p;
  EXPECT_DOUBLE_EQ(arm_elbow_angle_deg(p, 0, 10), 0.0);
  EXPECT_DOUBLE_EQ(arm_elbow_angle_deg(p, 10, 10), 90.0);
  EXPECT_NEAR(arm_elbow_angle_deg(p, 5, 10), 45.0, 1e-12);
  EXPECT_NEAR(arm_elbow_angle_deg(p, 2, 10), 90.0 * (3 * 0.04 - 2 * 0.008), 1e-12);
  for (int f = 1; f <= 10; ++f) EXPECT_GT(arm_elbow_angle_deg(p, f, 10), arm_elbow_angle_deg(p, f - 1, 10));
  EXPECT_THROW((void)arm_elbow_angle_deg(p, 11, 10), InvalidInput);
  EXPECT_THROW((void)arm_elbow_angle_deg(p, 0, 0), InvalidInput);
}

TEST(ArmMotion, ForearmTurnsRigidlyAboutTheElbow) {
  const ArmMotionParams p;
  const TriMesh straight = arm_body_mesh(p, 0.0);
  const int nu = arm_upper_vertex_count(p);
  const Vec3 elbow(p.upper_length_mm, 0, 0);
  for (double angle : {30.0, 90.0}) {
    const TriMesh bent = arm_body_mesh(p, angle);
    ASSERT_EQ(bent.faces, straight.faces);
    for (int v = 0; v < nu; ++v) EXPECT_EQ(bent.vertices[v], straight.vertices[v]);
    // The forearm's far pole (the last vertex) lies along (cos a, 0, sin a) from the elbow.
    const Vec3 d = bent.vertices.back() - elbow;
    EXPECT_NEAR(std::atan2(d.z(), d.x()) * 180 / kPi, angle, 1e-9);
    EXPECT_NEAR(d.norm(), p.forearm_length_mm + p.forearm_radius_mm, 1e-9);
    // Distances within the forearm are kept (a rigid motion).
    for (int v = nu; v + 7 < bent.num_vertices(); v += 7) {
      EXPECT_NEAR((bent.vertices[v] - bent.vertices[v + 7]).norm(),
                  (straight.vertices[v] - straight.vertices[v + 7]).norm(), 1e-9);
    }
  }
}

TEST(ArmMotion, CapsulesAreClosedAndOutward) {
  const ArmMotionParams p;
  const TriMesh m = arm_body_mesh(p, 60.0);
  // The first capsule's faces come first; both capsules have the same face count formula.
  int upper_faces = 0;
  const int nu = arm_upper_vertex_count(p);
  for (const auto& f : m.faces) upper_faces += f[0] < nu ? 1 : 0;
  const double vu = signed_volume(m, 0, upper_faces), vf = signed_volume(m, upper_faces, m.num_faces());
  const auto capsule_volume = [](double r, double l) { return kPi * r * r * l + 4.0 / 3.0 * kPi * r * r * r; };
  // Inscribed polyhedra: positive (outward) and a little below the true volume.
  EXPECT_GT(vu, 0.95 * capsule_volume(p.upper_radius_mm, p.upper_length_mm));
  EXPECT_LT(vu, capsule_volume(p.upper_radius_mm, p.upper_length_mm));
  EXPECT_GT(vf, 0.95 * capsule_volume(p.forearm_radius_mm, p.forearm_length_mm));
  EXPECT_LT(vf, capsule_volume(p.forearm_radius_mm, p.forearm_length_mm));
}

TEST(ArmMotion, SleeveFitsWithItsClearance) {
  const ArmMotionParams p;
  const SleeveMesh s = arm_sleeve_mesh(p);
  ASSERT_FALSE(s.shoulder_ring.empty());
  EXPECT_EQ(s.shoulder_ring.size(), s.cuff_ring.size());
  ASSERT_EQ(s.course_directions.size(), s.mesh.faces.size());
  const double end = p.upper_length_mm + p.forearm_length_mm - p.wrist_margin_mm;
  for (int v : s.shoulder_ring) EXPECT_DOUBLE_EQ(s.mesh.vertices[v].x(), p.sleeve_start_mm);
  for (int v : s.cuff_ring) {
    EXPECT_NEAR(s.mesh.vertices[v].x(), end, 1e-9);
    EXPECT_NEAR(std::hypot(s.mesh.vertices[v].y(), s.mesh.vertices[v].z()), p.forearm_radius_mm + p.clearance_mm,
                1e-9);
  }
  // Every sleeve vertex is at least the clearance from both capsules (straight arm), less a little
  // where the sleeve narrows over the elbow's sphere.
  const Vec3 elbow(p.upper_length_mm, 0, 0), wrist(p.upper_length_mm + p.forearm_length_mm, 0, 0);
  auto segment_distance = [](const Vec3& x, const Vec3& a, const Vec3& b) {
    const double t = std::clamp((x - a).dot(b - a) / (b - a).squaredNorm(), 0.0, 1.0);
    return (x - (a + t * (b - a))).norm();
  };
  for (const Vec3& x : s.mesh.vertices) {
    EXPECT_GT(segment_distance(x, Vec3::Zero(), elbow) - p.upper_radius_mm, 0.8 * p.clearance_mm);
    EXPECT_GT(segment_distance(x, elbow, wrist) - p.forearm_radius_mm, 0.8 * p.clearance_mm);
  }
  for (const Vec3& c : s.course_directions) {
    EXPECT_NEAR(c.norm(), 1.0, 1e-12);
    EXPECT_NEAR(c.x(), 0.0, 1e-12);  // round the arm
  }
}

TEST(ArmMotion, RefusesInconsistentSizes) {
  ArmMotionParams p;
  p.forearm_radius_mm = 50;
  EXPECT_THROW((void)arm_body_mesh(p, 0), InvalidInput);
  p = {};
  p.sleeve_edge_mm = 40;
  EXPECT_THROW((void)arm_sleeve_mesh(p), InvalidInput);
  p = {};
  p.wrist_margin_mm = 200;
  EXPECT_THROW((void)arm_sleeve_mesh(p), InvalidInput);
  p = {};
  p.clearance_mm = 0;
  EXPECT_THROW((void)arm_sleeve_mesh(p), InvalidInput);
}

}  // namespace
}  // namespace knitforge
