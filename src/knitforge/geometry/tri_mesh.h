#pragma once
/// \file tri_mesh.h
/// TriMesh: the triangle mesh of an input surface (plain data). Connectivity
/// is built on demand with build_halfedges() (halfedges.h); validation with
/// validate_surface() (surface_checks.h).

#include <array>
#include <vector>

#include "knitforge/geometry/vec.h"

namespace knitforge {

/// A triangle mesh: vertex positions (mm) and counter-clockwise triangles
/// (vertex indices into `vertices`).
struct TriMesh {
  std::vector<Vec3> vertices;
  std::vector<std::array<int, 3>> faces;

  int num_vertices() const { return static_cast<int>(vertices.size()); }
  int num_faces() const { return static_cast<int>(faces.size()); }
};

}  // namespace knitforge
