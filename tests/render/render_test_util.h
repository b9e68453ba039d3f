#pragma once
// Small scenes for the render tests.

#include <cmath>
#include <numbers>

#include "knitforge/render/render_mesh.h"

namespace knitforge::test {

/// Axis-aligned rectangle [x0, x1] x [y0, y1] at height z, two CCW triangles
/// facing +z (or -z when `flip`).
inline RenderMesh rectangle_mesh(double x0, double y0, double x1, double y1, double z, RenderColour c,
                                 bool flip = false) {
  RenderMesh m;
  m.mesh.vertices = {{x0, y0, z}, {x1, y0, z}, {x1, y1, z}, {x0, y1, z}};
  if (flip)
    m.mesh.faces = {{0, 2, 1}, {0, 3, 2}};
  else
    m.mesh.faces = {{0, 1, 2}, {0, 2, 3}};
  m.colour = c;
  return m;
}

/// UV sphere with `segments` vertices around and `rings` bands from pole to
/// pole (rings even puts a vertex ring on the equator), outward CCW faces.
inline RenderMesh uv_sphere(const Vec3& centre, double radius, int segments, int rings, RenderColour c) {
  RenderMesh m;
  m.colour = c;
  auto& v = m.mesh.vertices;
  v.push_back(centre + Vec3(0, 0, radius));
  for (int i = 1; i < rings; ++i) {
    const double th = std::numbers::pi * i / rings;
    for (int j = 0; j < segments; ++j) {
      const double ph = 2.0 * std::numbers::pi * j / segments;
      v.push_back(centre +
                  radius * Vec3(std::sin(th) * std::cos(ph), std::sin(th) * std::sin(ph), std::cos(th)));
    }
  }
  v.push_back(centre - Vec3(0, 0, radius));
  const int south = static_cast<int>(v.size()) - 1;
  auto at = [&](int i, int j) { return 1 + (i - 1) * segments + (j % segments); };
  for (int j = 0; j < segments; ++j) m.mesh.faces.push_back({0, at(1, j), at(1, j + 1)});
  for (int i = 1; i + 1 < rings; ++i) {
    for (int j = 0; j < segments; ++j) {
      m.mesh.faces.push_back({at(i, j), at(i + 1, j), at(i + 1, j + 1)});
      m.mesh.faces.push_back({at(i, j), at(i + 1, j + 1), at(i, j + 1)});
    }
  }
  for (int j = 0; j < segments; ++j) m.mesh.faces.push_back({south, at(rings - 1, j + 1), at(rings - 1, j)});
  return m;
}

}  // namespace knitforge::test
