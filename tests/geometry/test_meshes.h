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

// A closed UV sphere round the origin, outward oriented: `segments` vertices
// round each of `rings` - 1 latitude circles, plus the two poles.
inline TriMesh uv_sphere_mesh(double radius, int segments, int rings) {
  TriMesh m;
  const double pi = std::numbers::pi;
  m.vertices.push_back({0, 0, radius});
  for (int i = 1; i < rings; ++i) {
    const double th = pi * i / rings;
    for (int j = 0; j < segments; ++j) {
      const double ph = 2 * pi * j / segments;
      m.vertices.push_back({radius * std::sin(th) * std::cos(ph), radius * std::sin(th) * std::sin(ph), radius * std::cos(th)});
    }
  }
  m.vertices.push_back({0, 0, -radius});
  const int south = static_cast<int>(m.vertices.size()) - 1;
  auto at = [&](int ring, int j) { return 1 + (ring - 1) * segments + (j % segments); };
  for (int j = 0; j < segments; ++j) m.faces.push_back({0, at(1, j), at(1, j + 1)});
  for (int i = 1; i + 1 < rings; ++i)
    for (int j = 0; j < segments; ++j) {
      m.faces.push_back({at(i, j), at(i + 1, j), at(i + 1, j + 1)});
      m.faces.push_back({at(i, j), at(i + 1, j + 1), at(i, j + 1)});
    }
  for (int j = 0; j < segments; ++j) m.faces.push_back({south, at(rings - 1, j + 1), at(rings - 1, j)});
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
