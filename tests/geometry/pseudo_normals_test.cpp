// Angle-weighted pseudo-normals and the inside test they give
// (geometry/pseudo_normals.h).
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "geometry/test_meshes.h"
#include "knitforge/geometry/mesh_measures.h"
#include "knitforge/geometry/pseudo_normals.h"
#include "knitforge/util/errors.h"

namespace knitforge {
namespace {

// Outside of the mesh by the pseudo-normal at the closest point (brute force).
bool outside_by_pseudo_normal(const TriMesh& m, const PseudoNormals& n, const Vec3& p) {
  double best = INFINITY;
  int face = -1;
  TrianglePoint where;
  for (int f = 0; f < m.num_faces(); ++f) {
    const auto& t = m.faces[static_cast<size_t>(f)];
    const TrianglePoint q = closest_triangle_point(p, m.vertices[t[0]], m.vertices[t[1]], m.vertices[t[2]]);
    const double d = (q.point - p).squaredNorm();
    if (d < best) best = d, face = f, where = q;
  }
  return (p - where.point).dot(n.at(m, face, where)) > 0.0;
}

TEST(PseudoNormals, TellInsideFromOutsideOfAClosedMeshEverywhere) {
  // A sphere of 8 x 6 facets, its top pulled down into a dimple: concave
  // edges and a saddle-like vertex there, where a face normal alone misjudges
  // points beside edges and vertices.
  TriMesh m = test::uv_sphere_mesh(10.0, 8, 6);
  m.vertices[0] = {0, 0, 2.0};  // the north pole pushed below its ring
  ASSERT_TRUE(is_closed_mesh(m));
  const PseudoNormals n = pseudo_normals(m);
  // The exact inside: a ray cast along a generic direction crosses the
  // surface an odd number of times.
  auto inside_by_rays = [&](const Vec3& p) {
    const Vec3 dir = Vec3(0.3127, -0.4419, 0.8408).normalized();
    int hits = 0;
    for (const auto& t : m.faces) {
      const Vec3 a = m.vertices[t[0]], b = m.vertices[t[1]], c = m.vertices[t[2]];
      const Vec3 e1 = b - a, e2 = c - a, h = dir.cross(e2);
      const double det = e1.dot(h);
      if (std::abs(det) < 1e-14) continue;
      const Vec3 s = p - a;
      const double u = s.dot(h) / det;
      const Vec3 q = s.cross(e1);
      const double v = dir.dot(q) / det, w = e2.dot(q) / det;
      if (u >= 0 && v >= 0 && u + v <= 1 && w > 0) ++hits;
    }
    return hits % 2 == 1;
  };
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-13.0, 13.0);
  int checked = 0, near_features = 0;
  for (int k = 0; k < 4000; ++k) {
    const Vec3 p(u(rng), u(rng), u(rng));
    EXPECT_EQ(outside_by_pseudo_normal(m, n, p), !inside_by_rays(p)) << "point " << p.transpose();
    ++checked;
  }
  // Points just off the dimple's vertex and its edges, both sides.
  for (int j = 0; j < 8; ++j) {
    const Vec3 ring = m.vertices[static_cast<size_t>(1 + j)];
    for (const double t : {0.0, 0.25, 0.5}) {
      const Vec3 on = (1 - t) * m.vertices[0] + t * ring;
      for (const double dz : {-0.05, 0.05}) {
        const Vec3 p = on + Vec3(0.01, -0.02, dz);
        EXPECT_EQ(outside_by_pseudo_normal(m, n, p), !inside_by_rays(p)) << "near the dimple " << p.transpose();
        ++near_features;
      }
    }
  }
  EXPECT_EQ(checked + near_features, 4048);
}

TEST(PseudoNormals, ClosedMeshesAreThoseWithTwoFacesAtEveryEdge) {
  EXPECT_TRUE(is_closed_mesh(test::tetrahedron()));
  EXPECT_TRUE(is_closed_mesh(test::uv_sphere_mesh(5.0, 6, 4)));
  TriMesh open = test::tetrahedron();
  open.faces.pop_back();
  EXPECT_FALSE(is_closed_mesh(open));
  TriMesh three = test::tetrahedron();
  three.faces.push_back(three.faces.front());  // an edge of three faces
  EXPECT_FALSE(is_closed_mesh(three));
  EXPECT_FALSE(is_closed_mesh(TriMesh{}));
  // The sphere helper is outward: every face normal points away from the centre.
  const TriMesh s = test::uv_sphere_mesh(5.0, 6, 4);
  const PseudoNormals n = pseudo_normals(s);
  for (size_t f = 0; f < s.faces.size(); ++f) {
    const Vec3 c = (s.vertices[s.faces[f][0]] + s.vertices[s.faces[f][1]] + s.vertices[s.faces[f][2]]) / 3.0;
    EXPECT_GT(n.face[f].dot(c), 0.0) << "face " << f;
  }
  // At a vertex of a regular tetrahedron the pseudo-normal points away from its centre.
  const TriMesh t = test::tetrahedron();
  const PseudoNormals tn = pseudo_normals(t);
  for (size_t v = 0; v < 4; ++v) EXPECT_GT(tn.vertex[v].normalized().dot(t.vertices[v].normalized()), 1 - 1e-12);
  TriMesh bad = t;
  bad.faces[0][1] = 9;
  EXPECT_THROW(pseudo_normals(bad), InvalidInput);
}

}  // namespace
}  // namespace knitforge
