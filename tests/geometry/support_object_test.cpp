#include "knitforge/geometry/support_object.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "knitforge/geometry/alpha_close.h"
#include "knitforge/geometry/halfedges.h"
#include "knitforge/geometry/mesh_measures.h"
#include "knitforge/geometry/shapes.h"
#include "knitforge/util/errors.h"
#include "test_meshes.h"

using namespace knitforge;

namespace {

void expect_watertight(const TriMesh& m) { EXPECT_EQ(test::expect_watertight(m), 1); }

double min_face_area(const TriMesh& m) {
  double a = INFINITY;
  for (double x : face_areas(m)) a = std::min(a, x);
  return a;
}

}  // namespace

TEST(SupportObject, HemisphereOnProjectedBase) {
  const double r = 30.0;
  const TriMesh h = hemisphere(r, 3.0);
  SupportOptions o;
  o.offset = 1.0;
  o.base_height = 5.0;
  const SupportObject s = support_object(h, o);
  expect_watertight(s.solid);
  EXPECT_FALSE(s.reoriented);
  EXPECT_EQ(s.flipped_faces, 0);
  EXPECT_GT(min_face_area(s.solid), 1e-6);
  // Half ball of radius r - offset on a cylinder of height 5.
  const double rr = r - o.offset;
  const double expected = 2.0 / 3.0 * std::numbers::pi * rr * rr * rr + std::numbers::pi * rr * rr * 5.0;
  const double vol = enclosed_volume(s.solid);
  EXPECT_NEAR(vol, expected, 0.03 * expected);
  const BoundingBox box = bounding_box(s.solid);
  EXPECT_NEAR(box.max.z(), rr, 0.05);
  EXPECT_NEAR(box.min.z(), -5.0, 0.1);  // below the lowest offset vertex
  EXPECT_NEAR(box.max.x(), rr, 0.05);
  // Every top vertex lies at distance r - offset from the centre.
  for (int v = 0; v < h.num_vertices(); ++v) EXPECT_NEAR(s.solid.vertices[v].norm(), rr, 0.05);
}

TEST(SupportObject, ReorientsADownwardSurfaceAndBuildsTheRectangleBase) {
  TriMesh grid = test::square_grid(6, 10.0);                                  // 60 x 60 at z = 0
  for (auto& p : grid.vertices) p.z() = 0.002 * (p.x() - 30) * (p.x() - 30);  // gentle trough
  for (auto& t : grid.faces) std::swap(t[1], t[2]);                           // normals down
  SupportOptions o;
  o.offset = 0.0;
  o.base = SupportBase::Rectangle;
  o.base_margin = 10.0;
  o.base_height = 4.0;
  const SupportObject s = support_object(grid, o);
  EXPECT_TRUE(s.reoriented);
  expect_watertight(s.solid);
  EXPECT_GT(enclosed_volume(s.solid), 0.0);
  const BoundingBox box = bounding_box(s.solid);
  EXPECT_NEAR(box.min.x(), -10.0, 1e-9);
  EXPECT_NEAR(box.max.y(), 70.0, 1e-9);
  EXPECT_NEAR(box.min.z(), -4.0, 1e-9);
  EXPECT_GT(min_face_area(s.solid), 1e-6);
  EXPECT_EQ(s.band_triangles, 24 + (s.solid.num_vertices() - grid.num_vertices() - 1));
}

TEST(SupportObject, ShellSupportIsWatertight) {
  const TriMesh h = hemisphere(20.0, 3.0);
  SupportOptions o;
  o.offset = 0.5;
  o.shell_thickness = 2.0;
  const SupportObject s = support_object(h, o);
  expect_watertight(s.solid);
  EXPECT_EQ(s.band_triangles, 0);
  const double expected = 2.0 / 3.0 * std::numbers::pi * (std::pow(19.5, 3) - std::pow(17.5, 3));
  EXPECT_NEAR(enclosed_volume(s.solid), expected, 0.03 * expected);
}

TEST(SupportObject, TriplePeakProjectedBaseWithCollinearBoundary) {
  const TriMesh tp = triple_peak(10.0);
  const SupportObject s = support_object(tp, {});
  expect_watertight(s.solid);
  EXPECT_GT(enclosed_volume(s.solid), 150.0 * 100.0 * 10.0);
  EXPECT_GT(min_face_area(s.solid), 1e-6);
}

TEST(SupportObject, RejectsBadInput) {
  const TriMesh grid = test::square_grid(3, 10.0);
  SupportOptions o;
  o.offset = -1.0;
  EXPECT_THROW(support_object(grid, o), InvalidInput);
  o = {};
  o.base_height = 0.0;
  EXPECT_THROW(support_object(grid, o), InvalidInput);
  o = {};
  o.up = Vec3::Zero();
  EXPECT_THROW(support_object(grid, o), InvalidInput);
  o = {};
  o.up = Vec3(1, 0, 0);  // edge-on
  EXPECT_THROW(support_object(grid, o), InvalidInput);
  EXPECT_THROW(support_object(TriMesh{}, {}), InvalidInput);
  // A closed surface has no boundary loop for a base; a shell works.
  EXPECT_THROW(support_object(test::tetrahedron(), {}), TopologyError);
  o = {};
  o.offset = 0.0;
  o.shell_thickness = 0.1;
  EXPECT_GT(enclosed_volume(support_object(test::tetrahedron(), o).solid), 0.0);
  // An annulus has two boundary loops.
  EXPECT_THROW(support_object(test::ring_grid(2, 16, false), {}), TopologyError);
}
