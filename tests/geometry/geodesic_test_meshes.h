#pragma once
// Meshes with known geodesic distances, for the geodesic tests.

#include <cmath>

#include "knitforge/geometry/tri_mesh.h"

namespace knitforge::test {

// An L-shaped grid of unit squares (split by diagonals) covering
// [0, n]² minus the open top-right quarter (n/2, n] x (n/2, n]; n even.
inline TriMesh l_shape(int n) {
  TriMesh m;
  const int h = n / 2;
  auto inside = [&](int i, int j) { return !(i > h && j > h); };
  std::vector<int> id((n + 1) * (n + 1), -1);
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i)
      if (inside(i, j)) {
        id[j * (n + 1) + i] = m.num_vertices();
        m.vertices.emplace_back(i, j, 0.0);
      }
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      if (i >= h && j >= h) continue;  // the removed quarter's squares
      const int a = id[j * (n + 1) + i], b = id[j * (n + 1) + i + 1];
      const int c = id[(j + 1) * (n + 1) + i + 1], d = id[(j + 1) * (n + 1) + i];
      m.faces.push_back({a, b, c});
      m.faces.push_back({a, c, d});
    }
  return m;
}

// Index of vertex (i, j) of developable_cylinder().
inline int developable_cylinder_vertex(int na, int i, int j) { return j * (na + 1) + i; }

// A cylinder patch x² + y² = r² meshed with vertices on generator lines at
// angles (i - na/2) angle/na, i = 0..na (na even), and heights j height/nz:
// every quad between two generators is planar, so the polyhedron unfolds
// exactly onto the rectangle [-na/2, na/2] chord x [0, height] with
// chord = 2 r sin(angle / (2 na)). Normals point outward.
inline TriMesh developable_cylinder(double r, double angle, double height, int na, int nz) {
  TriMesh m;
  const double dth = angle / na;
  for (int j = 0; j <= nz; ++j)
    for (int i = 0; i <= na; ++i) {
      const double th = (i - na / 2) * dth;
      m.vertices.emplace_back(r * std::cos(th), r * std::sin(th), height * j / nz);
    }
  for (int j = 0; j < nz; ++j)
    for (int i = 0; i < na; ++i) {
      const int a = developable_cylinder_vertex(na, i, j), b = developable_cylinder_vertex(na, i + 1, j);
      const int c = developable_cylinder_vertex(na, i + 1, j + 1), d = developable_cylinder_vertex(na, i, j + 1);
      if ((i + j) % 2 == 0) {
        m.faces.push_back({a, b, c});
        m.faces.push_back({a, c, d});
      } else {
        m.faces.push_back({a, b, d});
        m.faces.push_back({b, c, d});
      }
    }
  return m;
}

}  // namespace knitforge::test
