// The built-in leg and legging (leg_motion.h): the leg hangs along -z, the
// knee bends by the smooth motion with the shin turning rigidly about the
// knee, the capsules stay closed and outward, the legging clears the leg,
// and bad sizes are refused in the leg's words.
#include "knitforge/sim/leg_motion.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "knitforge/util/errors.h"

namespace knitforge {
namespace {

constexpr double kPi = std::numbers::pi;

TEST(LegMotion, KneeBendsTheShinRigidlyBackwards) {
  const LegMotionParams p;
  EXPECT_DOUBLE_EQ(leg_knee_angle_deg(p, 0, 10), 0.0);
  EXPECT_DOUBLE_EQ(leg_knee_angle_deg(p, 10, 10), 90.0);
  EXPECT_NEAR(leg_knee_angle_deg(p, 5, 10), 45.0, 1e-12);
  const TriMesh straight = leg_body_mesh(p, 0.0);
  const Vec3 knee = leg_knee(p);
  EXPECT_EQ(knee, Vec3(0, 0, -420));
  // Straight: hanging along -z, the shin's far pole below the ankle by its radius.
  EXPECT_NEAR((straight.vertices.back() - Vec3(0, 0, -820 - p.shin_radius_mm)).norm(), 0.0, 1e-9);
  for (double angle : {45.0, 90.0}) {
    const TriMesh bent = leg_body_mesh(p, angle);
    ASSERT_EQ(bent.faces, straight.faces);
    const Vec3 d = bent.vertices.back() - knee;
    // Back (+x) and up from straight down by the angle.
    EXPECT_NEAR(std::atan2(d.x(), -d.z()) * 180 / kPi, angle, 1e-9);
    EXPECT_NEAR(d.norm(), p.shin_length_mm + p.shin_radius_mm, 1e-9);
    EXPECT_NEAR((leg_ankle(p, angle) - knee).normalized().dot(d.normalized()), 1.0, 1e-12);
    // The thigh does not move; the shin moves rigidly.
    int moved = 0;
    for (int v = 0; v < bent.num_vertices(); ++v) moved += bent.vertices[v] != straight.vertices[v] ? 1 : 0;
    EXPECT_GT(moved, 0);
    EXPECT_LT(moved, bent.num_vertices());
    const int n = bent.num_vertices();
    EXPECT_NEAR((bent.vertices[n - 1] - bent.vertices[n - 9]).norm(),
                (straight.vertices[n - 1] - straight.vertices[n - 9]).norm(), 1e-9);
  }
  // Signed distance: the true capsules.
  EXPECT_NEAR(leg_signed_distance(p, 0, Vec3(100, 0, -200)), 30.0, 1e-9);
  EXPECT_NEAR(leg_signed_distance(p, 90, leg_ankle(p, 90) + Vec3(0, 0, 80)), 30.0, 1e-9);
  EXPECT_LT(leg_signed_distance(p, 90, leg_ankle(p, 90)), 0.0);
}

TEST(LegMotion, CapsulesAreClosedAndOutward) {
  const TriMesh m = leg_body_mesh(LegMotionParams{}, 60.0);
  double v = 0;
  for (const auto& t : m.faces) v += m.vertices[t[0]].dot(m.vertices[t[1]].cross(m.vertices[t[2]])) / 6.0;
  const auto capsule = [](double r, double l) { return kPi * r * r * l + 4.0 / 3.0 * kPi * r * r * r; };
  EXPECT_GT(v, 0.95 * (capsule(70, 420) + capsule(50, 400)));
  EXPECT_LT(v, capsule(70, 420) + capsule(50, 400));
}

TEST(LegMotion, LeggingClearsTheStraightLeg) {
  const LegMotionParams p;
  const SleeveMesh s = legging_mesh(p);
  ASSERT_FALSE(s.shoulder_ring.empty());
  EXPECT_EQ(s.attached.size(), s.shoulder_ring.size() + s.cuff_ring.size());
  for (int v : s.shoulder_ring) EXPECT_NEAR(s.mesh.vertices[v].z(), -p.waist_margin_mm, 1e-9);
  for (int v : s.cuff_ring) {
    EXPECT_NEAR(s.mesh.vertices[v].z(), -(p.thigh_length_mm + p.shin_length_mm - p.ankle_margin_mm), 1e-9);
    EXPECT_NEAR(std::hypot(s.mesh.vertices[v].x(), s.mesh.vertices[v].y()), p.shin_radius_mm + p.clearance_mm, 1e-9);
  }
  for (const Vec3& x : s.mesh.vertices) EXPECT_GT(leg_signed_distance(p, 0, x), 0.8 * p.clearance_mm);
  for (const Vec3& c : s.course_directions) {
    EXPECT_NEAR(c.norm(), 1.0, 1e-12);
    EXPECT_NEAR(c.z(), 0.0, 1e-12);  // round the leg
  }
  // Outward: the tube's faces point away from the leg's axis.
  for (const auto& f : s.mesh.faces) {
    const Vec3 a = s.mesh.vertices[f[0]], b = s.mesh.vertices[f[1]], c = s.mesh.vertices[f[2]];
    const Vec3 centre = (a + b + c) / 3.0;
    EXPECT_GT((b - a).cross(c - a).dot(Vec3(centre.x(), centre.y(), 0)), 0.0);
  }
}

TEST(LegMotion, RefusesInconsistentSizesNamingTheLeg) {
  auto message = [](LegMotionParams p) {
    try {
      (void)legging_mesh(p);
    } catch (const InvalidInput& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  LegMotionParams p;
  p.shin_radius_mm = 80;
  EXPECT_NE(message(p).find("leg motion: the shin radius 80 mm exceeds the thigh's 70 mm"), std::string::npos);
  p = {};
  p.legging_edge_mm = 60;
  EXPECT_NE(message(p).find("legging"), std::string::npos);
  p = {};
  p.ankle_margin_mm = 350;
  EXPECT_NE(message(p).find("ankle_margin_mm"), std::string::npos);
  p = {};
  p.clearance_mm = 0;
  EXPECT_NE(message(p).find("clearance_mm must be a positive"), std::string::npos);
  p = {};
  p.max_angle_deg = 170;
  EXPECT_NE(message(p).find("knee angle 170"), std::string::npos);
}

}  // namespace
}  // namespace knitforge
