#pragma once
// Planar test meshes of the short-column tests.
#include <cmath>

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

}  // namespace knitforge::test
