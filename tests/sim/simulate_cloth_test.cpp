// Garments on a moving body (simulate_cloth.h, body_sliding.h): a short run
// of the built-in sleeve never enters the arm and records energy and
// Newton iterations per frame; a garment carried rigidly with the body
// slides 0; a frictionless sheet under a plate that moves sideways slides by
// the plate's motion.
#include "knitforge/sim/simulate_cloth.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "geometry/test_meshes.h"
#include "knitforge/sim/arm_motion.h"
#include "knitforge/sim/leg_motion.h"
#include "knitforge/util/errors.h"

namespace knitforge {
namespace {

double segment_distance(const Vec3& x, const Vec3& a, const Vec3& b) {
  const double t = std::clamp((x - a).dot(b - a) / (b - a).squaredNorm(), 0.0, 1.0);
  return (x - (a + t * (b - a))).norm();
}

// A small, coarse arm: seconds, not minutes.
ArmMotionParams small_arm() {
  ArmMotionParams p;
  p.upper_length_mm = 110;
  p.forearm_length_mm = 100;
  p.upper_radius_mm = 30;
  p.forearm_radius_mm = 26;
  p.body_edge_mm = 9;
  p.sleeve_edge_mm = 9;
  p.transition_mm = 40;
  p.max_angle_deg = 60;
  return p;
}

// The short sleeve run; with check_inside, every free vertex is also checked
// against the true capsules (independently of the engine's own distances).
void run_sleeve(bool check_inside, ClothSolver solver = ClothSolver::Implicit) {
  const ArmMotionParams p = small_arm();
  const int frames = 4;
  const SleeveMesh sleeve = arm_sleeve_mesh(p);
  SimModel model = build_sim_model(sleeve.mesh, sleeve.course_directions);
  const std::vector<int>& attached = sleeve.attached;
  model.pinned = attached;
  std::vector<std::vector<Vec3>> poses;
  std::vector<double> angles;
  for (int f = 0; f <= frames; ++f) {
    angles.push_back(arm_elbow_angle_deg(p, f, frames));
    poses.push_back(arm_body_mesh(p, angles.back()).vertices);
  }
  ClothOptions o;
  o.frames = frames;
  o.frame_rate_hz = 20;
  o.substeps = 2;  // the default: 7.5 degrees a step (15 pinch the elbow's crease, see docs/sim.md)
  o.newton.max_iterations = 8;  // the property tested holds after every Newton step
  // And after every L-BFGS step: 15 a step (not 400) leave the closest
  // approach to the true capsules the same (-0.25 mm) and take 7 s instead
  // of 35 s under ASan.
  o.quasi_newton.max_iterations = 15;
  o.solver = solver;
  const bool preview = solver == ClothSolver::Preview;
  int seen = 0;
  const ClothResult r =
      simulate_cloth(model, arm_body_mesh(p, 0), poses, attached, o, [&](const ClothFrame&) { ++seen; });
  ASSERT_EQ(r.frames.size(), static_cast<size_t>(frames + 1));
  EXPECT_EQ(seen, frames + 1);
  // The capsule meshes are inscribed in the true capsules; a vertex outside the mesh is at
  // most the chord sag (< 0.8 mm here) inside the true surface.
  const double sag = 0.8;
  std::vector<char> is_attached(model.num_vertices(), 0);
  for (int v : attached) is_attached[v] = 1;
  for (const ClothFrame& f : r.frames) {
    const double a = angles[f.frame] * std::numbers::pi / 180;
    const Vec3 elbow(p.upper_length_mm, 0, 0);
    const Vec3 wrist = elbow + p.forearm_length_mm * Vec3(std::cos(a), 0, std::sin(a));
    EXPECT_EQ(f.body, poses[f.frame]);
    if (check_inside) {
      for (int v = 0; v < model.num_vertices(); ++v) {
        if (is_attached[v]) continue;
        EXPECT_GT(segment_distance(f.positions[v], Vec3::Zero(), elbow), p.upper_radius_mm - sag) << "frame " << f.frame;
        EXPECT_GT(segment_distance(f.positions[v], elbow, wrist), p.forearm_radius_mm - sag) << "frame " << f.frame;
      }
    }
    EXPECT_GT(f.min_distance_mm, 0.0);
    EXPECT_TRUE(std::isfinite(f.elastic_energy_uj) && std::isfinite(f.kinetic_energy_uj));
    EXPECT_EQ(f.stress_kpa.size(), static_cast<size_t>(model.num_elements()));
    EXPECT_EQ(f.sliding_mm.size(), static_cast<size_t>(model.num_vertices()));
    if (f.frame > 0 && preview) {
      EXPECT_EQ(f.newton_iterations + f.quasi_newton_iterations, 0);
      EXPECT_GE(f.preview_iterations, f.steps);
      EXPECT_EQ(f.factorizations, f.steps);  // one a step
    }
    if (f.frame > 0 && !preview) {
      EXPECT_GT(f.newton_iterations + f.quasi_newton_iterations, 0);
      EXPECT_GE(f.factorizations, f.steps);  // at least the L-BFGS phase's factor per step
    }
    if (f.frame > 0) {
      EXPECT_GE(f.steps, 1);
      EXPECT_GT(f.kinetic_energy_uj, 0.0);
    }
  }
  // The bend stretches the sleeve over the elbow: stress rises from the start.
  double s0 = 0, s_end = 0;
  for (double s : r.frames.front().stress_kpa) s0 = std::max(s0, s);
  for (double s : r.frames.back().stress_kpa) s_end = std::max(s_end, s);
  EXPECT_GT(s_end, s0);
  EXPECT_GT(preview ? r.preview_iterations : r.quasi_newton_iterations, 0);
  EXPECT_EQ(r.max_stress_kpa.size(), static_cast<size_t>(model.num_elements()));
}


// Records every frame, and never enters the arm: checked against the true
// capsules, independently of the engine's own (unsigned) distances, which cannot tell a vertex that crossed the surface from one
// outside it. This found that the collision-free steps did not limit any
// move (collision_free_step_test.cpp).
TEST(SimulateCloth, SleeveOnABendingArmNeverEntersIt) { run_sleeve(true); }

// The projective-dynamics preview of the same run: contact by projection
// keeps the sleeve out of the true arm too (beyond the chord sag), here.
TEST(SimulateCloth, PreviewSleeveStaysOutsideTheArm) { run_sleeve(true, ClothSolver::Preview); }

// The legging on a small leg bending at the knee (leg_motion.h): the run
// finishes, the knee bends, the fabric over the front of the knee stretches,
// and no free vertex enters the true capsules beyond the meshes' chord sag.
TEST(SimulateCloth, LeggingOnABendingKneeNeverEntersIt) {
  LegMotionParams p;
  p.thigh_length_mm = 120;
  p.shin_length_mm = 110;
  p.thigh_radius_mm = 32;
  p.shin_radius_mm = 27;
  p.body_edge_mm = 9;
  p.legging_edge_mm = 9;
  p.transition_mm = 40;
  p.max_angle_deg = 60;
  const int frames = 4;
  const SleeveMesh legging = legging_mesh(p);
  SimModel model = build_sim_model(legging.mesh, legging.course_directions);
  model.pinned = legging.attached;
  std::vector<std::vector<Vec3>> poses;
  std::vector<double> angles;
  for (int f = 0; f <= frames; ++f) {
    angles.push_back(leg_knee_angle_deg(p, f, frames));
    poses.push_back(leg_body_mesh(p, angles.back()).vertices);
  }
  ClothOptions o;
  o.frames = frames;
  o.frame_rate_hz = 20;
  o.substeps = 2;
  o.newton.max_iterations = 8;
  o.quasi_newton.max_iterations = 15;  // as the sleeve's: the same clearance (-0.18 mm), 20 s instead of 47 s under ASan
  const ClothResult r = simulate_cloth(model, leg_body_mesh(p, 0), poses, legging.attached, o);
  ASSERT_EQ(r.frames.size(), static_cast<size_t>(frames + 1));
  EXPECT_DOUBLE_EQ(angles.back(), 60.0);
  std::vector<char> held(model.num_vertices(), 0);
  for (int v : legging.attached) held[v] = 1;
  const double sag = 0.8;
  for (const ClothFrame& f : r.frames) {
    EXPECT_EQ(f.body, poses[f.frame]);
    EXPECT_GT(f.min_distance_mm, 0.0);
    for (int v = 0; v < model.num_vertices(); ++v) {
      if (!held[v]) {
        EXPECT_GT(leg_signed_distance(p, angles[f.frame], f.positions[v]), -sag) << "frame " << f.frame;
      }
    }
  }
  // The ankle cuff rode with the shin: back and up by the bend.
  const Vec3 ankle0 = leg_ankle(p, 0), ankle = leg_ankle(p, 60);
  EXPECT_GT(ankle.x() - ankle0.x(), 90.0);
  for (int v : legging.cuff_ring) EXPECT_GT(r.frames.back().positions[v].x() - r.frames.front().positions[v].x(), 60.0);
  double s0 = 0, s_end = 0;
  for (double s : r.frames.front().stress_kpa) s0 = std::max(s0, s);
  for (double s : r.frames.back().stress_kpa) s_end = std::max(s_end, s);
  EXPECT_GT(s_end, s0);
}

// A flat square sheet of (n+1)² vertices, spacing d, at height z.
TriMesh sheet(int n, double d, double z) {
  TriMesh m;
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) m.vertices.emplace_back(i * d, j * d, z);
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < n; ++i) {
      const int a = j * (n + 1) + i;
      m.faces.push_back({a, a + 1, a + n + 2});
      m.faces.push_back({a, a + n + 2, a + n + 1});
    }
  }
  return m;
}

