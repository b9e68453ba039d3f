#include "knitforge/geometry/isotropic_remesh.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <gtest/gtest.h>

#include "geometry/test_meshes.h"
#include "knitforge/geometry/halfedges.h"
#include "knitforge/geometry/mesh_measures.h"
#include "knitforge/geometry/surface_checks.h"
#include "knitforge/util/errors.h"

namespace knitforge {
namespace {

double fraction_in_range(const TriMesh& m, double l) {
  const auto lengths = edge_lengths(m);
  const auto n = std::count_if(lengths.begin(), lengths.end(),
                               [&](double x) { return x >= 0.6 * l && x <= 1.5 * l; });
  return static_cast<double>(n) / lengths.size();
}

bool has_vertex(const TriMesh& m, const Vec3& p) {
  return std::any_of(m.vertices.begin(), m.vertices.end(), [&](const Vec3& q) { return q == p; });
}

TEST(IsotropicRemesh, CoarseSquareWithDefaultProjections) {
  // Two triangles; the corners are detected (90° turns) and kept.
  TriMesh m = test::square_grid(1, 40.0);
  RemeshOptions o;
  o.target_edge_length = 3.0;
  const TriMesh out = isotropic_remesh(m, o);
  const SurfaceReport r = validate_surface(out);
  EXPECT_TRUE(r.is_disk) << r.summary();
  EXPECT_GT(out.num_faces(), 300);
  EXPECT_GE(fraction_in_range(out, 3.0), 0.95);
  EXPECT_NEAR(total_area(out), 1600.0, 1e-6);
  for (const Vec3& c : m.vertices) EXPECT_TRUE(has_vertex(out, c));
  for (int f = 0; f < out.num_faces(); ++f) EXPECT_GT(face_normal(out, f).z(), 0.99);
  const Halfedges he = build_halfedges(out.num_vertices(), out.faces);
  for (int v = 0; v < out.num_vertices(); ++v) {
    const Vec3& p = out.vertices[v];
    EXPECT_EQ(p.z(), 0.0);
    if (he.is_boundary_vertex(v)) {
      EXPECT_TRUE(std::abs(p.x()) < 1e-9 || std::abs(p.x() - 40.0) < 1e-9 || std::abs(p.y()) < 1e-9 ||
                  std::abs(p.y() - 40.0) < 1e-9)
          << v;
    }
  }
}

TEST(IsotropicRemesh, UserProjectionOntoASphericalCap) {
  // A grid lifted onto the sphere of radius 50; the patch is the part above
  // the square |x|, |y| <= 30, its boundary lies in the planes |x| = 30, |y| = 30.
  const double R = 50.0;
  TriMesh m = test::square_grid(6, 10.0);
  for (Vec3& p : m.vertices) {
    p = Vec3(p.x() - 30.0, p.y() - 30.0, 0.0);
    p.z() = std::sqrt(R * R - p.x() * p.x() - p.y() * p.y());
  }
  RemeshOptions o;
  o.target_edge_length = 2.5;
  o.iterations = 6;
  o.project = [R](const Vec3& p) { return Vec3(R * p.normalized()); };
  // Boundary: the sphere intersected with the four planes |x| = 30, |y| = 30.
  o.project_boundary = [R](const Vec3& p) {
    Vec3 q = p;
    const double dx = 30.0 - std::abs(q.x()), dy = 30.0 - std::abs(q.y());
    if (dx < dy) {
      q.x() = std::copysign(30.0, q.x());
    } else {
      q.y() = std::copysign(30.0, q.y());
    }
    q.z() = std::sqrt(R * R - q.x() * q.x() - q.y() * q.y());
    return q;
  };
  const TriMesh out = isotropic_remesh(m, o);
  EXPECT_TRUE(validate_surface(out).is_disk);
  EXPECT_GE(fraction_in_range(out, 2.5), 0.95);
  for (const Vec3& p : out.vertices) EXPECT_NEAR(p.norm(), R, 1e-9);
  const Halfedges he = build_halfedges(out.num_vertices(), out.faces);
  for (int v = 0; v < out.num_vertices(); ++v) {
    if (!he.is_boundary_vertex(v)) continue;
    const Vec3& p = out.vertices[v];
    EXPECT_NEAR(std::max(std::abs(p.x()), std::abs(p.y())), 30.0, 1e-9);
  }
  for (int f = 0; f < out.num_faces(); ++f) EXPECT_GT(face_normal(out, f).z(), 0.0);
}

TEST(IsotropicRemesh, KeepsTopologyOfAnnulusTorusAndClosedSurface) {
  for (const TriMesh& m : {test::ring_grid(3, 24, false), test::ring_grid(8, 24, true)}) {
    const SurfaceReport before = validate_surface(m);
    RemeshOptions o;
    o.target_edge_length = 0.4;
    o.iterations = 5;
    const TriMesh out = isotropic_remesh(m, o);
    const SurfaceReport after = validate_surface(out);
    EXPECT_TRUE(after.ok()) << after.summary();
    EXPECT_EQ(after.num_components, before.num_components);
    EXPECT_EQ(after.num_boundary_loops, before.num_boundary_loops);
    EXPECT_EQ(after.genus, before.genus);
    EXPECT_GT(out.num_faces(), m.num_faces());
  }
}

TEST(IsotropicRemesh, FixedVerticesStayAndCoarseningWorks) {
  TriMesh m = test::square_grid(20, 1.0);  // 20 x 20 mm, edges 1 mm
  RemeshOptions o;
  o.target_edge_length = 4.0;
  o.fixed_vertices = {220};  // the centre (10, 10)
  const TriMesh out = isotropic_remesh(m, o);
  EXPECT_TRUE(validate_surface(out).is_disk);
  EXPECT_LT(out.num_faces(), m.num_faces() / 4);
  EXPECT_TRUE(has_vertex(out, Vec3(10.0, 10.0, 0.0)));
  EXPECT_GE(fraction_in_range(out, 4.0), 0.9);
  EXPECT_NEAR(total_area(out), 400.0, 1e-6);
}

TEST(IsotropicRemesh, DefaultProjectionStaysOnTheInputSurface) {
  // A bent strip (a quarter cylinder as a coarse polyhedron): every output
  // vertex must lie on the input triangles.
  TriMesh m = test::square_grid(4, 10.0);
  for (Vec3& p : m.vertices) {
    const double a = p.x() / 40.0 * 1.5;
    p = Vec3(30.0 * std::sin(a), p.y(), 30.0 * std::cos(a));
  }
  RemeshOptions o;
  o.target_edge_length = 3.0;
  const TriMesh out = isotropic_remesh(m, o);
  EXPECT_TRUE(validate_surface(out).is_disk);
  double worst = 0.0;
  for (const Vec3& p : out.vertices) {
    double d = std::numeric_limits<double>::infinity();
    for (const auto& t : m.faces) {
      d = std::min(d, point_triangle_distance(p, m.vertices[t[0]], m.vertices[t[1]], m.vertices[t[2]]));
    }
    worst = std::max(worst, d);
  }
  EXPECT_LT(worst, 1e-9);
}

TEST(IsotropicRemesh, IsDeterministic) {
  RemeshOptions o;
  o.target_edge_length = 2.0;
  const TriMesh m = test::ring_grid(4, 16, false);
  const TriMesh a = isotropic_remesh(m, o);
  const TriMesh b = isotropic_remesh(m, o);
  EXPECT_EQ(a.faces, b.faces);
  ASSERT_EQ(a.vertices.size(), b.vertices.size());
  for (size_t i = 0; i < a.vertices.size(); ++i) EXPECT_EQ(a.vertices[i], b.vertices[i]);
}

TEST(IsotropicRemesh, ZeroIterationsReturnsTheInput) {
  const TriMesh m = test::square_grid(3);
  RemeshOptions o;
  o.target_edge_length = 1.0;
  o.iterations = 0;
  const TriMesh out = isotropic_remesh(m, o);
  EXPECT_EQ(out.faces, m.faces);
  EXPECT_EQ(out.vertices, m.vertices);
}

TEST(IsotropicRemesh, BadInputThrows) {
  const TriMesh m = test::square_grid(2);
  RemeshOptions o;
  EXPECT_THROW(isotropic_remesh(m, o), InvalidInput);  // no target length
  o.target_edge_length = std::nan("");
  EXPECT_THROW(isotropic_remesh(m, o), InvalidInput);
  o.target_edge_length = 0.5;
  o.iterations = -1;
  EXPECT_THROW(isotropic_remesh(m, o), InvalidInput);
  o.iterations = 2;
  o.fixed_vertices = {9};
  EXPECT_THROW(isotropic_remesh(m, o), InvalidInput);
  o.fixed_vertices.clear();
  TriMesh flipped = m;
  std::swap(flipped.faces[0][1], flipped.faces[0][2]);
  EXPECT_THROW(isotropic_remesh(flipped, o), TopologyError);
  o.project = [](const Vec3&) { return Vec3(std::nan(""), 0.0, 0.0); };
  EXPECT_THROW(isotropic_remesh(m, o), InvalidInput);
}

}  // namespace
}  // namespace knitforge
