// Cutting a mesh along the zero level of a field (geometry/clip_mesh_by_field.h).
#include "knitforge/geometry/clip_mesh_by_field.h"

#include <gtest/gtest.h>

#include <cmath>

#include "knitforge/geometry/mesh_measures.h"
#include "knitforge/geometry/shapes.h"
#include "knitforge/geometry/surface_checks.h"
#include "knitforge/util/errors.h"

namespace knitforge {
namespace {

TEST(ClipMeshByField, ALinearFieldCutsAFlatMeshExactlyOnItsLevel) {
  const TriMesh m = rectangle(150.0, 100.0, 7.0);
  std::vector<double> f;
  // The cut line x = 23.4 + 0.3 y is oblique: it crosses the triangles.
  for (const Vec3& v : m.vertices) f.push_back(v.x() - 23.4 - 0.3 * v.y());
  const ClippedMesh c = clip_mesh_by_field(m, f);
  const SurfaceReport rep = validate_surface(c.mesh);
  EXPECT_TRUE(rep.is_disk) << rep.summary();
  // The kept part is the trapezoid right of the line: width at y is 75 - 23.4 - 0.3 y.
  EXPECT_NEAR(total_area(c.mesh), (75.0 - 23.4) * 100.0, 1e-6);
  // Every vertex is on the kept side; the new ones and the snapped ones lie on the line.
  int on_line = 0;
  for (size_t i = 0; i < c.mesh.vertices.size(); ++i) {
    const Vec3& p = c.mesh.vertices[i];
    const double g = p.x() - 23.4 - 0.3 * p.y();
    EXPECT_GE(g, -1e-9);
    if (std::abs(g) < 1e-9) ++on_line;
    if (c.vertex_origin[i] < 0) {
      EXPECT_NEAR(g, 0.0, 1e-9);
    }
  }
  EXPECT_GT(on_line, 10);
  EXPECT_GT(c.snapped_vertices, 0);
  // No slivers: the crossings keep a fifth of an edge from the vertices.
  EXPECT_GT(edge_length_stats(c.mesh).min, 0.15 * edge_length_stats(m).min);
  // Without snapping the vertices stay where they were.
  ClipFieldOptions o;
  o.snap_fraction = 0.0;
  const ClippedMesh n = clip_mesh_by_field(m, f, o);
  EXPECT_EQ(n.snapped_vertices, 0);
  EXPECT_NEAR(total_area(n.mesh), (75.0 - 23.4) * 100.0, 1e-6);
  for (size_t i = 0; i < n.mesh.vertices.size(); ++i) {
    if (n.vertex_origin[i] >= 0) {
      EXPECT_EQ(n.mesh.vertices[i], m.vertices[static_cast<size_t>(n.vertex_origin[i])]);
    }
  }
}

TEST(ClipMeshByField, KeepsOrientationAndBothSidesTileTheMesh) {
  const TriMesh m = hemisphere(40.0, 5.0);
  std::vector<double> f, g;
  for (const Vec3& v : m.vertices) {
    f.push_back(v.z() - 17.0 + 0.2 * v.x());
    g.push_back(-f.back());
  }
  ClipFieldOptions o;
  o.snap_fraction = 0.0;  // both sides cut at the same points
  const ClippedMesh a = clip_mesh_by_field(m, f, o), b = clip_mesh_by_field(m, g, o);
  EXPECT_TRUE(validate_surface(a.mesh).ok());
  EXPECT_TRUE(validate_surface(b.mesh).ok());
  EXPECT_NEAR(total_area(a.mesh) + total_area(b.mesh), total_area(m), 1e-6 * total_area(m));
  // The normals still point outward (away from the sphere's centre).
  for (int k = 0; k < a.mesh.num_faces(); ++k) {
    const auto& t = a.mesh.faces[static_cast<size_t>(k)];
    const Vec3 c = (a.mesh.vertices[static_cast<size_t>(t[0])] + a.mesh.vertices[static_cast<size_t>(t[1])] +
                    a.mesh.vertices[static_cast<size_t>(t[2])]) / 3.0;
    const Vec3 n = triangle_area_vector(a.mesh.vertices[static_cast<size_t>(t[0])],
                                        a.mesh.vertices[static_cast<size_t>(t[1])],
                                        a.mesh.vertices[static_cast<size_t>(t[2])]);
    if (n.norm() > 1e-9) {
      EXPECT_GT(n.dot(c), 0.0) << "face " << k;
    }
  }
}

TEST(ClipMeshByField, AllPositiveKeepsEverythingAllNegativeNothing) {
  const TriMesh m = rectangle(20.0, 10.0, 2.0);
  const ClippedMesh all = clip_mesh_by_field(m, std::vector<double>(m.vertices.size(), 1.0));
  EXPECT_EQ(all.mesh.num_faces(), m.num_faces());
  EXPECT_EQ(all.mesh.num_vertices(), m.num_vertices());
  const ClippedMesh none = clip_mesh_by_field(m, std::vector<double>(m.vertices.size(), -1.0));
  EXPECT_EQ(none.mesh.num_faces(), 0);
  EXPECT_EQ(none.mesh.num_vertices(), 0);
}

TEST(ClipMeshByField, RejectsBadInput) {
  const TriMesh m = rectangle(20.0, 10.0, 2.0);
  EXPECT_THROW(clip_mesh_by_field(m, {1.0, 2.0}), InvalidInput);
  std::vector<double> f(m.vertices.size(), 1.0);
  f[3] = std::nan("");
  EXPECT_THROW(clip_mesh_by_field(m, f), InvalidInput);
  f[3] = 1.0;
  ClipFieldOptions o;
  o.snap_fraction = 0.5;
  EXPECT_THROW(clip_mesh_by_field(m, f, o), InvalidInput);
}

}  // namespace
}  // namespace knitforge
