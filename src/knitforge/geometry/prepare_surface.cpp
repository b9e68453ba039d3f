#include "knitforge/geometry/prepare_surface.h"

#include <algorithm>
#include <array>
#include <numeric>

#include "knitforge/geometry/surface_checks.h"

namespace knitforge {

namespace {

bool valid_index(const TriMesh& mesh, int v) { return v >= 0 && v < mesh.num_vertices(); }

/// Welds vertices at identical positions that share no face (the copies
/// along a split seam): per vertex, the first vertex of its group. A group
/// with two members in one face (a zero-length edge) is left alone: that
/// is a degenerate face, not a split.
TriMesh weld(const TriMesh& mesh, std::vector<int>& rep, int& welded) {
  const int n = mesh.num_vertices();
  std::vector<int> order(n);
  std::iota(order.begin(), order.end(), 0);
  auto less = [&](int a, int b) {
    const Vec3& p = mesh.vertices[a];
    const Vec3& q = mesh.vertices[b];
    if (p.x() != q.x()) return p.x() < q.x();
    if (p.y() != q.y()) return p.y() < q.y();
    if (p.z() != q.z()) return p.z() < q.z();
    return a < b;
  };
  std::sort(order.begin(), order.end(), less);
  std::vector<int> group(n, -1);  // the group's first vertex, for groups of two or more
  for (int i = 1; i < n; ++i) {
    const int v = order[i], u = order[i - 1];
    if (mesh.vertices[u] == mesh.vertices[v] && mesh.vertices[v].allFinite()) {
      if (group[u] < 0) group[u] = u;
      group[v] = group[u];
    }
  }
  std::vector<char> touching(n, 0);  // per group: two members share a face
  for (const auto& t : mesh.faces) {
    if (!valid_index(mesh, t[0]) || !valid_index(mesh, t[1]) || !valid_index(mesh, t[2])) continue;
    for (int k = 0; k < 3; ++k) {
      const int a = group[t[k]], b = group[t[(k + 1) % 3]];
      if (a >= 0 && a == b) touching[a] = 1;
    }
  }
  rep.resize(n);
  welded = 0;
  for (int v = 0; v < n; ++v) {
    rep[v] = v;
    if (group[v] >= 0 && !touching[group[v]] && group[v] != v) {
      rep[v] = group[v];
      ++welded;
    }
  }
  TriMesh out;
  out.vertices = mesh.vertices;
  out.faces = mesh.faces;
  if (welded == 0) return out;
  for (auto& t : out.faces)
    for (int& v : t)
      if (valid_index(mesh, v)) v = rep[v];
  return out;
}

}  // namespace

PreparedSurface prepare_surface(const TriMesh& mesh) {
  PreparedSurface out;
  TriMesh m = mesh;
  std::vector<int> rep(mesh.num_vertices());
  std::iota(rep.begin(), rep.end(), 0);
  int welded = 0;
  TriMesh w = weld(mesh, rep, welded);
  if (welded > 0) {
    if (validate_surface(w).num_errors <= validate_surface(mesh).num_errors) {
      m = std::move(w);
      out.welded_vertices = welded;
    } else {
      std::iota(rep.begin(), rep.end(), 0);
    }
  }
  // Drop the vertices no face uses, keeping the order of the others.
  std::vector<int> index(m.num_vertices(), -1);
  for (const auto& t : m.faces)
    for (int v : t)
      if (valid_index(m, v)) index[v] = 0;
  for (int v = 0; v < m.num_vertices(); ++v) {
    if (index[v] < 0) continue;
    index[v] = static_cast<int>(out.mesh.vertices.size());
    out.mesh.vertices.push_back(m.vertices[v]);
  }
  out.mesh.faces = m.faces;
  for (auto& t : out.mesh.faces)
    for (int& v : t)
      if (valid_index(m, v)) v = index[v];
  out.vertex_map.resize(mesh.num_vertices());
  for (int v = 0; v < mesh.num_vertices(); ++v) {
    out.vertex_map[v] = index[rep[v]];
    if (index[v] < 0 && rep[v] == v) ++out.unused_vertices;
  }
  return out;
}

}  // namespace knitforge
