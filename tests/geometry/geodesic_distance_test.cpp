// Tests of geodesic_distance(): fields with known distances.
#include "knitforge/geometry/geodesic_distance.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "geometry/geodesic_test_meshes.h"
#include "geometry/test_meshes.h"
#include "knitforge/geometry/geodesic_source.h"
#include "knitforge/geometry/mesh_measures.h"
#include "knitforge/geometry/shapes.h"
#include "knitforge/util/errors.h"

namespace knitforge {
namespace {

constexpr double kPi = std::numbers::pi;

double segment_distance(const Vec3& p, const Vec3& a, const Vec3& b) {
  return (p - closest_point_on_segment(p, a, b)).norm();
}

// A straight line across a flat, irregularly meshed rectangle: the field is
// |x - c| (signed: x - c), exactly.
TEST(GeodesicDistance, FlatRectangleLineSourceIsExact) {
  const TriMesh m = rectangle(150.0, 100.0, 4.0);
  const double c = 7.3;
  const GeodesicSource src = source_from_plane(m, Vec3(2.0, 0.0, 0.0), c);  // normal need not be unit
  const GeodesicField f = geodesic_distance(m, src);
  ASSERT_TRUE(f.is_signed);
  for (int v = 0; v < m.num_vertices(); ++v) {
    const double expect = m.vertices[v].x() - c;
    ASSERT_NEAR(f.distance[v], expect, 1e-9 * std::max(1.0, std::abs(expect))) << "vertex " << v;
  }
}

// An oblique line: still the Euclidean distance to the line, and the side the
// normal points to is positive.
TEST(GeodesicDistance, FlatObliqueLineSignedByNormal) {
  const TriMesh m = rectangle(150.0, 100.0, 5.0);
  const Vec3 n = Vec3(1.0, 2.0, 0.0).normalized();
  const GeodesicSource src = source_from_plane(m, n, -3.0);
  const GeodesicField f = geodesic_distance(m, src);
  GeodesicOptions unsigned_opt;
  unsigned_opt.signed_field = false;
  const GeodesicField u = geodesic_distance(m, src, unsigned_opt);
  EXPECT_FALSE(u.is_signed);
  ASSERT_EQ(src.polylines.size(), 1u);
  const Vec3 a = surface_point_position(m, src.polylines[0].front());
  const Vec3 b = surface_point_position(m, src.polylines[0].back());
  int pos = 0, neg = 0;
  for (int v = 0; v < m.num_vertices(); ++v) {
    // The domain is convex: the distance to the chord of the line inside it.
    const double side = n.dot(m.vertices[v]) + 3.0;
    const double dist = segment_distance(m.vertices[v], a, b);
    const double expect = side < 0.0 ? -dist : dist;
    ASSERT_NEAR(f.distance[v], expect, 1e-9 * std::max(1.0, dist)) << v << " at " << m.vertices[v].transpose();
    ASSERT_NEAR(u.distance[v], dist, 1e-9 * std::max(1.0, dist));
    pos += side > 1e-6;
    neg += side < -1e-6;
  }
  EXPECT_GT(pos, 100);
  EXPECT_GT(neg, 100);
}

// A segment that ends inside a flat disk: distance to the segment (its
// interior and both end points count).
TEST(GeodesicDistance, FlatSegmentSourceInsideDisk) {
  const TriMesh m = flat_disk(50.0, 4.0);
  const Vec3 a(-20.3, -5.1, 0.0), b(17.9, 11.2, 0.0);
  const GeodesicSource src = source_from_polyline(m, {a, b});
  EXPECT_TRUE(src.vertex_side.empty());  // an open curve inside: unsigned
  EXPECT_NEAR(src.length(m), (b - a).norm(), 1e-9);
  const GeodesicField f = geodesic_distance(m, src);
  EXPECT_FALSE(f.is_signed);
  for (int v = 0; v < m.num_vertices(); ++v) {
    const double expect = segment_distance(m.vertices[v], a, b);
    ASSERT_NEAR(f.distance[v], expect, 1e-9 * std::max(1.0, expect)) << "vertex " << v;
  }
}

// A polyline with a corner: the distance to the union of both segments.
TEST(GeodesicDistance, FlatPolylineWithCorner) {
  const TriMesh m = rectangle(150.0, 100.0, 5.0);
  const Vec3 a(-60.0, -30.0, 0.0), b(0.5, 20.0, 0.0), c(55.0, -35.0, 0.0);
  const GeodesicSource src = source_from_polyline(m, {a, b, c});
  const GeodesicField f = geodesic_distance(m, src);
  for (int v = 0; v < m.num_vertices(); ++v) {
    const Vec3& p = m.vertices[v];
    const double expect = std::min(segment_distance(p, a, b), segment_distance(p, b, c));
    ASSERT_NEAR(f.distance[v], expect, 1e-9 * std::max(1.0, expect)) << "vertex " << v;
  }
}

// A single vertex of a flat convex mesh: Euclidean distance.
TEST(GeodesicDistance, FlatVertexSourceIsEuclidean) {
  const TriMesh m = flat_disk(50.0, 3.0);
  const int s = 17;
  const GeodesicField f = geodesic_distance(m, source_from_vertex(m, s));
  EXPECT_FALSE(f.is_signed);
  for (int v = 0; v < m.num_vertices(); ++v) {
    const double expect = (m.vertices[v] - m.vertices[s]).norm();
    ASSERT_NEAR(f.distance[v], expect, 1e-9 * std::max(1.0, expect)) << "vertex " << v;
  }
  EXPECT_EQ(f.distance[s], 0.0);
}

// A non-convex flat domain (L shape, grid): around the reflex corner the
// distance bends there (a saddle-free boundary vertex acting as pseudo-source).
TEST(GeodesicDistance, LShapeBendsAroundReflexCorner) {
  const TriMesh m = test::l_shape(20);  // [0,20]^2 minus (10,20]x(10,20]
  int src_v = -1;
  for (int v = 0; v < m.num_vertices(); ++v)
    if (m.vertices[v] == Vec3(0.0, 20.0, 0.0)) src_v = v;
  ASSERT_GE(src_v, 0);
  const GeodesicField f = geodesic_distance(m, source_from_vertex(m, src_v));
  const Vec3 corner(10.0, 10.0, 0.0), s_pos(0.0, 20.0, 0.0);
  int hidden_count = 0;
  for (int v = 0; v < m.num_vertices(); ++v) {
    const Vec3& p = m.vertices[v];
    // Points right of the reflex corner above the line y = 20 - x through the
    // source and the corner are not visible: their path bends at the corner.
    const bool hidden = p.x() > 10.0 && p.y() > 20.0 - p.x();
    hidden_count += hidden;
    const double expect = hidden ? (corner - s_pos).norm() + (p - corner).norm() : (p - s_pos).norm();
    ASSERT_NEAR(f.distance[v], expect, 1e-9 * std::max(1.0, expect)) << "vertex " << v << " at " << p.transpose();
  }
  EXPECT_GT(hidden_count, 20);
}

// A developable (exactly unfoldable) cylinder patch: from a generator line the
// distance is the unfolded arc (sum of chords), and from a vertex it is the
// Euclidean distance in the unfolding. Also close to the smooth r·θ.
TEST(GeodesicDistance, DevelopableCylinder) {
  const double r = 40.0;
  const int na = 24, nz = 10;
  const double angle = kPi, height = 50.0;
  const TriMesh m = test::developable_cylinder(r, angle, height, na, nz);
  const double dth = angle / na, chord = 2.0 * r * std::sin(0.5 * dth);
  // Generator at theta = 0 (i = na / 2): the plane y = 0.
  const GeodesicField f = geodesic_distance(m, source_from_plane(m, Vec3(0.0, 1.0, 0.0), 0.0));
  ASSERT_TRUE(f.is_signed);
  for (int v = 0; v < m.num_vertices(); ++v) {
    const Vec3& p = m.vertices[v];
    const double th = std::atan2(p.y(), p.x());
    const double k = std::round(th / dth);
    ASSERT_NEAR(f.distance[v], k * chord, 1e-9 * r) << "vertex " << v;
    EXPECT_NEAR(f.distance[v], r * th, r * std::abs(th) * dth * dth / 24.0 + 1e-9);  // chord vs arc
  }
  // From a vertex: unfolded coordinates (k chord, z).
  const int s = test::developable_cylinder_vertex(na, 3, 2);
  const GeodesicField g = geodesic_distance(m, source_from_vertex(m, s));
  auto unfold = [&](const Vec3& p) {
    return Vec2(std::round(std::atan2(p.y(), p.x()) / dth) * chord, p.z());
  };
  for (int v = 0; v < m.num_vertices(); ++v) {
    const double expect = (unfold(m.vertices[v]) - unfold(m.vertices[s])).norm();
    ASSERT_NEAR(g.distance[v], expect, 1e-9 * r) << "vertex " << v;
  }
}

// The hemisphere from its boundary: R x latitude up to the
// discretisation error of the inscribed polyhedron, which shrinks
// with the edge length (at least halving when the edge length halves).
TEST(GeodesicDistance, HemisphereFromBoundaryConverges) {
  const double R = 75.0;
  double prev_err = 0.0;
  for (double h : {10.0, 5.0}) {
    const TriMesh m = hemisphere(R, h);
    const GeodesicField f = geodesic_distance(m, source_from_boundary(m, 0.0, 1.0));
    EXPECT_FALSE(f.is_signed);
    double err = 0.0;
    for (int v = 0; v < m.num_vertices(); ++v) {
      const Vec3& p = m.vertices[v];
      const double lat = std::asin(std::clamp(p.z() / p.norm(), -1.0, 1.0));
      const double expect = R * lat;
      ASSERT_GE(f.distance[v], 0.0);
      err = std::max(err, std::abs(f.distance[v] - expect));
    }
    // The inscribed polyhedron's paths are shorter than the sphere's by at most
    // about (h / R)^2 / 24 relative (chords versus arcs) plus the boundary
    // polygon's sagitta h^2 / (8 R).
    const double bound = R * kPi / 2.0 * (h / R) * (h / R) / 12.0 + h * h / (8.0 * R);
    EXPECT_LT(err, bound) << "edge length " << h;
    if (prev_err > 0.0) {
      EXPECT_LT(err, 0.5 * prev_err);
    }
    prev_err = err;
  }
}

// Part of the boundary by arc-length fractions on a flat rectangle: the bottom
// side is the distance y + 50 where its projection falls on the part.
TEST(GeodesicDistance, BoundaryPartByFractions) {
  const TriMesh m = rectangle(100.0, 100.0, 5.0);
  // Find where the bottom side lies in the loop's arc length.
  const GeodesicSource whole = source_from_boundary(m, 0.0, 1.0);
  ASSERT_EQ(whole.polylines.size(), 1u);
  EXPECT_NEAR(whole.length(m), 400.0, 1e-9);
  const GeodesicField fw = geodesic_distance(m, whole);
  for (int v = 0; v < m.num_vertices(); ++v) {
    const Vec3& p = m.vertices[v];
    const double expect = std::min({p.x() + 50.0, 50.0 - p.x(), p.y() + 50.0, 50.0 - p.y()});
    ASSERT_NEAR(fw.distance[v], expect, 1e-9 * 50.0);
  }
  // Any part: the field is the Euclidean distance to the part (convex domain).
  const GeodesicSource part = source_from_boundary(m, 0.8, 0.15);  // wraps around
  EXPECT_NEAR(part.length(m), 0.35 * 400.0, 1e-9);
  const GeodesicField fp = geodesic_distance(m, part);
  for (int v = 0; v < m.num_vertices(); ++v) {
    double expect = 1e300;
    for (const auto& line : part.polylines)
      for (size_t i = 0; i + 1 < line.size(); ++i)
        expect = std::min(expect, segment_distance(m.vertices[v], surface_point_position(m, line[i]),
                                                   surface_point_position(m, line[i + 1])));
    ASSERT_NEAR(fp.distance[v], expect, 1e-9 * 50.0);
  }
}

TEST(GeodesicDistance, BoundaryVertexSource) {
  const TriMesh m = test::square_grid(8, 2.0);
  // The bottom side (j = 0): vertices 0..8.
  const GeodesicSource src = source_from_boundary_vertices(m, {3, 2, 4, 8, 3});
  ASSERT_EQ(src.polylines.size(), 2u);  // run 2-3-4 and the corner 8
  const GeodesicField f = geodesic_distance(m, src);
  for (int v = 0; v < m.num_vertices(); ++v) {
    const Vec3& p = m.vertices[v];
    const double expect = std::min(segment_distance(p, Vec3(4, 0, 0), Vec3(8, 0, 0)), (p - Vec3(16, 0, 0)).norm());
    ASSERT_NEAR(f.distance[v], expect, 1e-12);
  }
}

TEST(GeodesicDistance, SolverReusesGeometry) {
  const TriMesh m = flat_disk(30.0, 3.0);
  const GeodesicSolver solver(m);
  for (int s : {0, 5, 40}) {
    const GeodesicField a = solver.distance(source_from_vertex(m, s));
    const GeodesicField b = geodesic_distance(m, source_from_vertex(m, s));
    EXPECT_EQ(a.distance, b.distance);  // deterministic, identical
    EXPECT_GT(a.num_windows, 0u);
  }
}

TEST(GeodesicDistance, ErrorCases) {
  const TriMesh m = test::square_grid(4);
  EXPECT_THROW(geodesic_distance(m, GeodesicSource{}), InvalidInput);
  GeodesicSource bad;
  bad.polylines = {{SurfacePoint{99, Vec3(1, 0, 0)}}};
  EXPECT_THROW(geodesic_distance(m, bad), InvalidInput);
  bad.polylines = {{SurfacePoint{0, Vec3(0.5, 0.6, 0.0)}}};  // does not sum to 1
  EXPECT_THROW(geodesic_distance(m, bad), InvalidInput);
  // Two points in faces that share nothing.
  bad.polylines = {{SurfacePoint{0, Vec3(1.0 / 3, 1.0 / 3, 1.0 / 3)}, SurfacePoint{31, Vec3(1.0 / 3, 1.0 / 3, 1.0 / 3)}}};
  EXPECT_THROW(geodesic_distance(m, bad), InvalidInput);
  GeodesicSource sides = source_from_vertex(m, 0);
  sides.vertex_side = {1, -1};
  EXPECT_THROW(geodesic_distance(m, sides), InvalidInput);
  // A second component without source.
  TriMesh two = m;
  const int n = two.num_vertices();
  for (int v = 0; v < n; ++v) two.vertices.push_back(m.vertices[v] + Vec3(10, 0, 0));
  for (auto f : m.faces) two.faces.push_back({f[0] + n, f[1] + n, f[2] + n});
  EXPECT_THROW(geodesic_distance(two, source_from_vertex(two, 0)), TopologyError);
  TriMesh nan = m;
  nan.vertices[3].x() = std::nan("");
  EXPECT_THROW(geodesic_distance(nan, source_from_vertex(m, 0)), InvalidInput);
}

}  // namespace
}  // namespace knitforge
