#include "knitforge/geometry/alpha_close.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "knitforge/geometry/halfedges.h"
#include "knitforge/geometry/mesh_measures.h"
#include "knitforge/geometry/shapes.h"
#include "knitforge/util/errors.h"
#include "test_meshes.h"

using namespace knitforge;

namespace {

// Fibonacci sphere points.
TriMesh sphere_points(double r, int n) {
  TriMesh m;
  const double golden = std::numbers::pi * (3.0 - std::sqrt(5.0));
  for (int i = 0; i < n; ++i) {
    const double z = 1.0 - 2.0 * (i + 0.5) / n;
    const double rho = std::sqrt(1.0 - z * z);
    m.vertices.emplace_back(r * rho * std::cos(golden * i), r * rho * std::sin(golden * i), r * z);
  }
  return m;
}

}  // namespace

TEST(AlphaClose, SpherePointCloudGivesAClosedBall) {
  const double r = 20.0;
  AlphaCloseOptions o;
  o.alpha = 4.0;
  o.offset = 0.5;
  const AlphaCloseResult res = alpha_close(sphere_points(r, 1500), o);
  test::expect_watertight(res.mesh);
  EXPECT_EQ(res.capped_holes, 0);
  int components = 0;
  build_halfedges(res.mesh.num_vertices(), res.mesh.faces).face_components(&components);
  EXPECT_EQ(components, 1);
  // The wrap lies about `offset` outside the points.
  const double expected = 4.0 / 3.0 * std::numbers::pi * std::pow(r + o.offset, 3);
  EXPECT_GT(res.volume, 0.0) << "outward-oriented";
  EXPECT_NEAR(res.volume, expected, 0.06 * expected);
  EXPECT_NEAR(res.volume, enclosed_volume(res.mesh), 1e-9 * res.volume);
  for (const Vec3& p : res.mesh.vertices) EXPECT_NEAR(p.norm(), r + o.offset, 1.5);
}

TEST(AlphaClose, OpenHemisphereIsCappedIntoAHalfBall) {
  const double r = 20.0;
  const TriMesh h = hemisphere(r, 3.0);
  AlphaCloseOptions o;
  o.alpha = 3.0;
  o.offset = 0.5;
  const AlphaCloseResult res = alpha_close(h, o);
  test::expect_watertight(res.mesh);
  EXPECT_EQ(res.capped_holes, 1);
  const double expected = 2.0 / 3.0 * std::numbers::pi * r * r * r;
  EXPECT_NEAR(res.volume, expected, 0.12 * expected);
  EXPECT_GT(res.volume, expected);  // the wrap encloses the input
  // Without capping the wrap is a thin shell around the bowl: far less volume.
  o.cap_holes = false;
  const AlphaCloseResult shell = alpha_close(h, o);
  test::expect_watertight(shell.mesh);
  EXPECT_LT(shell.volume, 0.3 * expected);
}

TEST(AlphaClose, GapsNarrowerThanAlphaAreBridged) {
  // Two cubes 2 mm apart ("toes"): a large alpha bridges the gap (one
  // component), a small one keeps them apart.
  auto cube = [](TriMesh& m, const Vec3& lo, double s) {
    const int b = m.num_vertices();
    for (int i = 0; i < 8; ++i) m.vertices.push_back(lo + s * Vec3(i & 1, (i >> 1) & 1, (i >> 2) & 1));
    const int f[12][3] = {{0, 2, 1}, {1, 2, 3}, {4, 5, 6}, {5, 7, 6}, {0, 1, 4}, {1, 5, 4},
                          {2, 6, 3}, {3, 6, 7}, {0, 4, 2}, {2, 4, 6}, {1, 3, 5}, {3, 7, 5}};
    for (const auto& t : f) m.faces.push_back({b + t[0], b + t[1], b + t[2]});
  };
  TriMesh two;
  cube(two, Vec3(0, 0, 0), 10.0);
  cube(two, Vec3(12, 0, 0), 10.0);
  AlphaCloseOptions o;
  o.offset = 0.3;
  o.alpha = 6.0;
  int comps = 0;
  AlphaCloseResult res = alpha_close(two, o);
  test::expect_watertight(res.mesh);
  build_halfedges(res.mesh.num_vertices(), res.mesh.faces).face_components(&comps);
  EXPECT_EQ(comps, 1);
  EXPECT_GT(res.volume, 2000.0 + 0.5 * 200.0);  // the 2 x 10 x 10 gap is (mostly) filled
  o.alpha = 0.5;
  res = alpha_close(two, o);
  test::expect_watertight(res.mesh);
  build_halfedges(res.mesh.num_vertices(), res.mesh.faces).face_components(&comps);
  EXPECT_EQ(comps, 2);
}

TEST(AlphaClose, ParameterValidationAndDefaults) {
  const TriMesh tet = test::tetrahedron();
  EXPECT_THROW(alpha_close(tet, {-1.0, 0.0}), InvalidInput);
  EXPECT_THROW(alpha_close(tet, {1.0, -0.1}), InvalidInput);
  EXPECT_THROW(alpha_close(tet, {std::nan(""), 0.0}), InvalidInput);
  TriMesh few;
  few.vertices = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0)};
  EXPECT_THROW(alpha_close(few), InvalidInput);
  TriMesh same;
  same.vertices.assign(5, Vec3(1, 2, 3));
  EXPECT_THROW(alpha_close(same), InvalidInput);
  TriMesh bad = tet;
  bad.faces[0][0] = 9;
  EXPECT_THROW(alpha_close(bad), InvalidInput);
  const AlphaCloseResult res = alpha_close(tet);
  const double diag = bounding_box(tet).diagonal();
  EXPECT_NEAR(res.alpha, diag / 20.0, 1e-12);
  EXPECT_NEAR(res.offset, res.alpha / 30.0, 1e-12);
  test::expect_watertight(res.mesh);
  // The tetrahedron has volume 8/3; the wrap encloses it, slightly larger.
  EXPECT_GT(res.volume, 8.0 / 3.0);
  EXPECT_LT(res.volume, 8.0 / 3.0 * 1.5);
}

namespace knitforge {
namespace {

TEST(AlphaClose, TooSmallAlphaIsRefusedBeforeWrapping) {
  const TriMesh m = hemisphere(75.0, 8.0);
  AlphaCloseOptions o;
  o.alpha = 0.01;  // ~1 billion triangles
  try {
    alpha_close(m, o);
    FAIL() << "no throw";
  } catch (const InvalidInput& e) {
    const std::string s = e.what();
    EXPECT_NE(s.find("billion triangles"), std::string::npos) << s;
    EXPECT_NE(s.find("limit of 2 million"), std::string::npos) << s;
  }
  o.alpha = 6.0;
  o.max_faces = 100.0;  // the limit is the caller's
  EXPECT_THROW(alpha_close(m, o), InvalidInput);
}

}  // namespace
}  // namespace knitforge