TriMesh plate() {
  TriMesh m;
  m.vertices = {{-50, -50, 0}, {70, -50, 0}, {70, 70, 0}, {-50, 70, 0}};
  m.faces = {{0, 1, 2}, {0, 2, 3}};
  return m;
}

TEST(SimulateCloth, GarmentCarriedRigidlySlidesZero) {
  const TriMesh g = sheet(4, 4.0, 0.4);
  SimModel model = build_sim_model(g, {Vec3(1, 0, 0)});
  std::vector<int> all(model.num_vertices());
  for (int v = 0; v < model.num_vertices(); ++v) all[v] = v;
  model.pinned = all;
  const TriMesh body = plate();
  const int frames = 3;
  std::vector<std::vector<Vec3>> poses;
  for (int f = 0; f <= frames; ++f) {
    const Mat3 R = Eigen::AngleAxisd(0.2 * f, Vec3(0.3, 0.4, 1).normalized()).matrix();
    const Vec3 t(3.0 * f, -2.0 * f, 5.0 * f);
    std::vector<Vec3> pose;
    for (const Vec3& v : body.vertices) pose.push_back(R * v + t);
    poses.push_back(pose);
  }
  ClothOptions o;
  o.frames = frames;
  o.substeps = 1;
  o.sliding_distance_mm = 1.0;
  const ClothResult r = simulate_cloth(model, body, poses, all, o);
  for (const ClothFrame& f : r.frames) {
    EXPECT_EQ(f.touching, model.num_vertices());
    const Mat3 R = Eigen::AngleAxisd(0.2 * f.frame, Vec3(0.3, 0.4, 1).normalized()).matrix();
    const Vec3 t(3.0 * f.frame, -2.0 * f.frame, 5.0 * f.frame);
    for (int v = 0; v < model.num_vertices(); ++v) {
      EXPECT_LT(f.sliding_mm[v], 1e-9);
      EXPECT_LT((f.positions[v] - (R * g.vertices[v] + t)).norm(), 1e-9);  // carried rigidly
    }
  }
  for (double s : r.max_sliding_mm) EXPECT_LT(s, 1e-9);
}

