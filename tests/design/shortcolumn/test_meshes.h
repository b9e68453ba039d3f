#pragma once
// Planar test meshes of the short-column tests.
#include <cmath>
#include <vector>

#include "knitforge/geometry/tri_mesh.h"

namespace knitforge::test {

/// A planar polar grid: r in [r0, r1], theta in [t0, t1], nr x nt cells,
/// each split into two triangles (counter-clockwise seen from +z), the
/// diagonals alternating.
inline TriMesh polar_grid(double r0, double r1, double t0, double t1, int nr, int nt) {
  TriMesh m;
  for (int j = 0; j <= nt; ++j) {
    for (int i = 0; i <= nr; ++i) {
      const double r = r0 + (r1 - r0) * i / nr, t = t0 + (t1 - t0) * j / nt;
      m.vertices.emplace_back(r * std::cos(t), r * std::sin(t), 0.0);
    }
  }
  auto id = [nr](int i, int j) { return j * (nr + 1) + i; };
  for (int j = 0; j < nt; ++j) {
    for (int i = 0; i < nr; ++i) {
      if ((i + j) % 2 == 0) {
        m.faces.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
        m.faces.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
      } else {
        m.faces.push_back({id(i, j), id(i + 1, j), id(i, j + 1)});
        m.faces.push_back({id(i + 1, j), id(i + 1, j + 1), id(i, j + 1)});
      }
    }
  }
  return m;
}

/// A planar grid of nx x ny square cells of side h from the origin, each
/// split into two triangles (counter-clockwise seen from +z), keeping the
/// cells (i, j) for which keep(i, j) is true; only used vertices are kept.
template <class Keep>
TriMesh grid_cells(int nx, int ny, double h, Keep keep) {
  TriMesh m;
  std::vector<int> id(static_cast<size_t>((nx + 1) * (ny + 1)), -1);
  auto vertex = [&](int i, int j) {
    int& v = id[static_cast<size_t>(j * (nx + 1) + i)];
    if (v < 0) {
      v = m.num_vertices();
      m.vertices.emplace_back(i * h, j * h, 0.0);
    }
    return v;
  };
  for (int j = 0; j < ny; ++j) {
    for (int i = 0; i < nx; ++i) {
      if (!keep(i, j)) continue;
      const int a = vertex(i, j), b = vertex(i + 1, j), c = vertex(i + 1, j + 1), d = vertex(i, j + 1);
      m.faces.push_back({a, b, c});
      m.faces.push_back({a, c, d});
    }
  }
  return m;
}

}  // namespace knitforge::test
