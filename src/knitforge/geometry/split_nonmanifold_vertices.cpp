#include "knitforge/geometry/split_nonmanifold_vertices.h"

#include <algorithm>
#include <cstdint>

#include <fmt/core.h>

#include "knitforge/util/counting_sort.h"
#include "knitforge/util/errors.h"
#include "knitforge/util/union_find.h"

namespace knitforge {

VertexFanSplit split_nonmanifold_vertices(int num_vertices, std::span<const int> face_start,
                                          std::span<const int> face_vertices) {
  if (face_start.empty() || face_start.front() != 0 ||
      face_start.back() != static_cast<int>(face_vertices.size())) {
    throw InvalidInput(
        "split_nonmanifold_vertices: face_start must start at 0 and end at the number of corners");
  }
  const int nf = static_cast<int>(face_start.size()) - 1;
  for (int f = 0; f < nf; ++f) {
    if (face_start[f + 1] < face_start[f]) {
      throw InvalidInput(fmt::format("split_nonmanifold_vertices: face {} has a negative corner count", f));
    }
  }
  const int nc = static_cast<int>(face_vertices.size());
  for (int c = 0; c < nc; ++c) {
    if (face_vertices[c] < 0 || face_vertices[c] >= num_vertices) {
      throw InvalidInput(fmt::format("split_nonmanifold_vertices: corner {} uses vertex {}, outside [0, {})",
                                     c, face_vertices[c], num_vertices));
    }
  }
  // Every corner c at v sees two edges (v, next) and (v, prev); corners of
  // v that see the same edge are in one fan.
  struct Side {
    int v, other, corner;
  };
  std::vector<Side> sides;
  sides.reserve(2 * static_cast<size_t>(nc));
  for (int f = 0; f < nf; ++f) {
    const int b = face_start[f], n = face_start[f + 1] - b;
    for (int k = 0; k < n; ++k) {
      const int v = face_vertices[b + k];
      sides.push_back({v, face_vertices[b + (k + 1) % n], b + k});
      sides.push_back({v, face_vertices[b + (k + n - 1) % n], b + k});
    }
  }
  // By (v, other), ties in corner order (linear time).
  counting_sort_by(sides, num_vertices, [](const Side& x) { return x.other; });
  counting_sort_by(sides, num_vertices, [](const Side& x) { return x.v; });
  UnionFind fans(static_cast<size_t>(nc));
  for (size_t i = 1; i < sides.size(); ++i) {
    if (sides[i].v == sides[i - 1].v && sides[i].other == sides[i - 1].other)
      fans.unite(sides[i].corner, sides[i - 1].corner);
  }
  VertexFanSplit out;
  out.face_vertices.assign(face_vertices.begin(), face_vertices.end());
  out.vertex_origin.resize(num_vertices);
  for (int v = 0; v < num_vertices; ++v) out.vertex_origin[v] = v;
  // Per vertex, its fans in order of their first corner (the smallest corner
  // of a class is its representative).
  std::vector<std::vector<int>> roots(num_vertices);
  for (int c = 0; c < nc; ++c) {
    const int v = face_vertices[c];
    const int r = fans.find(c);
    if (std::find(roots[v].begin(), roots[v].end(), r) == roots[v].end()) roots[v].push_back(r);
  }
  std::vector<int> copy_of_root(static_cast<size_t>(nc), -1);
  for (int v = 0; v < num_vertices; ++v) {
    if (roots[v].size() < 2) continue;
    ++out.num_split;
    copy_of_root[roots[v][0]] = v;
    for (size_t i = 1; i < roots[v].size(); ++i) {
      copy_of_root[roots[v][i]] = static_cast<int>(out.vertex_origin.size());
      out.vertex_origin.push_back(v);
    }
  }
  if (out.num_split == 0) return out;
  for (int c = 0; c < nc; ++c) {
    const int r = fans.find(c);
    if (copy_of_root[r] >= 0) out.face_vertices[c] = copy_of_root[r];
  }
  return out;
}

}  // namespace knitforge
