#include "knitforge/body/poisson_reconstruct.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "knitforge/geometry/alpha_close.h"
#include "knitforge/geometry/surface_checks.h"
#include "knitforge/util/errors.h"

using namespace knitforge;

namespace {

// Points on a sphere with their outward normals (Fibonacci spiral).
OrientedPoints sphere_points(int n, double radius, const Vec3& centre) {
  OrientedPoints op;
  const double golden = M_PI * (3.0 - std::sqrt(5.0));
  for (int i = 0; i < n; ++i) {
    const double z = 1.0 - 2.0 * (i + 0.5) / n, r = std::sqrt(1.0 - z * z), phi = golden * i;
    const Vec3 d(r * std::cos(phi), r * std::sin(phi), z);
    op.points.push_back(centre + radius * d);
    op.normals.push_back(d);
  }
  return op;
}

}  // namespace

TEST(PoissonReconstruct, ASphereIsReconstructedClosedOutwardAndClose) {
  const Vec3 c(10, -20, 1000);
  const double R = 100.0;
  const PoissonResult r = poisson_reconstruct(sphere_points(4000, R, c));
  const SurfaceReport rep = validate_surface(r.mesh);
  EXPECT_TRUE(rep.ok()) << rep.summary();
  EXPECT_EQ(rep.num_boundary_loops, 0);
  EXPECT_EQ(rep.genus, 0);
  double worst = 0.0, sum2 = 0.0;
  for (const Vec3& v : r.mesh.vertices) {
    const double d = std::abs((v - c).norm() - R);
    worst = std::max(worst, d);
    sum2 += d * d;
  }
  // Spacing ~ sqrt(4 pi R^2 / 4000) ~ 5.6 mm; the mesher's distance bound is
  // 0.375 spacing ~ 2.1 mm.
  EXPECT_LT(worst, PoissonOptions{}.distance * r.spacing_mm);
  EXPECT_LT(std::sqrt(sum2 / r.mesh.num_vertices()), 0.5);
  EXPECT_GT(r.spacing_mm, 3.0);
  EXPECT_LT(r.spacing_mm, 8.0);
  // Oriented outwards: the enclosed volume is positive, near the sphere's.
  EXPECT_NEAR(enclosed_volume(r.mesh) / (4.0 / 3.0 * M_PI * R * R * R), 1.0, 0.03);
}

TEST(PoissonReconstruct, RefusesTooFewOrTooManyPointsAndBadNormals) {
  EXPECT_THROW(poisson_reconstruct(sphere_points(5, 100, Vec3::Zero())), InvalidInput);
  PoissonOptions o;
  o.max_points = 1000;
  try {
    poisson_reconstruct(sphere_points(2000, 100, Vec3::Zero()), o);
    FAIL();
  } catch (const InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find("--voxel"), std::string::npos) << e.what();
  }
  OrientedPoints bad = sphere_points(100, 100, Vec3::Zero());
  bad.normals[7] = Vec3::Zero();
  EXPECT_THROW(poisson_reconstruct(bad), InvalidInput);
}

TEST(PoissonReconstruct, TheSameCloudGivesTheSameMeshEveryTime) {
  // CGAL's surface mesher starts from random points of its default random
  // generator, seeded by the clock once per thread: without a fixed seed
  // the second call (and the next second's run) gives another mesh.
  const OrientedPoints cloud = sphere_points(2000, 100, Vec3(0, 0, 1000));
  const PoissonResult a = poisson_reconstruct(cloud), b = poisson_reconstruct(cloud);
  ASSERT_EQ(a.mesh.vertices.size(), b.mesh.vertices.size());
  EXPECT_EQ(a.mesh.vertices, b.mesh.vertices);
  EXPECT_EQ(a.mesh.faces, b.mesh.faces);
}
