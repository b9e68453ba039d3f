// The two-sides propagation of geodesic_distance() (GeodesicOptions::
// split_sides): for a signed source, the two sides are propagated separately
// (concurrently) and give the field of the single propagation up to rounding;
// sides that are not certified consistent with the source curve (a pocket of
// one side reachable only around the free end of a truncated source, or
// across the other side) fall back to the single propagation.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <thread>
#include <vector>

#include "knitforge/geometry/geodesic_distance.h"
#include "knitforge/geometry/geodesic_source.h"
#include "knitforge/geometry/shapes.h"

namespace knitforge {
namespace {

double mesh_size(const TriMesh& m) {
  Vec3 lo = m.vertices[0], hi = lo;
  for (const Vec3& p : m.vertices) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  return (hi - lo).norm();
}

GeodesicField field(const GeodesicSolver& solver, const GeodesicSource& src, bool split, double tol = 0.0) {
  GeodesicOptions o;
  o.split_sides = split;
  o.tolerance = tol;
  o.max_saddle_fraction = 1.0;
  return solver.distance(src, o);
}

// Largest |a - b| over the vertices (both fields finite where one is).
double max_diff(const GeodesicField& a, const GeodesicField& b) {
  EXPECT_EQ(a.distance.size(), b.distance.size());
  double d = 0.0;
  for (size_t v = 0; v < a.distance.size(); ++v) {
    if (!std::isfinite(a.distance[v]) || !std::isfinite(b.distance[v])) {
      EXPECT_EQ(a.distance[v], b.distance[v]) << "vertex " << v;
      continue;
    }
    d = std::max(d, std::abs(a.distance[v] - b.distance[v]));
  }
  return d;
}

// Split field == single field within 1e-9 x mesh size; deterministic.
void expect_split_matches_single(const TriMesh& m, const GeodesicSource& src, const char* what) {
  const GeodesicSolver solver(m);
  const GeodesicField single = field(solver, src, false);
  const GeodesicField split = field(solver, src, true);
  EXPECT_FALSE(single.split_sides) << what;
  ASSERT_TRUE(split.split_sides) << what;
  EXPECT_TRUE(split.is_signed) << what;
  EXPECT_LE(max_diff(split, single), 1e-9 * mesh_size(m)) << what;
  for (size_t v = 0; v < split.distance.size(); ++v) {
    if (src.vertex_side[v] != 0 && std::isfinite(single.distance[v])) {
      ASSERT_EQ(split.distance[v] < 0.0, src.vertex_side[v] < 0) << what << " vertex " << v;
    }
  }
  EXPECT_NEAR(split.max_abs_distance, single.max_abs_distance, 1e-9 * mesh_size(m)) << what;
  // Each side's propagation is deterministic, so the combination is too.
  const GeodesicField again = field(solver, src, true);
  EXPECT_EQ(again.num_windows, split.num_windows) << what;
  for (size_t v = 0; v < split.distance.size(); ++v)
    ASSERT_EQ(std::memcmp(&again.distance[v], &split.distance[v], sizeof(double)), 0) << what << " vertex " << v;
}

// A grid of `step` squares over [-r, r]^2 minus the cells whose centre
// satisfies `drop`, with a gentle bump (curved, so the windows bend).
template <class Drop>
TriMesh grid_without(double r, double step, Drop drop) {
  TriMesh m;
  const int n = static_cast<int>(std::lround(2 * r / step));
  auto id = [&](int i, int j) { return j * (n + 1) + i; };
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) {
      const double x = -r + i * step, y = -r + j * step;
      m.vertices.emplace_back(x, y, 4.0 * std::sin(x / 11.0) * std::cos(y / 13.0));
    }
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const double cx = -r + (i + 0.5) * step, cy = -r + (j + 0.5) * step;
      if (drop(cx, cy)) continue;
      if ((i + j) % 2 == 0) {
        m.faces.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
        m.faces.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
      } else {
        m.faces.push_back({id(i, j), id(i + 1, j), id(i, j + 1)});
        m.faces.push_back({id(i + 1, j), id(i + 1, j + 1), id(i, j + 1)});
      }
    }
  // Drop the vertices no face uses.
  std::vector<int> remap(m.vertices.size(), -1);
  TriMesh out;
  for (auto& f : m.faces)
    for (int& v : f) {
      if (remap[v] < 0) {
        remap[v] = out.num_vertices();
        out.vertices.push_back(m.vertices[v]);
      }
      v = remap[v];
    }
  out.faces = m.faces;
  return out;
}