TEST(SimulateCloth, FrictionlessSheetSlidesByThePlatesMotion) {
  const TriMesh g = sheet(4, 4.0, 0.3);
  const SimModel model = build_sim_model(g, {Vec3(1, 0, 0)});
  const TriMesh body = plate();
  const int frames = 3;
  std::vector<std::vector<Vec3>> poses;
  for (int f = 0; f <= frames; ++f) {
    std::vector<Vec3> pose;
    for (const Vec3& v : body.vertices) pose.push_back(v + Vec3(2.0 * f, 0, 0));
    poses.push_back(pose);
  }
  ClothOptions o;
  o.frames = frames;
  o.substeps = 2;
  o.contact.friction = 0.0;
  // Tight: a step starts with the vertices near the body carried along with
  // it, and the inertial force that pulls them back (m/h² x 1 mm, 0.01 mN
  // here) is below the default tolerance.
  o.newton = {50, 1e-6};
  const ClothResult r = simulate_cloth(model, body, poses, {}, o);
  const ClothFrame& last = r.frames.back();
  for (int v = 0; v < model.num_vertices(); ++v) {
    EXPECT_LT(std::abs(last.positions[v].x() - g.vertices[v].x()), 0.05);  // no friction: it stays
    EXPECT_NEAR(last.sliding_mm[v], 6.0, 0.05);
    EXPECT_GT(last.positions[v].z(), 0.0);
  }
  EXPECT_EQ(last.touching, model.num_vertices());
}

