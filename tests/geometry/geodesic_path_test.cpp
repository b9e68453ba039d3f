// Tests of geodesic_path() and geodesic_path_to_boundary().
#include "knitforge/geometry/geodesic_path.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "geometry/geodesic_test_meshes.h"
#include "geometry/test_meshes.h"
#include "knitforge/geometry/geodesic_distance.h"
#include "knitforge/geometry/geodesic_source.h"
#include "knitforge/geometry/halfedges.h"
#include "knitforge/geometry/mesh_measures.h"
#include "knitforge/geometry/shapes.h"
#include "knitforge/util/errors.h"

namespace knitforge {
namespace {

// Structural checks every path must pass: consistent point descriptions,
// consecutive points sharing a face, and the length as the sum of pieces.
void check_path(const TriMesh& m, const GeodesicPath& path) {
  ASSERT_GE(path.points.size(), 2u);
  double len = 0.0;
  for (size_t i = 0; i < path.points.size(); ++i) {
    const GeodesicPathPoint& p = path.points[i];
    EXPECT_NEAR((surface_point_position(m, p.point) - p.position).norm(), 0.0, 1e-9);
    if (p.is_vertex()) {
      EXPECT_NEAR((m.vertices[p.v0] - p.position).norm(), 0.0, 1e-9);
    }
    if (p.is_edge_point()) {
      EXPECT_GT(p.ratio, 0.0);
      EXPECT_LT(p.ratio, 1.0);
      EXPECT_NEAR(((1 - p.ratio) * m.vertices[p.v0] + p.ratio * m.vertices[p.v1] - p.position).norm(), 0.0, 1e-9);
    }
    if (i > 0) {
      len += (p.position - path.points[i - 1].position).norm();
      // Some face contains both points' supports.
      auto support = [&](const GeodesicPathPoint& q) {
        std::vector<int> s;
        for (int k = 0; k < 3; ++k)
          if (q.point.bary[k] != 0.0) s.push_back(m.faces[q.point.face][k]);
        return s;
      };
      const auto a = support(path.points[i - 1]), b = support(p);
      bool shared = false;
      for (const auto& f : m.faces) {
        bool all = true;
        for (int v : a) all = all && (f[0] == v || f[1] == v || f[2] == v);
        for (int v : b) all = all && (f[0] == v || f[1] == v || f[2] == v);
        if (all) {
          shared = true;
          break;
        }
      }
      EXPECT_TRUE(shared) << "points " << i - 1 << " and " << i << " share no face";
    }
  }
  EXPECT_NEAR(path.length, len, 1e-9 * std::max(1.0, len));
}

bool on_boundary(const TriMesh& m, const Halfedges& he, const GeodesicPathPoint& p) {
  if (p.is_vertex()) return he.is_boundary_vertex(p.v0);
  if (!p.is_edge_point()) return false;
  for (int h = 0; h < he.num_halfedges(); ++h)
    if (he.is_boundary_halfedge(h) && ((he.from(h) == p.v0 && he.to(h) == p.v1) || (he.from(h) == p.v1 && he.to(h) == p.v0)))
      return true;
  (void)m;
  return false;
}

// For a boundary source the field value at a vertex is the length of the
// shortest path from that vertex to the boundary.
TEST(GeodesicPath, ToBoundaryLengthEqualsBoundaryField) {
  for (const TriMesh& m : {triple_peak(8.0), hemisphere(40.0, 6.0)}) {
    const Halfedges he = build_halfedges(m.num_vertices(), m.faces);
    const GeodesicField f = geodesic_distance(m, source_from_boundary(m, 0.0, 1.0));
    for (int v = 0; v < m.num_vertices(); v += std::max(1, m.num_vertices() / 12)) {
      if (he.is_boundary_vertex(v)) continue;
      const GeodesicPath path = geodesic_path_to_boundary(m, surface_point_at_vertex(m, v));
      check_path(m, path);
      EXPECT_NEAR(path.length, f.distance[v], 1e-9 * 100.0) << "vertex " << v;
      EXPECT_EQ(path.points.front().v0, v);
      EXPECT_TRUE(path.points.front().is_vertex());
      EXPECT_TRUE(on_boundary(m, he, path.points.back())) << "vertex " << v;
    }
  }
}

// From the pole of a hemisphere the boundary is R π/2 away (up to the
// inscribed polyhedron's discretisation), and the path ends on the boundary.
TEST(GeodesicPath, HemispherePoleToBoundary) {
  const double R = 40.0;
  const TriMesh m = hemisphere(R, 4.0);
  int top = 0;
  for (int v = 0; v < m.num_vertices(); ++v)
    if (m.vertices[v].z() > m.vertices[top].z()) top = v;
  const GeodesicPath path = geodesic_path_to_boundary(m, surface_point_at_vertex(m, top));
  check_path(m, path);
  // R x latitude of the top vertex, within the discretisation error (1 %).
  EXPECT_NEAR(path.length, R * std::asin(m.vertices[top].z() / R), 0.01 * R);
  EXPECT_GT(path.points.size(), 5u);
}

// On a flat convex mesh the path between two points is the straight segment.
TEST(GeodesicPath, FlatPathIsStraight) {
  const TriMesh m = flat_disk(30.0, 3.0);
  const SurfacePoint a{3, Vec3(0.2, 0.3, 0.5)};
  const SurfacePoint b = closest_surface_point(m, Vec3(17.0, -11.0, 0.0));
  const GeodesicPath path = geodesic_path(m, a, b);
  check_path(m, path);
  const Vec3 pa = surface_point_position(m, a), pb = surface_point_position(m, b);
  EXPECT_NEAR(path.length, (pb - pa).norm(), 1e-9 * 30.0);
  for (const GeodesicPathPoint& p : path.points)
    EXPECT_NEAR((p.position - closest_point_on_segment(p.position, pa, pb)).norm(), 0.0, 1e-9);
  EXPECT_NEAR((path.points.front().position - pa).norm(), 0.0, 1e-12);
  EXPECT_NEAR((path.points.back().position - pb).norm(), 0.0, 1e-12);
}

// Around a reflex corner the path bends exactly at the corner vertex.
TEST(GeodesicPath, LShapeBendsAtCorner) {
  const TriMesh m = test::l_shape(10);  // [0,10]^2 minus (5,10]x(5,10]
  int s = -1, t = -1, corner = -1;
  for (int v = 0; v < m.num_vertices(); ++v) {
    if (m.vertices[v] == Vec3(0, 10, 0)) s = v;
    if (m.vertices[v] == Vec3(10, 4, 0)) t = v;
    if (m.vertices[v] == Vec3(5, 5, 0)) corner = v;
  }
  const GeodesicPath path = geodesic_path(m, surface_point_at_vertex(m, s), surface_point_at_vertex(m, t));
  check_path(m, path);
  EXPECT_NEAR(path.length, std::hypot(5.0, 5.0) + std::hypot(5.0, 1.0), 1e-9);
  bool through_corner = false;
  for (const GeodesicPathPoint& p : path.points) through_corner = through_corner || (p.is_vertex() && p.v0 == corner);
  EXPECT_TRUE(through_corner);
}

// On the developable cylinder a path is straight in the unfolding.
TEST(GeodesicPath, DevelopableCylinderUnfoldedLength) {
  const int na = 16, nz = 8;
  const double r = 30.0, angle = std::numbers::pi, height = 40.0;
  const TriMesh m = test::developable_cylinder(r, angle, height, na, nz);
  const double chord = 2.0 * r * std::sin(angle / na / 2.0);
  const int a = test::developable_cylinder_vertex(na, 1, 1), b = test::developable_cylinder_vertex(na, 14, 6);
  const GeodesicPath path = geodesic_path(m, surface_point_at_vertex(m, a), surface_point_at_vertex(m, b));
  check_path(m, path);
  EXPECT_NEAR(path.length, std::hypot(13 * chord, 5 * height / nz), 1e-9 * r);
  EXPECT_GT(path.points.size(), 10u);  // it crosses many edges
}

// A path whose window reaches the boundary exactly at an end of its edge goes
// on through that vertex (geodesic_propagation.cpp, trace_window_from): on
// the built-in cap the shortest path from the ear (the vertex nearest
// (-90, 0, 0) at edge 2.5) to the neck rim ends at such a vertex; the trace
// once stopped there and returned the straight chord (77.1 mm instead of the
// 79.7 mm of the field), whose two points share no face.
TEST(GeodesicPath, ThroughTheVertexWhereAWindowEnds) {
  const TriMesh m = cap(CapShape{}, 2.5);
  const Halfedges he = build_halfedges(m.num_vertices(), m.faces);
  const GeodesicField f = geodesic_distance(m, source_from_boundary(m, 0.0, 1.0, 0));
  const GeodesicField g = geodesic_distance(m, source_from_boundary(m, 0.0, 1.0, 1));
  for (const Vec3& ear : {Vec3(-90, 0, 0), Vec3(90, 0, 0), Vec3(0, 90, 0), Vec3(0, 0, 90)}) {
    int v = 0;
    for (int u = 0; u < m.num_vertices(); ++u)
      if ((m.vertices[u] - ear).norm() < (m.vertices[v] - ear).norm()) v = u;
    const GeodesicPath path = geodesic_path_to_boundary(m, surface_point_at_vertex(m, v));
    check_path(m, path);
    EXPECT_NEAR(path.length, std::min(f.distance[v], g.distance[v]), 1e-6) << "from " << ear.transpose();
    EXPECT_TRUE(on_boundary(m, he, path.points.back()));
    EXPECT_GT(path.points.size(), 20u);
  }
}

// The shortest path from a source to the nearest of some vertices: between
// the two rims of the tube it runs straight up (the height), from a rim
// point to a vertex of the other rim.
TEST(GeodesicPath, FromSourceToNearestTarget) {
  const TriMesh m = open_tube(20.0, 30.0, 2.0);
  const Halfedges he = build_halfedges(m.num_vertices(), m.faces);
  const auto loops = he.boundary_loops();
  ASSERT_EQ(loops.size(), 2u);
  const GeodesicPath path = geodesic_path_from_source(m, source_from_boundary(m, 0.0, 1.0, 0), loops[1]);
  check_path(m, path);
  EXPECT_NEAR(path.length, 30.0, 0.001 * 30.0);  // straight up, bending where the faceted bands meet
  EXPECT_TRUE(path.points.back().is_vertex());
  EXPECT_NE(std::find(loops[1].begin(), loops[1].end(), path.points.back().v0), loops[1].end());
  EXPECT_TRUE(on_boundary(m, he, path.points.front()));
  // Unreachable targets, no targets.
  TriMesh two = m;
  const int n = two.num_vertices();
  for (int v = 0; v < n; ++v) two.vertices.push_back(m.vertices[v] + Vec3(100, 0, 0));
  for (auto t : m.faces) two.faces.push_back({t[0] + n, t[1] + n, t[2] + n});
  EXPECT_THROW(geodesic_path_from_source(two, source_from_vertex(two, 0), {n + 1}), TopologyError);
  EXPECT_THROW(geodesic_path_from_source(m, source_from_vertex(m, 0), {}), InvalidInput);
  EXPECT_THROW(geodesic_path_from_source(m, source_from_vertex(m, 0), {m.num_vertices()}), InvalidInput);
}

TEST(GeodesicPath, ErrorCases) {
  const TriMesh m = test::square_grid(4);
  EXPECT_THROW(geodesic_path_to_boundary(m, SurfacePoint{-1, Vec3(1, 0, 0)}), InvalidInput);
  EXPECT_THROW(geodesic_path_to_boundary(m, SurfacePoint{0, Vec3(2, -1, 0)}), InvalidInput);
  EXPECT_THROW(geodesic_path(m, SurfacePoint{0, Vec3(1, 0, 0)}, SurfacePoint{999, Vec3(1, 0, 0)}), InvalidInput);
  const TriMesh closed = test::tetrahedron();
  EXPECT_THROW(geodesic_path_to_boundary(closed, SurfacePoint{0, Vec3(1.0 / 3, 1.0 / 3, 1.0 / 3)}), TopologyError);
  TriMesh two = m;
  const int n = two.num_vertices();
  for (int v = 0; v < n; ++v) two.vertices.push_back(m.vertices[v] + Vec3(10, 0, 0));
  for (auto f : m.faces) two.faces.push_back({f[0] + n, f[1] + n, f[2] + n});
  EXPECT_THROW(geodesic_path(two, SurfacePoint{0, Vec3(1, 0, 0)}, SurfacePoint{m.num_faces(), Vec3(1, 0, 0)}),
               TopologyError);
}

}  // namespace
}  // namespace knitforge