// A U: the square minus a slot open at the top (|x| < 9, y > -12).
TriMesh u_shape() {
  return grid_without(30.0, 2.0, [](double x, double y) { return std::abs(x) < 9.0 && y > -12.0; });
}

// A square annulus: the square minus |x|, |y| < 9.
TriMesh annulus() {
  return grid_without(30.0, 2.0, [](double x, double y) { return std::abs(x) < 9.0 && std::abs(y) < 9.0; });
}

TEST(GeodesicSides, HemispherePlanesMatchSingle) {
  const TriMesh m = hemisphere(75.0, 5.0);
  expect_split_matches_single(m, source_from_plane(m, Vec3(1, 0, 0), 0.0), "hemisphere x = 0");
  expect_split_matches_single(m, source_from_plane(m, Vec3(0.3, 1, 0.2), 12.0), "hemisphere oblique");
  // A horizontal plane: a closed circle; the cap is one side, the band the other.
  expect_split_matches_single(m, source_from_plane(m, Vec3(0, 0, 1), 40.0), "hemisphere z = 40");
}

TEST(GeodesicSides, TriplePeakPlanesMatchSingle) {
  const TriMesh m = triple_peak(4.0);
  expect_split_matches_single(m, source_from_plane(m, Vec3(1, 0, 0), 0.0), "triple peak x = 0");
  expect_split_matches_single(m, source_from_plane(m, Vec3(1, -0.4, 0), 7.0), "triple peak oblique");
}

TEST(GeodesicSides, FlatDiskPlanesMatchSingle) {
  const TriMesh m = flat_disk(50.0, 3.0);
  // x = 0 runs through vertices and along edges of the disk's mesh.
  expect_split_matches_single(m, source_from_plane(m, Vec3(1, 0, 0), 0.0), "disk x = 0");
  expect_split_matches_single(m, source_from_plane(m, Vec3(1, 1, 0), 3.3), "disk oblique");
  // The flat field is the signed distance to the line (away from the ends of
  // the chord, where the closest source point is its end on the boundary).
  const GeodesicField f = geodesic_distance(m, source_from_plane(m, Vec3(1, 0, 0), 0.0));
  ASSERT_TRUE(f.split_sides);
  for (int v = 0; v < m.num_vertices(); ++v) {
    if (std::abs(m.vertices[v].y()) < 40.0) {
      ASSERT_NEAR(f.distance[v], m.vertices[v].x(), 1e-9) << v;
    }
  }
}

TEST(GeodesicSides, UShapeAndAnnulusMatchSingle) {
  const TriMesh u = u_shape();
  // y = 10 cuts both arms: three regions (two arm tips on +, the bottom on -).
  const GeodesicSource both = source_from_plane(u, Vec3(0, 1, 0), 10.0);
  ASSERT_EQ(both.polylines.size(), 2u);
  expect_split_matches_single(u, both, "U, both arms");
  const TriMesh a = annulus();
  // x = 9 runs along the hole's right wall (vertices and edges on the plane,
  // boundary edges in the source): the + side is a strip, - wraps the hole.
  expect_split_matches_single(a, source_from_plane(a, Vec3(1, 0, 0), 9.0), "annulus x = 9 (wall)");
  expect_split_matches_single(a, source_from_plane(a, Vec3(1, 0, 0), 10.0), "annulus x = 10");
  expect_split_matches_single(a, source_from_plane(a, Vec3(1, 0.5, 0), 0.0), "annulus through the hole");
}

