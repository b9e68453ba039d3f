// Tests of the geodesic source builders (geodesic_source.h).
#include "knitforge/geometry/geodesic_source.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <vector>

#include "geometry/test_meshes.h"
#include "knitforge/geometry/geodesic_distance.h"
#include "knitforge/geometry/mesh_measures.h"
#include "knitforge/geometry/shapes.h"
#include "knitforge/util/errors.h"

namespace knitforge {
namespace {

// Every point of every polyline lies on the plane; consecutive points share a face.
TEST(GeodesicSource, PlaneSectionLiesOnPlane) {
  const TriMesh m = triple_peak(6.0);
  const GeodesicSource src = source_from_plane(m, Vec3(1, 0, 0), 0.0);
  ASSERT_EQ(src.polylines.size(), 1u);
  EXPECT_GT(src.num_segments(), 20);
  EXPECT_GT(src.length(m), 100.0);  // y from -50 to 50 over the middle peak
  for (const auto& line : src.polylines)
    for (const SurfacePoint& p : line) EXPECT_NEAR(surface_point_position(m, p).x(), 0.0, 1e-9);
  ASSERT_EQ(src.vertex_side.size(), static_cast<size_t>(m.num_vertices()));
  for (int v = 0; v < m.num_vertices(); ++v) {
    const double x = m.vertices[v].x();
    if (std::abs(x) > 1e-6) {
      EXPECT_EQ(src.vertex_side[v], x > 0 ? 1 : -1);
    }
  }
  // The signed field has the sign of the side.
  const GeodesicField f = geodesic_distance(m, src);
  for (int v = 0; v < m.num_vertices(); ++v)
    if (src.vertex_side[v] != 0) {
      EXPECT_EQ(f.distance[v] > 0, src.vertex_side[v] > 0);
    }
}

// A plane through a row of vertices: the source runs along mesh edges.
TEST(GeodesicSource, PlaneThroughVertices) {
  const TriMesh m = test::square_grid(6, 1.0);
  const GeodesicSource src = source_from_plane(m, Vec3(0, -1, 0), -2.0);  // y = 2, normal -y
  ASSERT_EQ(src.polylines.size(), 1u);
  EXPECT_EQ(src.polylines[0].size(), 7u);
  const GeodesicField f = geodesic_distance(m, src);
  for (int v = 0; v < m.num_vertices(); ++v) EXPECT_NEAR(f.distance[v], 2.0 - m.vertices[v].y(), 1e-12);
}

// A plane crossing the surface in two pieces gives two polylines.
TEST(GeodesicSource, PlaneWithTwoPieces) {
  const TriMesh m = hemisphere(30.0, 5.0);
  const GeodesicSource src = source_from_plane(m, Vec3(0, 0, 1), 0.5 * 30.0);  // a circle: one closed loop
  ASSERT_EQ(src.polylines.size(), 1u);
  EXPECT_NEAR((surface_point_position(m, src.polylines[0].front()) - surface_point_position(m, src.polylines[0].back())).norm(), 0.0, 1e-12);
  const TriMesh s = monkey_saddle(6.0);
  const GeodesicSource two = source_from_plane(s, Vec3(0, 0, 1), 30.0);  // high level set: the three lobes
  EXPECT_GE(two.polylines.size(), 2u);
}

TEST(GeodesicSource, BoundaryFractionsAndWrap) {
  const TriMesh m = test::square_grid(4, 1.0);  // boundary length 16
  const GeodesicSource all = source_from_boundary(m, 0.0, 1.0);
  EXPECT_NEAR(all.length(m), 16.0, 1e-12);
  const GeodesicSource part = source_from_boundary(m, 0.1, 0.3);
  EXPECT_NEAR(part.length(m), 0.2 * 16.0, 1e-12);
  const GeodesicSource wrap = source_from_boundary(m, 0.9, 0.05);
  EXPECT_NEAR(wrap.length(m), 0.15 * 16.0, 1e-12);
  const GeodesicSource point = source_from_boundary(m, 0.5, 0.5);
  ASSERT_EQ(point.polylines.size(), 1u);
  EXPECT_EQ(point.polylines[0].size(), 1u);
  EXPECT_TRUE(all.vertex_side.empty());
  EXPECT_THROW(source_from_boundary(m, -0.1, 0.5), InvalidInput);
  EXPECT_THROW(source_from_boundary(m, 0.2, 1.5), InvalidInput);
  EXPECT_THROW(source_from_boundary(m, 0.2, std::nan("")), InvalidInput);
  EXPECT_THROW(source_from_boundary(m, 0.2, 0.4, 1), InvalidInput);
  EXPECT_THROW(source_from_boundary(test::tetrahedron(), 0.2, 0.4), InvalidInput);  // no boundary loop
}

// Vertex paths: a row of grid vertices is the same source as the plane
// through it (same field), signed with the left of the path positive; a
// path that does not cross the surface is unsigned.
TEST(GeodesicSource, VertexPaths) {
  const TriMesh m = test::square_grid(6, 1.0);
  std::vector<int> row;
  for (int i = 0; i <= 6; ++i) row.push_back(2 * 7 + i);  // y = 2, walking towards +x
  const GeodesicSource src = source_from_vertex_paths(m, {row}, "row y = 2");
  EXPECT_EQ(src.description, "row y = 2");
  ASSERT_EQ(src.vertex_side.size(), static_cast<size_t>(m.num_vertices()));
  const GeodesicField f = geodesic_distance(m, src);
  for (int v = 0; v < m.num_vertices(); ++v) {
    EXPECT_NEAR(f.distance[v], m.vertices[v].y() - 2.0, 1e-12) << v;  // +y is left of +x (normal +z)
    EXPECT_EQ(src.vertex_side[v], m.vertices[v].y() > 2.0 ? 1 : (m.vertices[v].y() < 2.0 ? -1 : 0));
  }
  EXPECT_EQ(source_sides(m, src), src.vertex_side);
  const GeodesicSource part = source_from_vertex_paths(m, {{16, 17, 18}}, "part");
  EXPECT_TRUE(part.vertex_side.empty());
  const GeodesicSource point = source_from_vertex_paths(m, {{24}}, "point");
  ASSERT_EQ(point.polylines.size(), 1u);
  EXPECT_EQ(point.polylines[0].size(), 1u);
  EXPECT_THROW(source_from_vertex_paths(m, {{0, 30}}, "gap"), InvalidInput);
  EXPECT_THROW(source_from_vertex_paths(m, {{0, 99}}, "range"), InvalidInput);
  EXPECT_THROW(source_from_vertex_paths(m, {{}}, "empty"), InvalidInput);
}

// A meridian of the hemisphere with any number of points is one polyline on
// the meridian plane (the normal section), whose consecutive points share a
// face; with 3 or 5 points one of them lies within 1e-14 of the pole and is
// put exactly on that vertex. Before, every other point count failed
// ("cannot be joined along the surface").
TEST(GeodesicSource, PolylineJoinedAlongItsNormalSection) {
  for (const double edge : {2.5, 10.0}) {
    const TriMesh m = hemisphere(75.0, edge);
    for (int n = 2; n <= 32; ++n) {
      SCOPED_TRACE(::testing::Message() << n << " points, edge " << edge);
      std::vector<Vec3> pts;
      for (int i = 0; i < n; ++i) {
        const double a = std::numbers::pi * i / (n - 1);
        pts.emplace_back(0.0, 75.0 * std::cos(a), 75.0 * std::sin(a));
      }
      const GeodesicSource src = source_from_polyline(m, pts);
      ASSERT_EQ(src.polylines.size(), 1u);
      const auto& line = src.polylines[0];
      EXPECT_GE(line.size(), static_cast<size_t>(n));
      for (size_t i = 0; i < line.size(); ++i) {
        if (n >= 3) {
          EXPECT_NEAR(surface_point_position(m, line[i]).x(), 0.0, 1e-9) << i;
        }
        if (i > 0) {
          // some face holds both points' supports
          bool shared = false;
          for (const auto& t : m.faces) {
            bool all = true;
            for (const SurfacePoint* p : {&line[i - 1], &line[i]})
              for (int k = 0; k < 3; ++k)
                if (p->bary[k] != 0.0) {
                  const int v = m.faces[p->face][k];
                  all = all && (t[0] == v || t[1] == v || t[2] == v);
                }
            if (all) {
              shared = true;
              break;
            }
          }
          EXPECT_TRUE(shared) << "points " << i - 1 << ", " << i;
        }
      }
      EXPECT_FALSE(src.vertex_side.empty());  // boundary to boundary: it cuts the hemisphere in two
      EXPECT_NO_THROW(geodesic_distance(m, src));
    }
    // A point within 1e-14 of the pole (a vertex) is the vertex.
    const GeodesicSource pole = source_from_polyline(m, {Vec3(0.0, 1e-14, 75.0)});
    const SurfacePoint& p = pole.polylines[0][0];
    EXPECT_EQ(surface_point_position(m, p), m.vertices[0]);
    EXPECT_EQ((p.bary.array() == 1.0).count(), 1);
  }
}

TEST(GeodesicSource, ErrorCases) {
  const TriMesh m = test::square_grid(4, 1.0);
  EXPECT_THROW(source_from_plane(m, Vec3(1, 0, 0), 7.0), InvalidInput);  // misses: x in [0, 4]
  EXPECT_THROW(source_from_plane(m, Vec3(0, 0, 0), 1.0), InvalidInput);
  EXPECT_THROW(source_from_plane(m, Vec3(1, 0, 0), std::nan("")), InvalidInput);
  EXPECT_THROW(source_from_plane(TriMesh{}, Vec3(1, 0, 0), 0.0), InvalidInput);
  EXPECT_THROW(source_from_vertex(m, -1), InvalidInput);
  EXPECT_THROW(source_from_vertex(m, m.num_vertices()), InvalidInput);
  EXPECT_THROW(source_from_boundary_vertices(m, {}), InvalidInput);
  EXPECT_THROW(source_from_boundary_vertices(m, {6}), InvalidInput);  // interior vertex
  EXPECT_THROW(source_from_boundary_vertices(m, {99}), InvalidInput);
  EXPECT_THROW(source_from_polyline(m, {}), InvalidInput);
  EXPECT_THROW(source_from_polyline(m, {Vec3(1, 1, std::nan(""))}), InvalidInput);
  EXPECT_THROW(surface_point_on_edge(m, 0, 7, 0.5), InvalidInput);  // not an edge
  EXPECT_THROW(surface_point_on_edge(m, 0, 1, 1.5), InvalidInput);
}

// A closed polyline cuts the disk in two: signed, positive on its left
// (inside for a counter-clockwise loop), and the distance is to the square.
TEST(GeodesicSource, ClosedPolylineIsSigned) {
  const TriMesh m = flat_disk(40.0, 4.0);
  const std::vector<Vec3> sq = {Vec3(-10, -10, 0), Vec3(10, -10, 0), Vec3(10, 10, 0), Vec3(-10, 10, 0),
                                Vec3(-10, -10, 0)};
  const GeodesicSource src = source_from_polyline(m, sq);
  ASSERT_FALSE(src.vertex_side.empty());
  const GeodesicField f = geodesic_distance(m, src);
  ASSERT_TRUE(f.is_signed);
  for (int v = 0; v < m.num_vertices(); ++v) {
    const Vec3& p = m.vertices[v];
    double d = 1e300;
    for (int i = 0; i < 4; ++i) d = std::min(d, (p - closest_point_on_segment(p, sq[i], sq[i + 1])).norm());
    const bool inside = std::abs(p.x()) < 10 && std::abs(p.y()) < 10;
    if (d < 1e-9) continue;
    EXPECT_NEAR(f.distance[v], inside ? d : -d, 1e-9) << "vertex " << v;
  }
}

// On a curved surface the projected polyline stays on the surface, and a
// polyline from boundary to boundary cuts it in two.
TEST(GeodesicSource, PolylineOnCurvedSurface) {
  const double R = 30.0;
  const TriMesh m = hemisphere(R, 4.0);
  std::vector<Vec3> pts;
  for (int i = 0; i <= 8; ++i) {
    const double a = -std::numbers::pi / 2 + std::numbers::pi * i / 8;  // meridian through the pole in y = 0.3 x
    pts.push_back(R * Vec3(std::sin(a) / std::sqrt(1.09), 0.3 * std::sin(a) / std::sqrt(1.09), std::cos(a)));
  }
  const GeodesicSource src = source_from_polyline(m, pts);
  ASSERT_EQ(src.polylines.size(), 1u);
  EXPECT_GT(src.polylines[0].size(), pts.size());  // edge crossings inserted
  for (const SurfacePoint& p : src.polylines[0]) EXPECT_NEAR(surface_point_position(m, p).norm(), R, 0.02 * R);
  EXPECT_NEAR(src.length(m), std::numbers::pi * R, 0.02 * std::numbers::pi * R);
  EXPECT_FALSE(src.vertex_side.empty());
  const GeodesicField f = geodesic_distance(m, src);  // consecutive points share faces
  EXPECT_TRUE(f.is_signed);
}

}  // namespace
}  // namespace knitforge
