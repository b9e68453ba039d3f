// Contact per body part (kinematic_body.h, contact_candidates.h): the parts
// of a body are its connected components or given labels; a vertex near two
// parts gets one contact pair (and one friction pair) with each; a sheet
// pushed by a wall into the corner it makes with the floor (two touching
// boxes, two parts) is never pushed into either box.
#include <algorithm>
#include <cmath>

#include <gtest/gtest.h>

#include "knitforge/sim/contact_candidates.h"
#include "knitforge/sim/friction_energy.h"
#include "knitforge/sim/step_simulation.h"
#include "knitforge/util/errors.h"
#include "sim_test_meshes.h"

namespace knitforge {
namespace {

// The closed box [lo, hi] (12 triangles, outward normals), appended to m.
void add_box(TriMesh& m, const Vec3& lo, const Vec3& hi) {
  const int b = m.num_vertices();
  for (int k = 0; k < 8; ++k) {
    m.vertices.emplace_back(k & 1 ? hi.x() : lo.x(), k & 2 ? hi.y() : lo.y(), k & 4 ? hi.z() : lo.z());
  }
  const int quads[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
  for (const auto& q : quads) {
    m.faces.push_back({b + q[0], b + q[1], b + q[2]});
    m.faces.push_back({b + q[0], b + q[2], b + q[3]});
  }
}

// A floor slab (top at z = 0) and a wall standing on it (its face towards
// the sheet at x = wall_x): two boxes touching along the floor.
TriMesh floor_and_wall(double wall_x) {
  TriMesh m;
  add_box(m, Vec3(-40, -30, -10), Vec3(40, 30, 0));
  add_box(m, Vec3(wall_x, -30, 0), Vec3(wall_x + 10, 30, 20));
  return m;
}

int pairs_of(const std::vector<ContactPair>& pairs, int v) {
  return static_cast<int>(
      std::count_if(pairs.begin(), pairs.end(), [&](const ContactPair& p) { return p.vertex == v; }));
}

TEST(KinematicBody, PartsAreTheConnectedComponentsOrTheGivenLabels) {
  const TriMesh m = floor_and_wall(0.0);
  const KinematicBody two(m);
  ASSERT_EQ(two.num_parts(), 2);
  for (int f = 0; f < m.num_faces(); ++f) EXPECT_EQ(two.face_part(f), f < 12 ? 0 : 1) << "face " << f;
  const KinematicBody one(m, std::vector<int>(m.faces.size(), 0));
  EXPECT_EQ(one.num_parts(), 1);
  // Bad labels: wrong count, negative, a part without faces.
  EXPECT_THROW(KinematicBody(m, std::vector<int>(5, 0)), InvalidInput);
  std::vector<int> bad(m.faces.size(), 0);
  bad[3] = -1;
  EXPECT_THROW(KinematicBody(m, bad), InvalidInput);
  bad[3] = 2;  // parts 0 and 2, none 1
  EXPECT_THROW(KinematicBody(m, bad), InvalidInput);
}

TEST(KinematicBody, ClosestPointPerPart) {
  const KinematicBody body(floor_and_wall(0.0));
  // In the corner: 0.2 mm above the floor and 0.3 mm from the wall.
  const Vec3 p(-0.3, 0.0, 0.2);
  const std::vector<BodyPoint> q = body.closest_points_per_part_within(p, 0.5);
  ASSERT_EQ(q.size(), 2u);
  EXPECT_EQ(q[0].part, 0);
  EXPECT_EQ(q[1].part, 1);
  EXPECT_NEAR(std::sqrt(q[0].distance2), 0.2, 1e-12);
  EXPECT_NEAR(std::sqrt(q[1].distance2), 0.3, 1e-12);
  EXPECT_NEAR(q[0].where.point.z(), 0.0, 1e-12);
  EXPECT_NEAR(q[1].where.point.x(), 0.0, 1e-12);
  // The overall closest point is the nearer part's.
  const auto c = body.closest_point_within(p, 0.5);
  ASSERT_TRUE(c.has_value());
  EXPECT_EQ(c->part, 0);
  EXPECT_EQ(c->distance2, q[0].distance2);
  // Within 0.25 mm only the floor; one part's own query.
  EXPECT_EQ(body.closest_points_per_part_within(p, 0.25).size(), 1u);
  const auto w = body.closest_point_of_part_within(p, 1, 0.5);
  ASSERT_TRUE(w.has_value());
  EXPECT_EQ(w->face, q[1].face);
  EXPECT_FALSE(body.closest_point_of_part_within(p, 1, 0.25).has_value());
  // A one-part body: the closest point only.
  const TriMesh m = floor_and_wall(0.0);
  const KinematicBody one(m, std::vector<int>(m.faces.size(), 0));
  const std::vector<BodyPoint> q1 = one.closest_points_per_part_within(p, 0.5);
  ASSERT_EQ(q1.size(), 1u);
  EXPECT_EQ(q1[0].face, c->face);
}

TEST(ContactCandidates, AVertexNearTwoPartsHasAPairWithEach) {
  const KinematicBody body(floor_and_wall(0.0));
  Eigen::VectorXd x(9);
  x << -0.3, 0, 0.2,  // the corner: both parts
      -5, 0, 0.2,     // on the floor only
      -5, 0, 3;       // away from both
  const std::vector<ContactPair> pairs = find_contact_candidates(body, x, 0.5);
  ASSERT_EQ(pairs.size(), 3u);
  EXPECT_EQ(pairs_of(pairs, 0), 2);
  EXPECT_EQ(pairs_of(pairs, 1), 1);
  EXPECT_EQ(pairs_of(pairs, 2), 0);
  EXPECT_EQ(pairs[0].body.part, 0);
  EXPECT_EQ(pairs[1].body.part, 1);
  // Pins are left out.
  EXPECT_EQ(find_contact_candidates(body, x, 0.5, {1, 0, 0}).size(), 1u);
  // Friction: a pair per contact pair, each with its own normal force and a
  // tangent plane perpendicular to its own normal.
  KnitParams kp;
  kp.stitch_width = kp.stitch_height = 1.0;
  const SimModel model = build_sim_model(test::knit_sheet(1, 1, 1.0, 1.0), kp);
  Eigen::VectorXd y = test::flatten(model.rest_positions);
  y.segment<3>(0) = x.segment<3>(0);
  for (int v = 1; v < 4; ++v) y.segment<3>(3 * v) += Vec3(-20, 0, 5);
  ContactParams cp;
  const std::vector<FrictionPair> f =
      build_friction_pairs(model, find_contact_candidates(body, y, 0.5), body, body, y, cp);
  ASSERT_EQ(f.size(), 2u);
  EXPECT_EQ(f[0].part, 0);
  EXPECT_EQ(f[1].part, 1);
  EXPECT_GT(f[0].normal_force_mn, f[1].normal_force_mn);  // the floor is nearer
  EXPECT_GT(f[1].normal_force_mn, 0.0);
  EXPECT_NEAR((f[0].tangent.transpose() * Vec3::UnitZ()).norm(), 0.0, 1e-12);
  EXPECT_NEAR((f[1].tangent.transpose() * Vec3::UnitX()).norm(), 0.0, 1e-12);
}

// Many vertices (the threaded search, ranges on all hardware threads): the
// pairs are those of each vertex searched alone, in vertex order, pins left
// out.
TEST(ContactCandidates, ManyVerticesGiveEachVertexsPairsInOrder) {
  const KinematicBody body(floor_and_wall(0.0));
  const int n = 6000;
  Eigen::VectorXd x(3 * n);
  std::vector<char> skip(n, 0);
  for (int v = 0; v < n; ++v) {
    const double a = 0.001 * v;  // scattered near the corner, some out of reach
    x.segment<3>(3 * v) = Vec3(-1.5 * std::fmod(7.3 * a, 1.0), 20 * std::fmod(3.1 * a, 1.0) - 10,
                               1.2 * std::fmod(5.7 * a, 1.0));
    skip[v] = v % 97 == 0;
  }
  const std::vector<ContactPair> pairs = find_contact_candidates(body, x, 0.5, skip);
  std::vector<ContactPair> want;
  for (int v = 0; v < n; ++v) {
    if (skip[v]) continue;
    for (ContactPair p : find_contact_candidates(body, x.segment<3>(3 * v), 0.5)) {
      p.vertex = v;
      want.push_back(p);
    }
  }
  ASSERT_GT(want.size(), 1000u);
  ASSERT_EQ(pairs.size(), want.size());
  for (size_t k = 0; k < want.size(); ++k) {
    ASSERT_EQ(pairs[k].vertex, want[k].vertex) << k;
    ASSERT_EQ(pairs[k].body.part, want[k].body.part) << k;
    ASSERT_EQ(pairs[k].body.face, want[k].body.face) << k;
    ASSERT_EQ(pairs[k].body.distance2, want[k].body.distance2) << k;
  }
}

// A sheet lying on the floor, its edge 0.3 mm from the wall; the wall moves
// 3 mm into it over 20 steps, pushing it along the floor with the edge
// vertices in the corner, near both parts. After every step every vertex is
// strictly outside both boxes (checked against the boxes themselves), the
// edge has pairs with both parts, and the sheet was pushed.
TEST(Contact, SheetPushedIntoTheCornerOfTwoBoxesEntersNeither) {
  const int cols = 6;
  const double s = 2.0;
  KnitParams kp;
  kp.stitch_width = kp.stitch_height = s;
  const SimModel model = build_sim_model(test::knit_sheet(cols, cols, s, s), kp);
  SimWorkspace ws(model);
  StepOptions o;
  o.time_step_s = 1.0 / 60.0;
  o.contact.friction = 0.3;
  o.newton.force_tolerance_mn = 1e-6;
  o.newton.max_iterations = 100;
  Eigen::VectorXd x0 = test::flatten(model.rest_positions);
  for (int v = 0; v < model.num_vertices(); ++v) x0.segment<3>(3 * v) += Vec3(-0.3 - cols * s, -0.5 * cols * s, 0.3);
  double wall_x = 0.0;
  KinematicBody body(floor_and_wall(wall_x));
  ASSERT_EQ(body.num_parts(), 2);
  SimState st{x0, Eigen::VectorXd::Zero(x0.size()), 0.0};
  const int steps = 20;
  const double push = 3.0 / steps;
  int both_parts = 0;
  for (int k = 0; k < steps; ++k) {
    const std::vector<Vec3> next = floor_and_wall(wall_x - push).vertices;
    const StepResult r = step_simulation(ws, st, body, next, {}, o);
    EXPECT_TRUE(r.converged) << "step " << k << ": force " << r.max_force_mn << " mN";
    wall_x -= push;
    body.move_to(next);
    st = r.state;
    ASSERT_GT(r.min_distance_mm, 0.0) << "step " << k;
    for (int v = 0; v < model.num_vertices(); ++v) {
      const Vec3 p = st.positions_mm.segment<3>(3 * v);
      ASSERT_GT(p.z(), 0.0) << "vertex " << v << " is in the floor at step " << k;
      ASSERT_LT(p.x(), wall_x) << "vertex " << v << " is in the wall at step " << k;
    }
    const std::vector<ContactPair> pairs = find_contact_candidates(body, st.positions_mm, o.contact.distance_mm);
    for (int v = 0; v < model.num_vertices(); ++v) both_parts += pairs_of(pairs, v) == 2;
  }
  EXPECT_GT(both_parts, 0) << "no vertex was ever near both parts";
  // The wall's side of the sheet moved with it (3 mm from where it started).
  double right = -INFINITY;
  for (int v = 0; v < model.num_vertices(); ++v) right = std::max(right, st.positions_mm[3 * v]);
  EXPECT_LT(right, -2.5);
}

}  // namespace
}  // namespace knitforge