// Sides that do not match the source curve: the split would drop the only
// paths of some vertices, so the single propagation must be used.
TEST(GeodesicSides, PocketsFallBackToSinglePropagation) {
  const TriMesh u = u_shape();
  const GeodesicSource both = source_from_plane(u, Vec3(0, 1, 0), 10.0);
  const GeodesicSolver solver(u);
  auto check_fallback = [&](const GeodesicSource& src, const char* what) -> GeodesicField {
    const GeodesicField single = field(solver, src, false);
    const GeodesicField f = field(solver, src, true);
    EXPECT_FALSE(f.split_sides) << what;
    EXPECT_EQ(max_diff(f, single), 0.0) << what;
    for (double d : f.distance) EXPECT_TRUE(std::isfinite(d)) << what;
    return single;
  };
  // 1. Only the left arm's cut is the source, the sides still those of the
  // whole plane: the right arm's tip (+) is reached only down the right arm,
  // across the bottom (-) and up the left arm to the source's - side.
  GeodesicSource left = both;
  const auto mean_x = [&](const std::vector<SurfacePoint>& l) {
    double s = 0.0;
    for (const SurfacePoint& p : l) s += surface_point_position(u, p).x();
    return s / static_cast<double>(l.size());
  };
  left.polylines = {mean_x(both.polylines[0]) < 0.0 ? both.polylines[0] : both.polylines[1]};
  const GeodesicField f1 = check_fallback(left, "one arm");
  // The right tip really is farther than any point of the left arm's + side.
  double right_tip = 0.0, left_tip = 0.0;
  for (int v = 0; v < u.num_vertices(); ++v) {
    if (u.vertices[v].y() < 29.0) continue;
    (u.vertices[v].x() > 0.0 ? right_tip : left_tip) =
        std::max(u.vertices[v].x() > 0.0 ? right_tip : left_tip, std::abs(f1.distance[v]));
  }
  EXPECT_GT(right_tip, 60.0);  // around the bottom of the U: at least 2 x 22 + 18 mm in the plane
  EXPECT_LT(left_tip, 30.0);
  // 2. Both cuts, but the left one stops short of the slot's wall: the two
  // sides of the left arm connect around the free end of the source curve.
  GeodesicSource cut = both;
  for (auto& l : cut.polylines)
    if (mean_x(l) < 0.0) {
      // Keep the points with x < -15 (the arm spans -30 .. -9).
      std::vector<SurfacePoint> kept;
      for (const SurfacePoint& p : l)
        if (surface_point_position(u, p).x() < -15.0) kept.push_back(p);
      ASSERT_GE(kept.size(), 2u);
      l = kept;
    }
  check_fallback(cut, "truncated arm");
  // 3. Wrong sides on a correct source: one vertex of the + side labelled -.
  GeodesicSource flipped = both;
  for (int v = 0; v < u.num_vertices(); ++v)
    if (u.vertices[v].y() > 25.0 && u.vertices[v].x() > 20.0) {
      flipped.vertex_side[v] = -1;
      break;
    }
  check_fallback(flipped, "flipped vertex");
}

TEST(GeodesicSides, ApproximateModeKeepsItsBound) {
  const TriMesh m = hemisphere(75.0, 5.0);
  const GeodesicSource src = source_from_plane(m, Vec3(1, 0, 0), 0.0);
  const GeodesicSolver solver(m);
  const GeodesicField exact = field(solver, src, false);
  for (double tol : {1e-3, 3e-3}) {
    const GeodesicField split = field(solver, src, true, tol);
    const GeodesicField single = field(solver, src, false, tol);
    ASSERT_TRUE(split.split_sides);
    EXPECT_LE(max_diff(split, exact), tol) << tol;
    EXPECT_LE(max_diff(single, exact), tol) << tol;
    EXPECT_LT(split.num_windows, exact.num_windows) << tol;
  }
}

TEST(GeodesicSides, UnsignedSourcesUseOnePropagation) {
  const TriMesh m = triple_peak(6.0);
  const GeodesicSolver solver(m);
  EXPECT_FALSE(solver.distance(source_from_boundary(m, 0.0, 0.3)).split_sides);
  EXPECT_FALSE(solver.distance(source_from_vertex(m, 5)).split_sides);
  // A signed source with the option off, and an unsigned-field request that
  // still splits (the sides are known) but returns distances >= 0.
  const GeodesicSource plane = source_from_plane(m, Vec3(1, 0, 0), 0.0);
  GeodesicOptions o;
  o.signed_field = false;
  const GeodesicField f = solver.distance(plane, o);
  EXPECT_TRUE(f.split_sides);
  EXPECT_FALSE(f.is_signed);
  for (double d : f.distance) ASSERT_GE(d, 0.0);
}

// One solver used by two threads at once (each distance() call runs its own
// two side propagations): the same fields as sequential calls.
TEST(GeodesicSides, SolverIsUsableConcurrently) {
  const TriMesh m = triple_peak(6.0);
  const GeodesicSolver solver(m);
  const GeodesicSource a = source_from_plane(m, Vec3(1, 0, 0), 0.0);
  const GeodesicSource b = source_from_plane(m, Vec3(0, 1, 0), 5.0);
  const GeodesicField ra = solver.distance(a), rb = solver.distance(b);
  GeodesicField ca, cb;
  std::thread t([&] { ca = solver.distance(a); });
  cb = solver.distance(b);
  t.join();
  EXPECT_EQ(max_diff(ca, ra), 0.0);
  EXPECT_EQ(max_diff(cb, rb), 0.0);
}

}  // namespace
}  // namespace knitforge
