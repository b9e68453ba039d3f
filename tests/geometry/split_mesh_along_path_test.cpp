#include "knitforge/geometry/split_mesh_along_path.h"

#include <cmath>
#include <set>
#include <string>
#include <utility>

#include <gtest/gtest.h>

#include "geometry/test_meshes.h"
#include "knitforge/geometry/halfedges.h"
#include "knitforge/geometry/isocurves.h"
#include "knitforge/geometry/mesh_measures.h"
#include "knitforge/geometry/shapes.h"
#include "knitforge/geometry/surface_checks.h"
#include "knitforge/util/errors.h"

namespace knitforge {
namespace {

std::set<std::pair<int, int>> undirected_edges(const TriMesh& m) {
  std::set<std::pair<int, int>> e;
  for (const auto& t : m.faces)
    for (int k = 0; k < 3; ++k) e.insert(std::minmax(t[k], t[(k + 1) % 3]));
  return e;
}

// The invariants every split must satisfy.
void check_split(const TriMesh& in, const SplitMeshResult& r) {
  ASSERT_EQ(r.original_num_vertices, in.num_vertices());
  ASSERT_EQ(r.mesh.num_vertices(), in.num_vertices() + static_cast<int>(r.new_vertex_origin.size()));
  for (int v = 0; v < in.num_vertices(); ++v) EXPECT_EQ(r.mesh.vertices[v], in.vertices[v]);
  EXPECT_NEAR(total_area(r.mesh), total_area(in), 1e-9 * total_area(in));
  const auto edges = undirected_edges(r.mesh);
  for (size_t i = 1; i < r.path.size(); ++i) {
    EXPECT_NE(r.path[i - 1], r.path[i]);
    EXPECT_TRUE(edges.count(std::minmax(r.path[i - 1], r.path[i])))
        << "path segment " << i - 1 << " is not an edge";
  }
  const SurfaceReport before = validate_surface(in);
  const SurfaceReport after = validate_surface(r.mesh);
  EXPECT_TRUE(after.ok()) << after.summary();
  EXPECT_EQ(after.num_components, before.num_components);
  EXPECT_EQ(after.num_boundary_loops, before.num_boundary_loops);
  EXPECT_EQ(after.genus, before.genus);
  EXPECT_EQ(after.count(SurfaceIssueKind::DegenerateFace), before.count(SurfaceIssueKind::DegenerateFace));
  ASSERT_EQ(r.face_origin.size(), r.mesh.faces.size());
  const auto normals_in = face_normals(in);
  for (int f = 0; f < r.mesh.num_faces(); ++f) {
    const int o = r.face_origin[f];
    ASSERT_GE(o, 0);
    ASSERT_LT(o, in.num_faces());
    const auto& t = in.faces[o];
    for (int v : r.mesh.faces[f]) {
      EXPECT_LT(point_triangle_distance(r.mesh.vertices[v], in.vertices[t[0]], in.vertices[t[1]],
                                        in.vertices[t[2]]),
                1e-9);
    }
    // Orientation is kept.
    EXPECT_GT(face_normal(r.mesh, f).dot(normals_in[o]), 0.99);
  }
  // New vertices sit where their origin says.
  for (size_t i = 0; i < r.new_vertex_origin.size(); ++i) {
    EXPECT_NEAR((mesh_point_position(in, r.new_vertex_origin[i]) -
                 r.mesh.vertices[in.num_vertices() + i])
                    .norm(),
                0.0, 1e-12);
  }
}

std::vector<MeshPoint> points_of(const Isocurve& c) { return c.points; }

TEST(SplitMeshAlongPath, StraightCrossingUsesTheSimpleSplit) {
  const TriMesh m = test::square_grid(4);
  std::vector<double> y;
  for (const Vec3& p : m.vertices) y.push_back(p.y());
  const auto curves = extract_isocurve(m, y, 1.5);
  ASSERT_EQ(curves.size(), 1u);
  const auto path = points_of(curves[0]);
  ASSERT_EQ(path.size(), 9u);  // 5 vertical edges and 4 diagonals
  const SplitMeshResult r = split_mesh_along_path(m, path);
  check_split(m, r);
  EXPECT_EQ(r.mesh.num_vertices(), 25 + 9);
  // 7 interior edges split (2 new faces each), 2 boundary edges (1 each).
  EXPECT_EQ(r.mesh.num_faces(), 32 + 2 * 7 + 2);
  EXPECT_EQ(r.faces_split_constrained, 0);
  EXPECT_GT(r.faces_split_simple, 0);
  ASSERT_EQ(r.path.size(), 9u);
  for (int v : r.path) EXPECT_NEAR(r.mesh.vertices[v].y(), 1.5, 1e-15);
  EXPECT_EQ(r.point_vertices, r.path);
  // Carrying a linear field over is exact.
  std::vector<double> lin;
  for (const Vec3& p : m.vertices) lin.push_back(2.0 * p.x() - p.y() + 0.5);
  const auto carried = carry_vertex_scalar(m, r, lin);
  ASSERT_EQ(static_cast<int>(carried.size()), r.mesh.num_vertices());
  for (int v = 0; v < r.mesh.num_vertices(); ++v) {
    const Vec3& p = r.mesh.vertices[v];
    EXPECT_NEAR(carried[v], 2.0 * p.x() - p.y() + 0.5, 1e-12);
  }
  // Deterministic.
  const SplitMeshResult again = split_mesh_along_path(m, path);
  EXPECT_EQ(again.mesh.faces, r.mesh.faces);
  EXPECT_EQ(again.path, r.path);
}

TEST(SplitMeshAlongPath, PathThroughVerticesOnlyChangesNothing) {
  const TriMesh m = test::square_grid(4);
  std::vector<double> x;
  for (const Vec3& p : m.vertices) x.push_back(p.x());
  const auto curves = extract_isocurve(m, x, 2.0);  // along the edges x = 2
  ASSERT_EQ(curves.size(), 1u);
  const SplitMeshResult r = split_mesh_along_path(m, curves[0].points);
  EXPECT_EQ(r.mesh.faces, m.faces);
  EXPECT_EQ(r.path, (std::vector<int>{2, 7, 12, 17, 22}));
  EXPECT_EQ(r.faces_split_simple + r.faces_split_constrained, 0);
}

TEST(SplitMeshAlongPath, EveryIsocurveOfAFieldOnTriplePeak) {
  const TriMesh m = triple_peak(6.0);
  std::vector<double> f;
  for (const Vec3& p : m.vertices) f.push_back(p.z() + 0.3 * p.x() - 0.2 * p.y());
  int curves_split = 0;
  for (const auto& curves : extract_isocurves(m, f, {-10.0, 5.0, 20.0, 35.0})) {
    for (const Isocurve& c : curves) {
      auto path = c.points;
      if (c.closed) path.push_back(path.front());
      const SplitMeshResult r = split_mesh_along_path(m, path);
      check_split(m, r);
      // The path vertices carry the level exactly (linear interpolation).
      const auto carried = carry_vertex_scalar(m, r, f);
      for (int v : r.path) EXPECT_NEAR(carried[v], c.value, 1e-9);
      ++curves_split;
    }
  }
  EXPECT_GE(curves_split, 4);
}

TEST(SplitMeshAlongPath, ZigZagThroughOneFace) {
  // Face 0 = (0, 1, 4) = (0,0), (10,0), (10,10); zig-zag between its bottom
  // edge (0, 1) and its diagonal (0, 4).
  const TriMesh m = test::square_grid(2, 10.0);
  const std::vector<MeshPoint> path = {
      MeshPoint::on_edge(0, 1, 0.2), MeshPoint::on_edge(0, 4, 0.3),
      MeshPoint::on_edge(1, 0, 0.5), MeshPoint::on_edge(4, 0, 0.4),
      MeshPoint::on_edge(0, 1, 0.8)};
  const SplitMeshResult r = split_mesh_along_path(m, path);
  check_split(m, r);
  EXPECT_EQ(r.mesh.num_vertices(), 9 + 5);
  // Face 0 becomes an octagon (6 triangles), face 1 = (0, 4, 3) a pentagon (3).
  EXPECT_EQ(r.mesh.num_faces(), 8 + 5 + 2);
  EXPECT_GE(r.faces_split_constrained, 1);
  EXPECT_EQ(r.path, (std::vector<int>{9, 10, 11, 12, 13}));
  int from_face0 = 0;
  for (int o : r.face_origin) from_face0 += o == 0 ? 1 : 0;
  EXPECT_EQ(from_face0, 6);
  // No sliver: every triangle has a sensible area.
  for (double a : face_areas(r.mesh)) EXPECT_GT(a, 0.5);
}

TEST(SplitMeshAlongPath, PointsInsideFaces) {
  const TriMesh m = test::square_grid(4);  // vertex (i, j) = 5 j + i
  // Face 0 = (0, 1, 6), face 3 = (1, 7, 6).
  const std::vector<MeshPoint> path = {
      MeshPoint::at_vertex(0), MeshPoint::in_face(0, {0.2, 0.5, 0.3}),
      MeshPoint::on_edge(1, 6, 0.5), MeshPoint::in_face(3, {0.2, 0.3, 0.5}),
      MeshPoint::at_vertex(7)};
  const SplitMeshResult r = split_mesh_along_path(m, path);
  check_split(m, r);
  EXPECT_EQ(r.mesh.num_vertices(), 25 + 3);
  EXPECT_EQ(r.mesh.num_faces(), 32 + 3 + 3);
  ASSERT_EQ(r.path.size(), 5u);
  EXPECT_EQ(r.path.front(), 0);
  EXPECT_EQ(r.path.back(), 7);
  EXPECT_NEAR((r.mesh.vertices[r.path[1]] - Vec3(0.8, 0.3, 0)).norm(), 0.0, 1e-15);
  EXPECT_NEAR((r.mesh.vertices[r.path[3]] - Vec3(1.3, 0.8, 0)).norm(), 0.0, 1e-15);
  std::vector<double> lin;
  for (const Vec3& p : m.vertices) lin.push_back(p.x() * 3.0 + p.y());
  const auto carried = carry_vertex_scalar(m, r, lin);
  for (int v = 0; v < r.mesh.num_vertices(); ++v)
    EXPECT_NEAR(carried[v], 3.0 * r.mesh.vertices[v].x() + r.mesh.vertices[v].y(), 1e-12);
}

TEST(SplitMeshAlongPath, SnapsPointsNearVerticesAndMergesNearPoints) {
  const TriMesh m = test::square_grid(2);
  {  // Both points snap to vertices 0 and 4: nothing to split.
    const SplitMeshResult r = split_mesh_along_path(
        m, {MeshPoint::on_edge(1, 0, 1.0 - 1e-7), MeshPoint::on_edge(4, 5, 1e-6)});
    EXPECT_EQ(r.mesh.faces, m.faces);
    EXPECT_EQ(r.path, (std::vector<int>{0, 4}));
    EXPECT_TRUE(r.new_vertex_origin.empty());
  }
  {  // Two points 1e-6 apart on one edge become one vertex; a face point
     // with a tiny barycentric coordinate moves onto the edge.
    const SplitMeshResult r = split_mesh_along_path(
        m, {MeshPoint::on_edge(0, 1, 0.5), MeshPoint::on_edge(1, 0, 0.5 - 1e-6),
            MeshPoint::in_face(0, {0.5, 1e-7, 0.5 - 1e-7})});
    check_split(m, r);
    // The face point (0, 1, 4) = (0.5, 0.5) lies on the diagonal (0, 4).
    EXPECT_EQ(r.mesh.num_vertices(), 9 + 2);
    EXPECT_EQ(r.point_vertices[0], r.point_vertices[1]);
    EXPECT_EQ(r.path.size(), 2u);
    EXPECT_TRUE(r.new_vertex_origin[1].is_edge());
  }
  {  // With snap 0.3 rejected; with snap 0.2 a point at t = 0.15 becomes a vertex.
    SplitOptions o;
    o.snap = 0.3;
    EXPECT_THROW(split_mesh_along_path(m, {MeshPoint::at_vertex(0)}, o), InvalidInput);
    o.snap = 0.2;
    const SplitMeshResult r = split_mesh_along_path(m, {MeshPoint::on_edge(0, 1, 0.15)}, o);
    EXPECT_EQ(r.path, std::vector<int>{0});
  }
}

TEST(SplitMeshAlongPath, AlongAnEdgeThroughOtherPathPoints) {
  const TriMesh m = test::square_grid(2);
  // The path comes back along edge (0, 1) past a point it visited before:
  // the output path passes through that vertex.
  const std::vector<MeshPoint> path = {MeshPoint::on_edge(0, 1, 0.5), MeshPoint::at_vertex(4),
                                          MeshPoint::on_edge(1, 5, 0.5), MeshPoint::at_vertex(1),
                                          MeshPoint::at_vertex(0)};
  const SplitMeshResult r = split_mesh_along_path(m, path);
  check_split(m, r);
  const int a = r.point_vertices[0];
  EXPECT_EQ(r.path, (std::vector<int>{a, 4, r.point_vertices[2], 1, a, 0}));
}

TEST(SplitMeshAlongPath, ClosedIsocurveOnHemisphere) {
  const TriMesh m = hemisphere(30.0, 3.0);
  std::vector<double> z;
  for (const Vec3& p : m.vertices) z.push_back(p.z());
  const auto curves = extract_isocurve(m, z, 12.0);
  ASSERT_EQ(curves.size(), 1u);
  ASSERT_TRUE(curves[0].closed);
  auto path = curves[0].points;
  path.push_back(path.front());
  const SplitMeshResult r = split_mesh_along_path(m, path);
  check_split(m, r);
  EXPECT_EQ(r.path.front(), r.path.back());
  EXPECT_EQ(r.path.size(), path.size());
  for (int v : r.path) EXPECT_NEAR(r.mesh.vertices[v].z(), 12.0, 1e-9);
}

// Several paths at once (the pieces of a plane section): every piece becomes
// a chain of mesh edges, and the split is the one the pieces would give one
// after the other (same vertices, same area), with point names per path in
// the messages.
TEST(SplitMeshAlongPath, SeveralPathsAtOnce) {
  const TriMesh m = monkey_saddle(6.0);
  std::vector<double> z;
  for (const Vec3& p : m.vertices) z.push_back(p.z());
  const auto curves = extract_isocurve(m, z, 30.0);  // the three lobes' level set: several pieces
  ASSERT_GE(curves.size(), 2u);
  std::vector<std::vector<MeshPoint>> paths;
  size_t points = 0;
  for (const auto& c : curves) {
    paths.push_back(points_of(c));
    points += c.points.size();
  }
  const SplitMeshResult r = split_mesh_along_paths(m, paths);
  ASSERT_EQ(r.paths.size(), paths.size());
  EXPECT_EQ(r.path, r.paths[0]);
  EXPECT_EQ(r.point_vertices.size(), points);
  const auto edges = undirected_edges(r.mesh);
  for (const auto& path : r.paths) {
    ASSERT_GE(path.size(), 2u);
    for (size_t i = 1; i < path.size(); ++i) EXPECT_TRUE(edges.count(std::minmax(path[i - 1], path[i])));
    for (int v : path) EXPECT_NEAR(r.mesh.vertices[v].z(), 30.0, 1e-9);
  }
  for (const auto& path : r.paths) {
    SplitMeshResult one = r;
    one.path = path;
    check_split(m, one);
  }
  // Consecutive points of different paths are not joined: a second path far
  // from the first splits without complaint, while the same points as one
  // path are rejected.
  std::vector<MeshPoint> joined = paths[0];
  joined.insert(joined.end(), paths[1].begin(), paths[1].end());
  EXPECT_THROW(split_mesh_along_path(m, joined), InvalidInput);
  std::vector<std::vector<MeshPoint>> bad = {paths[0], {paths[1][0], paths[0][0]}};
  try {
    split_mesh_along_paths(m, bad);
    ADD_FAILURE() << "expected InvalidInput";
  } catch (const InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find("of path 1"), std::string::npos) << e.what();
  }
}

TEST(SplitMeshAlongPath, RejectsBadPaths) {
  const TriMesh m = test::square_grid(2, 10.0);
  // Not on a common face.
  EXPECT_THROW(split_mesh_along_path(m, {MeshPoint::at_vertex(0), MeshPoint::at_vertex(8)}),
               InvalidInput);
  // Not an edge.
  EXPECT_THROW(split_mesh_along_path(m, {MeshPoint::on_edge(0, 8, 0.5)}), InvalidInput);
  EXPECT_THROW(split_mesh_along_path(m, {MeshPoint::at_vertex(9)}), InvalidInput);
  EXPECT_THROW(split_mesh_along_path(m, {MeshPoint::on_edge(0, 1, 1.5)}), InvalidInput);
  EXPECT_THROW(split_mesh_along_path(m, {MeshPoint::in_face(8, {1, 0, 0})}), InvalidInput);
  EXPECT_THROW(split_mesh_along_path(m, {MeshPoint::in_face(0, {0.5, 0.5, 0.5})}), InvalidInput);
  EXPECT_THROW(split_mesh_along_path(m, {MeshPoint::in_face(0, {-0.5, 1.0, 0.5})}), InvalidInput);
  // Self-crossing inside face 0 = (0,0), (10,0), (10,10).
  const std::vector<MeshPoint> crossing = {
      MeshPoint::on_edge(0, 1, 0.2), MeshPoint::on_edge(1, 4, 0.5),
      MeshPoint::on_edge(0, 4, 0.4), MeshPoint::on_edge(0, 1, 0.8)};
  EXPECT_THROW(split_mesh_along_path(m, crossing), InvalidInput);
  // Carrying a scalar of the wrong size.
  const SplitMeshResult r = split_mesh_along_path(m, {MeshPoint::on_edge(0, 1, 0.5)});
  EXPECT_THROW(carry_vertex_scalar(m, r, {1.0, 2.0}), InvalidInput);
}

}  // namespace
}  // namespace knitforge
