#pragma once
// Small hand-made meshes shared by the geometry tests.

#include <array>
#include <cmath>
#include <numbers>
#include <vector>

#include <gtest/gtest.h>

#include "knitforge/geometry/halfedges.h"
#include "knitforge/geometry/tri_mesh.h"

namespace knitforge::test {

// An n x n grid of unit squares in z = 0 over [0, n]², every square split by
// the diagonal (i, j)-(i+1, j+1); vertex (i, j) has index j (n + 1) + i.
inline TriMesh square_grid(int n, double size = 1.0) {
  TriMesh m;
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) m.vertices.emplace_back(size * i, size * j, 0.0);
  auto id = [n](int i, int j) { return j * (n + 1) + i; };
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < n; ++i) {
      m.faces.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
      m.faces.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
    }
  }
  return m;
}

// A grid on an annulus (rings x sectors quads), or on a torus when `torus`;
// consistently oriented.
inline TriMesh ring_grid(int rings, int sectors, bool torus) {
  TriMesh m;
  const int nr = torus ? rings : rings + 1;
  for (int r = 0; r < nr; ++r) {
    for (int s = 0; s < sectors; ++s) {
      const double phi = 2.0 * std::numbers::pi * s / sectors;
      if (torus) {
        const double theta = 2.0 * std::numbers::pi * r / rings;
        const double rho = 3.0 + std::cos(theta);
        m.vertices.emplace_back(rho * std::cos(phi), rho * std::sin(phi), std::sin(theta));
      } else {
        m.vertices.emplace_back((1.0 + r) * std::cos(phi), (1.0 + r) * std::sin(phi), 0.0);
      }
    }
  }
  auto id = [&](int r, int s) { return (r % nr) * sectors + (s % sectors); };
  for (int r = 0; r < rings; ++r) {
    for (int s = 0; s < sectors; ++s) {
      m.faces.push_back({id(r, s), id(r + 1, s), id(r + 1, s + 1)});
      m.faces.push_back({id(r, s), id(r + 1, s + 1), id(r, s + 1)});
    }
  }
  return m;
}

// A regular tetrahedron surface (closed, outward normals).
inline TriMesh tetrahedron() {
  TriMesh m;
  m.vertices = {{1, 1, 1}, {1, -1, -1}, {-1, 1, -1}, {-1, -1, 1}};
  m.faces = {{0, 1, 2}, {0, 3, 1}, {0, 2, 3}, {1, 3, 2}};
  return m;
}

// Expects a closed (watertight), oriented, edge-manifold mesh: every half-edge
// has an opposite (build_halfedges() has already rejected non-manifold and
// inconsistently oriented input). Returns the number of face components.
inline int expect_watertight(const TriMesh& m) {
  const Halfedges he = build_halfedges(m.num_vertices(), m.faces);
  EXPECT_TRUE(he.boundary_loops().empty());
  for (int h = 0; h < he.num_halfedges(); ++h) EXPECT_GE(he.opposite(h), 0) << "half-edge " << h;
  EXPECT_EQ(2 * he.num_edges(), he.num_halfedges());
  int components = 0;
  he.face_components(&components);
  return components;
}

}  // namespace knitforge::test
