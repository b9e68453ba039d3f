// Marching tetrahedra (geometry/marching_tetrahedra.h): the polygonised zero
// set of an implicit function is closed, manifold, outward-oriented and of the
// right size and topology.
#include "knitforge/geometry/marching_tetrahedra.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>

#include "knitforge/geometry/alpha_close.h"
#include "knitforge/geometry/surface_checks.h"
#include "knitforge/util/errors.h"

namespace knitforge {
namespace {

constexpr double kPi = std::numbers::pi;

BoundingBox box(double lo, double hi) {
  BoundingBox b;
  b.min = Vec3::Constant(lo);
  b.max = Vec3::Constant(hi);
  return b;
}

// One closed, manifold, consistently oriented component of the given genus.
void expect_closed_surface(const TriMesh& m, int genus) {
  const SurfaceReport rep = validate_surface(m);
  ASSERT_TRUE(rep.ok()) << rep.summary();
  EXPECT_TRUE(rep.manifold);
  EXPECT_EQ(rep.num_components, 1);
  EXPECT_EQ(rep.num_boundary_loops, 0);
  EXPECT_EQ(rep.genus, genus);
}

TEST(MarchingTetrahedra, SphereIsClosedManifoldGenusZeroWithTheSphereVolume) {
  const double r = 50.0;
  const Vec3 c(1.3, -2.1, 0.7);  // off the grid's symmetry
  const ImplicitFunction f = [&](const Vec3& p) { return (p - c).norm() - r; };
  const double cell = 4.0;
  const TriMesh m = marching_tetrahedra(f, box(-60, 60), cell);
  expect_closed_surface(m, 0);
  // Every vertex lies on an edge of the grid between an inside and an
  // outside node, where the linear interpolant of f crosses 0: within the
  // chord error of the sphere.
  double worst = 0.0;
  for (const Vec3& p : m.vertices) worst = std::max(worst, std::abs((p - c).norm() - r));
  EXPECT_LT(worst, 0.1 * cell);
  // Outward orientation (positive volume), and the volume of the sphere: the
  // piecewise-linear surface is inscribed, so a little below it.
  const double exact = 4.0 / 3.0 * kPi * r * r * r;
  const double vol = enclosed_volume(m);
  EXPECT_GT(vol, 0.98 * exact);
  EXPECT_LT(vol, 1.001 * exact);
}

TEST(MarchingTetrahedra, VolumeConvergesAsTheCellShrinks) {
  const double r = 30.0;
  const ImplicitFunction f = [&](const Vec3& p) { return p.norm() - r; };
  const double exact = 4.0 / 3.0 * kPi * r * r * r;
  const double e_coarse = std::abs(enclosed_volume(marching_tetrahedra(f, box(-40, 40), 6.0)) - exact);
  const double e_fine = std::abs(enclosed_volume(marching_tetrahedra(f, box(-40, 40), 2.0)) - exact);
  EXPECT_LT(e_fine, 0.25 * e_coarse);  // second order: (6 / 2)^2 = 9
}

TEST(MarchingTetrahedra, TorusHasGenusOne) {
  const double R = 30.0, a = 10.0;
  const ImplicitFunction f = [&](const Vec3& p) {
    const double q = std::hypot(p.x(), p.y()) - R;
    return std::hypot(q, p.z()) - a;
  };
  const TriMesh m = marching_tetrahedra(f, box(-45, 45), 2.5);
  expect_closed_surface(m, 1);
  const double exact = 2.0 * kPi * kPi * R * a * a;
  EXPECT_NEAR(enclosed_volume(m), exact, 0.03 * exact);
}

TEST(MarchingTetrahedra, PlaneIsReproducedExactlyAndCutByTheBox) {
  // A linear f is its own interpolant: every vertex is on the plane, and the
  // surface is the plane clipped to the box (one boundary loop).
  const Vec3 n = Vec3(0.3, -0.2, 1.0).normalized();
  const ImplicitFunction f = [&](const Vec3& p) { return n.dot(p) - 0.37; };
  const TriMesh m = marching_tetrahedra(f, box(-10, 10), 1.0);
  const SurfaceReport rep = validate_surface(m);
  ASSERT_TRUE(rep.ok()) << rep.summary();
  EXPECT_EQ(rep.num_components, 1);
  EXPECT_EQ(rep.num_boundary_loops, 1);
  for (const Vec3& p : m.vertices) EXPECT_NEAR(n.dot(p), 0.37, 1e-9);
  // Normals towards increasing f.
  for (const auto& t : m.faces) {
    const Vec3 fn = (m.vertices[t[1]] - m.vertices[t[0]]).cross(m.vertices[t[2]] - m.vertices[t[0]]);
    EXPECT_GT(fn.dot(n), 0.0);
  }
}

TEST(MarchingTetrahedra, LargestComponentKeepsTheBiggerOfTwoSpheres) {
  const ImplicitFunction f = [](const Vec3& p) {
    return std::min((p - Vec3(-25, 0, 0)).norm() - 15.0, (p - Vec3(25, 0, 0)).norm() - 8.0);
  };
  const TriMesh both = marching_tetrahedra(f, box(-45, 45), 2.0);
  EXPECT_EQ(validate_surface(both).num_components, 2);
  const TriMesh big = largest_component(both);
  expect_closed_surface(big, 0);
  for (const Vec3& p : big.vertices) EXPECT_LT(p.x(), 0.0);
  EXPECT_LT(big.num_vertices(), both.num_vertices());
  const double exact = 4.0 / 3.0 * kPi * 15.0 * 15.0 * 15.0;
  EXPECT_NEAR(enclosed_volume(big), exact, 0.03 * exact);
}

TEST(MarchingTetrahedra, NoSurfaceWhenFDoesNotChangeSign) {
  const ImplicitFunction f = [](const Vec3& p) { return p.norm() + 1.0; };
  EXPECT_EQ(marching_tetrahedra(f, box(-5, 5), 1.0).num_faces(), 0);
}

TEST(MarchingTetrahedra, RejectsBadInput) {
  const ImplicitFunction f = [](const Vec3& p) { return p.norm() - 1.0; };
  EXPECT_THROW(marching_tetrahedra(f, box(-2, 2), 0.0), InvalidInput);
  EXPECT_THROW(marching_tetrahedra(f, box(-2, 2), std::numeric_limits<double>::quiet_NaN()), InvalidInput);
  EXPECT_THROW(marching_tetrahedra(f, box(2, 2), 0.5), InvalidInput);
  EXPECT_THROW(marching_tetrahedra(f, box(-2000, 2000), 1.0), InvalidInput);  // 4001^3 nodes
  const ImplicitFunction nan = [](const Vec3& p) {
    return p.x() > 1.0 ? std::numeric_limits<double>::quiet_NaN() : p.norm() - 1.0;
  };
  try {
    marching_tetrahedra(nan, box(-2, 2), 0.5);
    FAIL() << "expected InvalidInput";
  } catch (const InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find("not finite"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace knitforge
