// Dressing a body: a garment on (or in) the body's surface moved out to a
// clearance (sim/dress_garment.h), and the inside test simulate_cloth()
// refuses a start with.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "geometry/test_meshes.h"
#include "knitforge/geometry/shapes.h"
#include "knitforge/sim/dress_garment.h"
#include "knitforge/sim/kinematic_body.h"
#include "knitforge/util/errors.h"

namespace knitforge {
namespace {

// A cap of points on the sphere of radius r round the z axis (polar angle up
// to 50 degrees), on a grid of polar and azimuth angles.
std::vector<Vec3> cap_points(double r) {
  std::vector<Vec3> p;
  const double pi = 3.14159265358979323846;
  for (int i = 0; i <= 10; ++i)
    for (int j = 0; j < 24; ++j) {
      const double th = (50.0 * pi / 180.0) * i / 10.0, ph = 2 * pi * j / 24.0;
      p.push_back({r * std::sin(th) * std::cos(ph), r * std::sin(th) * std::sin(ph), r * std::cos(th)});
    }
  return p;
}

TEST(DressGarment, MovesEveryVertexOnOrInsideTheBodyOutToTheClearance) {
  const KinematicBody body(test::uv_sphere_mesh(60.0, 48, 24));
  // On the smooth sphere of radius 59: inside the faceted one of radius 60
  // by 0.3 to 1 mm.
  std::vector<Vec3> garment = cap_points(59.0);
  garment.push_back({0, 0, 80});  // far outside: stays
  const size_t far = garment.size() - 1;
  ASSERT_EQ(points_inside_body(body, garment).size(), garment.size() - 1);
  DressOptions o;
  o.clearance_mm = 1.5;
  const DressResult r = dress_garment(body, garment, {}, o);
  EXPECT_EQ(r.moved, static_cast<int>(garment.size()) - 1);
  EXPECT_EQ(r.inside, r.moved);
  EXPECT_GT(r.deepest_mm, 0.3);
  EXPECT_LE(r.deepest_mm, 1.0 + 1e-9);
  EXPECT_LT(r.largest_move_mm, 2.6);
  EXPECT_EQ(r.positions[far], garment[far]);
  for (size_t v = 0; v < garment.size(); ++v) {
    const auto q = body.closest_point_within(r.positions[v], 1e9);
    ASSERT_TRUE(q.has_value());
    if (v != far) {
      EXPECT_NEAR(std::sqrt(q->distance2), 1.5, 1e-9) << "vertex " << v;
    }
  }
  EXPECT_TRUE(points_inside_body(body, r.positions).empty());
  // Dressed again: nothing to do.
  EXPECT_EQ(dress_garment(body, r.positions, {}, o).moved, 0);
}

// A closed body given inside out (its faces point inwards) has the same
// inside: the same vertices are found in it and moved out the same way.
TEST(DressGarment, AnInsideOutClosedBodyHasTheSameInside) {
  TriMesh ball = test::uv_sphere_mesh(60.0, 48, 24);
  const KinematicBody body(ball);
  for (auto& f : ball.faces) std::swap(f[1], f[2]);
  const KinematicBody flipped(ball);
  const std::vector<Vec3> garment = cap_points(59.0);
  EXPECT_EQ(points_inside_body(flipped, garment).size(), garment.size());
  const DressResult a = dress_garment(body, garment, {}), b = dress_garment(flipped, garment, {});
  ASSERT_EQ(a.positions.size(), b.positions.size());
  EXPECT_EQ(a.moved, b.moved);
  EXPECT_EQ(a.inside, b.inside);
  // (the same up to which feature, face or edge, a tie of the closest point
  // goes to in the two face orders: the pseudo-normals there differ a little)
  for (size_t v = 0; v < garment.size(); ++v) {
    EXPECT_LT((a.positions[v] - b.positions[v]).norm(), 0.25) << v;
    EXPECT_NEAR(std::sqrt(flipped.closest_point_within(b.positions[v], 1e9)->distance2), 1.0, 1e-9) << v;
  }
  EXPECT_TRUE(points_inside_body(flipped, b.positions).empty());
}

TEST(DressGarment, PinsStayAndBadInputIsRefusedNamingIt) {
  const KinematicBody body(test::uv_sphere_mesh(60.0, 48, 24));
  std::vector<Vec3> garment = cap_points(59.0);
  const DressResult r = dress_garment(body, garment, {0, 5});
  EXPECT_EQ(r.positions[0], garment[0]);
  EXPECT_EQ(r.positions[5], garment[5]);
  EXPECT_EQ(r.moved, static_cast<int>(garment.size()) - 2);
  // Held vertices are not tested for the inside either.
  EXPECT_EQ(points_inside_body(body, r.positions, {0, 5}).size(), 0u);
  EXPECT_EQ(points_inside_body(body, r.positions).size(), 2u);
  garment[7] = {0, 0, 20};  // 40 mm inside
  try {
    dress_garment(body, garment, {});
    FAIL() << "not refused";
  } catch (const InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find("garment vertex 7 lies 39."), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("place it around the body"), std::string::npos) << e.what();
  }
  DressOptions o;
  o.clearance_mm = 0;
  EXPECT_THROW(dress_garment(body, cap_points(59.0), {}, o), InvalidInput);
  EXPECT_THROW(dress_garment(body, cap_points(59.0), {1000}), InvalidInput);
  std::vector<Vec3> broken = cap_points(59.0);
  broken[3].x() = std::nan("");
  EXPECT_THROW(dress_garment(body, broken, {}), InvalidInput);
  EXPECT_THROW(points_inside_body(body, broken), InvalidInput);
}

TEST(DressGarment, AnOpenBodyHasNoInside) {
  // The upper hemisphere (open): points under it are not "inside".
  const KinematicBody dome(hemisphere(60.0, 8.0));
  EXPECT_TRUE(points_inside_body(dome, cap_points(50.0)).empty());
  // Dressing still moves vertices to the side its normals point to.
  const DressResult r = dress_garment(dome, cap_points(59.9), {});
  EXPECT_GT(r.moved, 0);
  for (const Vec3& p : r.positions) EXPECT_GT(p.norm(), 60.0 - 0.5);
}

}  // namespace
}  // namespace knitforge
