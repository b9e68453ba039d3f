#include "knitforge/geometry/cut_mesh_along_path.h"

#include <cmath>
#include <numbers>

#include <gtest/gtest.h>

#include "geometry/test_meshes.h"
#include "knitforge/geometry/halfedges.h"
#include "knitforge/geometry/isocurves.h"
#include "knitforge/geometry/mesh_measures.h"
#include "knitforge/geometry/shapes.h"
#include "knitforge/geometry/split_mesh_along_path.h"
#include "knitforge/geometry/surface_checks.h"
#include "knitforge/util/errors.h"

namespace knitforge {
namespace {

double boundary_length(const TriMesh& m) {
  const Halfedges h = build_halfedges(m.num_vertices(), m.faces);
  double len = 0.0;
  for (const auto& loop : h.boundary_loops())
    for (size_t i = 0; i < loop.size(); ++i)
      len += (m.vertices[loop[(i + 1) % loop.size()]] - m.vertices[loop[i]]).norm();
  return len;
}

double path_length(const TriMesh& m, const std::vector<int>& path) {
  double len = 0.0;
  for (size_t i = 1; i < path.size(); ++i) len += (m.vertices[path[i]] - m.vertices[path[i - 1]]).norm();
  return len;
}

// The faces of one component as a mesh of its own (vertices compacted).
TriMesh component(const CutMeshResult& r, int c) {
  TriMesh out;
  std::vector<int> map(r.mesh.num_vertices(), -1);
  for (int f = 0; f < r.mesh.num_faces(); ++f) {
    if (r.face_component[f] != c) continue;
    std::array<int, 3> t{};
    for (int k = 0; k < 3; ++k) {
      int& v = map[r.mesh.faces[f][k]];
      if (v < 0) {
        v = out.num_vertices();
        out.vertices.push_back(r.mesh.vertices[r.mesh.faces[f][k]]);
      }
      t[k] = v;
    }
    out.faces.push_back(t);
  }
  return out;
}

void check_cut_basics(const TriMesh& in, const CutMeshResult& r) {
  ASSERT_EQ(static_cast<int>(r.vertex_origin.size()), r.mesh.num_vertices());
  for (int v = 0; v < r.mesh.num_vertices(); ++v) {
    EXPECT_EQ(r.mesh.vertices[v], in.vertices[r.vertex_origin[v]]);
    if (v < in.num_vertices()) {
      EXPECT_EQ(r.vertex_origin[v], v);
    }
  }
  ASSERT_EQ(r.mesh.num_faces(), in.num_faces());
  for (int f = 0; f < in.num_faces(); ++f)
    for (int k = 0; k < 3; ++k) EXPECT_EQ(r.vertex_origin[r.mesh.faces[f][k]], in.faces[f][k]);
  EXPECT_NEAR(total_area(r.mesh), total_area(in), 1e-9 * total_area(in));
  EXPECT_TRUE(validate_surface(r.mesh).ok());
}

// A flat disk split along the isocurve y = 0.3 (boundary to boundary,
// walking towards -x).
struct SplitDisk {
  TriMesh disk;
  SplitMeshResult split;
};
SplitDisk split_disk(bool half) {
  SplitDisk s{flat_disk(50.0, 5.0), {}};
  std::vector<double> y;
  for (const Vec3& p : s.disk.vertices) y.push_back(p.y());
  const auto curves = extract_isocurve(s.disk, y, 0.3);
  EXPECT_EQ(curves.size(), 1u);
  std::vector<MeshPoint> path;
  for (int i = 0; i < curves[0].num_points(); ++i) {
    if (half && curves[0].positions[i].x() < 0.0) break;  // from the boundary to the centre
    path.push_back(curves[0].points[i]);
  }
  s.split = split_mesh_along_path(s.disk, path);
  return s;
}

TEST(CutMeshAlongPath, InteriorToBoundaryKeepsADisk) {
  const SplitDisk s = split_disk(true);
  const TriMesh& m = s.split.mesh;
  const auto& path = s.split.path;
  ASSERT_GE(path.size(), 5u);
  const Halfedges h = build_halfedges(m.num_vertices(), m.faces);
  ASSERT_TRUE(h.is_boundary_vertex(path.front()));
  ASSERT_FALSE(h.is_boundary_vertex(path.back()));
  const CutMeshResult r = cut_mesh_along_path(m, path);
  check_cut_basics(m, r);
  EXPECT_EQ(r.num_components, 1);
  EXPECT_EQ(r.num_cut_edges, static_cast<int>(path.size()) - 1);
  const SurfaceReport rep = validate_surface(r.mesh);
  EXPECT_TRUE(rep.is_disk) << rep.summary();
  // Every path vertex but the interior end is duplicated once.
  EXPECT_EQ(r.mesh.num_vertices(), m.num_vertices() + static_cast<int>(path.size()) - 1);
  EXPECT_NEAR(boundary_length(r.mesh), boundary_length(m) + 2.0 * path_length(m, path), 1e-9);
  // The two sides differ except at the slit's interior end.
  for (size_t i = 0; i + 1 < path.size(); ++i) {
    EXPECT_NE(r.left[i], r.right[i]) << i;
    EXPECT_EQ(r.vertex_origin[r.left[i]], path[i]);
    EXPECT_EQ(r.vertex_origin[r.right[i]], path[i]);
  }
  EXPECT_EQ(r.left.back(), r.right.back());
}

TEST(CutMeshAlongPath, BoundaryToBoundaryGivesTwoDisks) {
  const SplitDisk s = split_disk(false);
  const TriMesh& m = s.split.mesh;
  const CutMeshResult r = cut_mesh_along_path(m, s.split.path);
  check_cut_basics(m, r);
  ASSERT_EQ(r.num_components, 2);
  double area = 0.0;
  for (int c = 0; c < 2; ++c) {
    const TriMesh piece = component(r, c);
    EXPECT_TRUE(validate_surface(piece).is_disk);
    area += total_area(piece);
  }
  EXPECT_NEAR(area, total_area(s.disk), 1e-9 * area);
  // Both path ends are on the boundary: every path vertex is duplicated.
  EXPECT_EQ(r.mesh.num_vertices(), m.num_vertices() + static_cast<int>(s.split.path.size()));
  // The smaller piece is the circular segment above y = 0.3 (up to the
  // polygonal boundary).
  const double small = std::min(total_area(component(r, 0)), total_area(component(r, 1)));
  const double R = 50.0, d = 0.3;
  const double segment = R * R * std::acos(d / R) - d * std::sqrt(R * R - d * d);
  EXPECT_NEAR(small, segment, 0.01 * segment);
}

TEST(CutMeshAlongPath, ClosedLoopOnHemisphereSeparatesCapAndBand) {
  const TriMesh m0 = hemisphere(30.0, 3.0);
  std::vector<double> z;
  for (const Vec3& p : m0.vertices) z.push_back(p.z());
  const auto curves = extract_isocurve(m0, z, 12.0);
  ASSERT_EQ(curves.size(), 1u);
  auto pts = curves[0].points;
  pts.push_back(pts.front());
  const SplitMeshResult s = split_mesh_along_path(m0, pts);
  const CutMeshResult r = cut_mesh_along_path(s.mesh, s.path);
  check_cut_basics(s.mesh, r);
  ASSERT_EQ(r.num_components, 2);
  int disks = 0, annuli = 0;
  for (int c = 0; c < 2; ++c) {
    const SurfaceReport rep = validate_surface(component(r, c));
    disks += rep.is_disk ? 1 : 0;
    annuli += rep.num_boundary_loops == 2 && rep.genus == 0 ? 1 : 0;
  }
  EXPECT_EQ(disks, 1);
  EXPECT_EQ(annuli, 1);
  // A closed loop of k distinct interior vertices gains k vertices.
  EXPECT_EQ(r.mesh.num_vertices(), s.mesh.num_vertices() + static_cast<int>(s.path.size()) - 1);
}

TEST(CutMeshAlongPath, InteriorSlitOpensAHole) {
  const TriMesh m = test::square_grid(4);  // vertex (i, j) = 5 j + i
  const CutMeshResult r = cut_mesh_along_path(m, {6, 7, 8});
  check_cut_basics(m, r);
  EXPECT_EQ(r.num_components, 1);
  EXPECT_EQ(r.mesh.num_vertices(), 26);  // only the middle vertex 7 doubles
  const SurfaceReport rep = validate_surface(r.mesh);
  EXPECT_EQ(rep.num_boundary_loops, 2);
  EXPECT_NEAR(boundary_length(r.mesh), 16.0 + 4.0, 1e-12);
  EXPECT_EQ(r.left[0], 6);
  EXPECT_EQ(r.right[0], 6);
  EXPECT_NE(r.left[1], r.right[1]);
}

TEST(CutMeshAlongPath, PathAlongTheBoundaryCutsNothing) {
  const TriMesh m = test::square_grid(2);
  const CutMeshResult r = cut_mesh_along_path(m, {0, 1, 2});
  EXPECT_EQ(r.num_cut_edges, 0);
  EXPECT_EQ(r.mesh.faces, m.faces);
  EXPECT_EQ(r.mesh.num_vertices(), m.num_vertices());
  EXPECT_EQ(r.right[0], -1);  // no face to the right of the boundary edge 0 -> 1
}

// Two radial paths of an annulus cut at once: the annulus falls into two
// pieces (each a disk), as cutting one after the other would; left/right
// list both paths' sides.
TEST(CutMeshAlongPath, SeveralPathsAtOnce) {
  const TriMesh ring = test::ring_grid(4, 24, false);
  const int sectors = 24;
  auto radial = [&](int s) {
    std::vector<int> p;
    for (int r = 0; r <= 4; ++r) p.push_back(r * sectors + s);
    return p;
  };
  const CutMeshResult both = cut_mesh_along_paths(ring, {radial(0), radial(12)});
  check_cut_basics(ring, both);
  EXPECT_EQ(both.num_components, 2);
  EXPECT_EQ(both.num_cut_edges, 8);  // every radial edge is interior
  ASSERT_EQ(both.left.size(), 10u);
  for (int c = 0; c < 2; ++c) EXPECT_TRUE(validate_surface(component(both, c)).is_disk);
  const CutMeshResult first = cut_mesh_along_path(ring, radial(0));
  EXPECT_EQ(first.num_components, 1);
  EXPECT_TRUE(validate_surface(first.mesh).is_disk);
  for (int i = 0; i < 5; ++i) {
    EXPECT_NE(both.left[i], both.right[i]);
    EXPECT_EQ(both.mesh.vertices[both.left[i]], both.mesh.vertices[both.right[i]]);
  }
  EXPECT_THROW(cut_mesh_along_paths(ring, {}), InvalidInput);
  EXPECT_THROW(cut_mesh_along_paths(ring, {radial(0), {0}}), InvalidInput);
}

TEST(CutMeshAlongPath, RejectsBadPaths) {
  const TriMesh m = test::square_grid(2);
  EXPECT_THROW(cut_mesh_along_path(m, {4}), InvalidInput);
  EXPECT_THROW(cut_mesh_along_path(m, {0, 8}), InvalidInput);  // not an edge
  EXPECT_THROW(cut_mesh_along_path(m, {0, 0, 1}), InvalidInput);
  EXPECT_THROW(cut_mesh_along_path(m, {0, 99}), InvalidInput);
}

}  // namespace
}  // namespace knitforge
