#include "knitforge/geometry/thicken_surface.h"

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

namespace {}  // namespace

TEST(ThickenSurface, FlatSquareBecomesABox) {
  const TriMesh grid = test::square_grid(4, 10.0);  // 40 x 40 in z = 0, normal +z
  for (ThickenSide side : {ThickenSide::Both, ThickenSide::Outside, ThickenSide::Inside}) {
    const ThickenResult r = thicken_surface(grid, {3.0, side});
    test::expect_watertight(r.solid);
    EXPECT_EQ(r.flipped_faces, 0);
    EXPECT_EQ(r.fallback_normals, 0);
    EXPECT_EQ(r.solid.num_vertices(), 2 * grid.num_vertices());
    // 2 layers + 16 boundary edges x 2 triangles
    EXPECT_EQ(r.solid.num_faces(), 2 * grid.num_faces() + 32);
    EXPECT_NEAR(enclosed_volume(r.solid), 40.0 * 40.0 * 3.0, 1e-9);
    const BoundingBox box = bounding_box(r.solid);
    const double top = side == ThickenSide::Both ? 1.5 : side == ThickenSide::Outside ? 3.0 : 0.0;
    EXPECT_NEAR(box.max.z(), top, 1e-12);
    EXPECT_NEAR(box.min.z(), top - 3.0, 1e-12);
  }
}

TEST(ThickenSurface, HemisphereShellVolume) {
  const double r = 30.0, t = 2.0;
  const TriMesh h = hemisphere(r, 3.0);
  const ThickenResult res = thicken_surface(h, {t, ThickenSide::Both});
  test::expect_watertight(res.solid);
  EXPECT_EQ(res.flipped_faces, 0);
  // Shell between radii r - t/2 and r + t/2 (polygonal: a little less).
  const double expected = 2.0 / 3.0 * std::numbers::pi * (std::pow(r + t / 2, 3) - std::pow(r - t / 2, 3));
  const double vol = enclosed_volume(res.solid);
  EXPECT_GT(vol, 0.0) << "outward-facing";
  EXPECT_NEAR(vol, expected, 0.03 * expected);
}

TEST(ThickenSurface, ThicknessBeyondCurvatureRadiusReportsFlips) {
  const TriMesh h = hemisphere(10.0, 1.5);
  // Inward by more than the radius: the inner layer turns inside out.
  const ThickenResult res = thicken_surface(h, {25.0, ThickenSide::Inside});
  EXPECT_GT(res.flipped_faces, h.num_faces() / 2);
  // Half the radius: nothing turns over.
  EXPECT_EQ(thicken_surface(h, {5.0, ThickenSide::Inside}).flipped_faces, 0);
  // A saddle thickened by more than its curvature radius (~ 8 mm at the
  // centre of this one) turns over in one principal direction.
  TriMesh saddle = monkey_saddle(5.0);
  for (auto& p : saddle.vertices) p.z() = 0.02 * (p.x() * p.x() - p.y() * p.y());
  int flipped = 0;
  offset_surface(saddle, 60.0, &flipped);
  EXPECT_GT(flipped, 0);
  offset_surface(saddle, 5.0, &flipped);
  EXPECT_EQ(flipped, 0);
  test::expect_watertight(res.solid);  // still closed, though self-intersecting
}

TEST(ThickenSurface, ClosedSurfaceGivesTwoShells) {
  TriMesh tet;
  tet.vertices = {Vec3(0, 0, 0), Vec3(10, 0, 0), Vec3(0, 10, 0), Vec3(0, 0, 10)};
  tet.faces = {{0, 2, 1}, {0, 1, 3}, {1, 2, 3}, {0, 3, 2}};
  const ThickenResult res = thicken_surface(tet, {0.5, ThickenSide::Both});
  test::expect_watertight(res.solid);
  EXPECT_EQ(res.solid.num_faces(), 8);
  int count = 0;
  build_halfedges(res.solid.num_vertices(), res.solid.faces).face_components(&count);
  EXPECT_EQ(count, 2);
}

TEST(ThickenSurface, DegenerateNormalsUseTheFallbackOrThrow) {
  // Two faces folded exactly onto each other: the normals cancel at the
  // shared edge's vertices, whichever weighting.
  TriMesh cancel;
  cancel.vertices = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 1, 0)};
  cancel.faces = {{0, 1, 2}, {1, 0, 3}};  // face 1 is face 0 mirrored: normals cancel at 0 and 1
  EXPECT_THROW(offset_normals(cancel), InvalidInput);
  // A tiny vertical sliver next to a good face: the area-weighted normal is
  // (almost) the good face's; unit-normal averaging would tilt it by 45°.
  TriMesh sliver;
  sliver.vertices = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0.5, -1e-9, 1e-3)};
  sliver.faces = {{0, 1, 2}, {1, 0, 3}};
  int fallbacks = -1;
  const auto n = offset_normals(sliver, &fallbacks);
  EXPECT_EQ(fallbacks, 0);
  EXPECT_GT(n[0].z(), 0.999);
  EXPECT_GT(n[0].y(), 0.0);
}

TEST(ThickenSurface, RejectsBadInput) {
  const TriMesh grid = test::square_grid(2, 1.0);
  EXPECT_THROW(thicken_surface(grid, {0.0}), InvalidInput);
  EXPECT_THROW(thicken_surface(grid, {-1.0}), InvalidInput);
  EXPECT_THROW(thicken_surface(grid, {std::nan("")}), InvalidInput);
  EXPECT_THROW(thicken_surface(TriMesh{}, {1.0}), InvalidInput);
  TriMesh bad = grid;
  std::swap(bad.faces[0][1], bad.faces[0][2]);  // inconsistent orientation
  EXPECT_THROW(thicken_surface(bad, {1.0}), TopologyError);
  EXPECT_THROW(offset_surface(grid, INFINITY), InvalidInput);
  int flipped = -1;
  const TriMesh up = offset_surface(grid, 2.0, &flipped);
  EXPECT_EQ(flipped, 0);
  EXPECT_NEAR(up.vertices[0].z(), 2.0, 1e-12);
}
