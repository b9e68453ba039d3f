#include "knitforge/geometry/pseudo_normals.h"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "knitforge/geometry/edge_key.h"
#include "knitforge/util/errors.h"

namespace knitforge {

Vec3 PseudoNormals::at(const TriMesh& mesh, int f, const TrianglePoint& where) const {
  const auto& t = mesh.faces[static_cast<size_t>(f)];
  switch (where.region) {
    case TrianglePoint::Region::Face:
      return face[static_cast<size_t>(f)];
    case TrianglePoint::Region::Edge: {
      const auto it = edge.find(undirected_edge_key(t[where.feature], t[(where.feature + 1) % 3]));
      return it == edge.end() ? face[static_cast<size_t>(f)] : it->second;
    }
    case TrianglePoint::Region::Vertex:
      return vertex[static_cast<size_t>(t[where.feature])];
  }
  return face[static_cast<size_t>(f)];
}

PseudoNormals pseudo_normals(const TriMesh& mesh) {
  const int n = mesh.num_vertices();
  PseudoNormals out;
  out.face.assign(mesh.faces.size(), Vec3::Zero());
  out.vertex.assign(static_cast<size_t>(n), Vec3::Zero());
  out.edge.reserve(3 * mesh.faces.size() / 2 + 1);
  for (size_t f = 0; f < mesh.faces.size(); ++f) {
    const auto& t = mesh.faces[f];
    for (int k = 0; k < 3; ++k)
      if (t[k] < 0 || t[k] >= n)
        throw InvalidInput(fmt::format("pseudo-normals: face {} has vertex {} out of range", f, t[k]));
    const Vec3 p[3] = {mesh.vertices[static_cast<size_t>(t[0])], mesh.vertices[static_cast<size_t>(t[1])],
                       mesh.vertices[static_cast<size_t>(t[2])]};
    const Vec3 cr = (p[1] - p[0]).cross(p[2] - p[0]);
    const double len = cr.norm();
    if (!(len > 0.0)) continue;
    const Vec3 nrm = cr / len;
    out.face[f] = nrm;
    for (int k = 0; k < 3; ++k) {
      const Vec3 a = p[(k + 1) % 3] - p[k], b = p[(k + 2) % 3] - p[k];
      const double angle = std::atan2(a.cross(b).norm(), a.dot(b));
      out.vertex[static_cast<size_t>(t[k])] += angle * nrm;
      out.edge.try_emplace(undirected_edge_key(t[k], t[(k + 1) % 3]), Vec3::Zero()).first->second += nrm;
    }
  }
  return out;
}

bool is_closed_mesh(const TriMesh& mesh) {
  std::unordered_map<std::uint64_t, int> count;
  count.reserve(3 * mesh.faces.size() / 2 + 1);
  for (const auto& t : mesh.faces)
    for (int k = 0; k < 3; ++k) ++count[undirected_edge_key(t[k], t[(k + 1) % 3])];
  if (count.empty()) return false;
  return std::all_of(count.begin(), count.end(), [](const auto& e) { return e.second == 2; });
}

}  // namespace knitforge
