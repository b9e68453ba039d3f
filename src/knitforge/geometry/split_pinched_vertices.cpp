#include "knitforge/geometry/split_pinched_vertices.h"

#include <numeric>

#include <fmt/format.h>

#include "knitforge/util/errors.h"

namespace knitforge {

namespace {

int find(std::vector<int>& parent, int x) {
  while (parent[static_cast<size_t>(x)] != x) {
    parent[static_cast<size_t>(x)] = parent[static_cast<size_t>(parent[static_cast<size_t>(x)])];
    x = parent[static_cast<size_t>(x)];
  }
  return x;
}

}  // namespace

std::vector<int> split_pinched_vertices(TriMesh& mesh) {
  const int n = mesh.num_vertices();
  std::vector<std::vector<int>> faces_at(static_cast<size_t>(n));
  for (int f = 0; f < mesh.num_faces(); ++f)
    for (int v : mesh.faces[static_cast<size_t>(f)]) {
      if (v < 0 || v >= n) throw InvalidInput(fmt::format("split_pinched_vertices: face {} uses vertex {} of {}", f, v, n));
      faces_at[static_cast<size_t>(v)].push_back(f);
    }
  std::vector<int> origin(static_cast<size_t>(n));
  std::iota(origin.begin(), origin.end(), 0);
  for (int v = 0; v < n; ++v) {
    const std::vector<int>& fan = faces_at[static_cast<size_t>(v)];
    if (fan.size() < 2) continue;
    std::vector<int> parent(fan.size());
    std::iota(parent.begin(), parent.end(), 0);
    // Faces i, j at v are linked when they share another vertex (the edge (v, w)).
    for (size_t i = 0; i < fan.size(); ++i)
      for (size_t j = i + 1; j < fan.size(); ++j) {
        bool linked = false;
        for (int a : mesh.faces[static_cast<size_t>(fan[i])])
          for (int b : mesh.faces[static_cast<size_t>(fan[j])]) linked = linked || (a == b && a != v);
        if (linked) parent[static_cast<size_t>(find(parent, static_cast<int>(i)))] = find(parent, static_cast<int>(j));
      }
    // The fan of the first face keeps v; every other fan gets a copy.
    const int keep = find(parent, 0);
    std::vector<int> copy_of(fan.size(), -1);  // root -> new vertex
    for (size_t i = 0; i < fan.size(); ++i) {
      const int root = find(parent, static_cast<int>(i));
      if (root == keep) continue;
      int& c = copy_of[static_cast<size_t>(root)];
      if (c < 0) {
        c = mesh.num_vertices();
        mesh.vertices.push_back(mesh.vertices[static_cast<size_t>(v)]);
        origin.push_back(v);
      }
      for (int& w : mesh.faces[static_cast<size_t>(fan[i])])
        if (w == v) w = c;
    }
  }
  return origin;
}

}  // namespace knitforge