TEST(SimulateCloth, RefusesBadSetups) {
  const TriMesh g = sheet(2, 4.0, 0.3);
  SimModel model = build_sim_model(g, {Vec3(1, 0, 0)});
  ClothOptions o;
  o.frames = 2;
  EXPECT_THROW((void)simulate_cloth(model, plate(), {plate().vertices}, {}, o), InvalidInput);  // 1 pose for 2 frames
  EXPECT_THROW((void)simulate_cloth(model, plate(), {}, {3}, o), InvalidInput);  // attached but not pinned
  const SimModel touching = build_sim_model(sheet(2, 4.0, 0.0), {Vec3(1, 0, 0)});
  EXPECT_THROW((void)simulate_cloth(touching, plate(), {}, {}, o), InvalidInput);
  // A garment inside a closed body would stay inside (the barrier keeps
  // each vertex on its side): refused, naming the deepest vertex.
  const SimModel inside = build_sim_model(sheet(4, 4.0, 0.0), {Vec3(1, 0, 0)});
  try {
    (void)simulate_cloth(inside, test::uv_sphere_mesh(40.0, 24, 12), {}, {}, o);
    ADD_FAILURE() << "a garment inside the body was simulated";
  } catch (const InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find("25 free garment vertices start inside the body"), std::string::npos)
        << e.what();
    EXPECT_NE(std::string(e.what()).find("garment.clearance_mm"), std::string::npos) << e.what();
  }
  EXPECT_THROW(check_cloth_work(100000, 1000, 10), InvalidInput);
  EXPECT_NO_THROW(check_cloth_work(1000, 60, 2));
  // The preview's count is vertex-steps x rounds / 30 (no less than the steps).
  EXPECT_NO_THROW(check_cloth_work(10000, 1000, 2, kMaxPreviewWork, 30));  // 2e7
  EXPECT_NO_THROW(check_cloth_work(10000, 1000, 2, kMaxPreviewWork, 1));
  try {
    check_cloth_work(10000, 1000, 2, kMaxPreviewWork, 90);  // 6e7
    ADD_FAILURE() << "not refused";
  } catch (const InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find("the preview (garment vertices x frames x substeps x rounds / 30)"),
              std::string::npos)
        << e.what();
    EXPECT_NE(std::string(e.what()).find("--preview-iterations"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace knitforge
