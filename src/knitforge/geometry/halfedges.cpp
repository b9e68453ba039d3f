#include "knitforge/geometry/halfedges.h"

#include <algorithm>
#include <cstdint>
#include <numeric>

#include <fmt/core.h>

#include "knitforge/util/counting_sort.h"
#include "knitforge/util/errors.h"

namespace knitforge {

namespace {

// Rotation around the source vertex of h: the next half-edge leaving the same
// vertex, in the face across the edge prev(h); -1 at the boundary.
int rotate(const Halfedges& m, int h) { return m.opposite(m.prev(h)); }

}  // namespace

Halfedges build_halfedges(int num_vertices, std::span<const int> face_start,
                          std::span<const int> face_vertices) {
  if (face_start.empty() || face_start.front() != 0 ||
      static_cast<size_t>(face_start.back()) != face_vertices.size()) {
    throw InvalidInput("build_halfedges: face_start must begin with 0 and end with the number of "
                       "face vertices");
  }
  for (size_t f = 0; f + 1 < face_start.size(); ++f) {
    if (face_start[f + 1] < face_start[f]) {
      throw InvalidInput(fmt::format("build_halfedges: face_start must not decrease (face {} starts at {}, "
                                     "face {} at {})",
                                     f, face_start[f], f + 1, face_start[f + 1]));
    }
  }
  Halfedges m;
  const int nf = static_cast<int>(face_start.size()) - 1;
  const int nh = static_cast<int>(face_vertices.size());
  m.num_vertices_ = num_vertices;
  m.face_start_.assign(face_start.begin(), face_start.end());
  m.from_.resize(nh);
  m.to_.resize(nh);
  m.face_.resize(nh);
  m.opposite_.assign(nh, -1);
  m.edge_.assign(nh, -1);

  for (int f = 0; f < nf; ++f) {
    const int b = face_start[f], e = face_start[f + 1];
    if (e - b < 3) {
      throw TopologyError(fmt::format("face {} has {} vertices; a face needs at least 3", f, e - b));
    }
    for (int i = b; i < e; ++i) {
      const int v = face_vertices[i];
      if (v < 0 || v >= num_vertices) {
        throw TopologyError(fmt::format("face {} uses vertex {}, but there are only {} vertices", f,
                                        v, num_vertices));
      }
      for (int j = b; j < i; ++j) {
        if (face_vertices[j] == v) {
          throw TopologyError(fmt::format("face {} uses vertex {} twice (degenerate face)", f, v));
        }
      }
      m.from_[i] = v;
      m.to_[i] = face_vertices[i + 1 < e ? i + 1 : b];
      m.face_[i] = f;
    }
  }

  // Pair half-edges by sorting undirected edge keys (min vertex, max vertex,
  // half-edge): by the max vertex, then stably by the min one (linear time,
  // the order a comparison sort of the keys gives).
  std::vector<std::pair<uint64_t, int>> keys(nh);
  for (int h = 0; h < nh; ++h) {
    const uint64_t a = static_cast<uint32_t>(std::min(m.from_[h], m.to_[h]));
    const uint64_t b = static_cast<uint32_t>(std::max(m.from_[h], m.to_[h]));
    keys[h] = {(a << 32) | b, h};
  }
  counting_sort_by(keys, num_vertices, [](const std::pair<uint64_t, int>& k) {
    return static_cast<int>(k.first & 0xffffffffu);
  });
  counting_sort_by(keys, num_vertices, [](const std::pair<uint64_t, int>& k) { return static_cast<int>(k.first >> 32); });
  int edge_count = 0;
  for (int i = 0; i < nh;) {
    int j = i + 1;
    while (j < nh && keys[j].first == keys[i].first) ++j;
    const int h0 = keys[i].second;
    if (j - i > 2) {
      std::string faces;
      for (int k = i; k < j && k < i + 8; ++k) faces += fmt::format("{}{}", k > i ? ", " : "", m.face_[keys[k].second]);
      if (j - i > 8) faces += fmt::format(" and {} more", j - i - 8);
      throw TopologyError(fmt::format(
          "edge ({}, {}) is shared by {} faces ({}); a manifold mesh has at most 2 per edge",
          m.from_[h0], m.to_[h0], j - i, faces));
    }
    if (j - i == 2) {
      const int h1 = keys[i + 1].second;
      if (m.from_[h0] == m.from_[h1]) {
        throw TopologyError(fmt::format(
            "faces {} and {} both use edge ({} -> {}) in the same direction: the face orientation "
            "is inconsistent (flip one of them) or the surface is non-orientable",
            m.face_[h0], m.face_[h1], m.from_[h0], m.to_[h0]));
      }
      m.opposite_[h0] = h1;
      m.opposite_[h1] = h0;
      m.edge_[h1] = edge_count;
    }
    m.edge_[h0] = edge_count++;
    i = j;
  }
  m.num_edges_ = edge_count;

  // One outgoing half-edge per vertex, a boundary one when the vertex has one.
  m.vertex_halfedge_.assign(num_vertices, -1);
  m.vertex_on_boundary_.assign(num_vertices, 0);
  std::vector<int> corner_count(num_vertices, 0);
  std::vector<int> boundary_out(num_vertices, 0);
  for (int h = 0; h < nh; ++h) {
    const int v = m.from_[h];
    ++corner_count[v];
    if (m.opposite_[h] < 0) {
      ++boundary_out[v];
      m.vertex_halfedge_[v] = h;
      m.vertex_on_boundary_[v] = 1;
      m.vertex_on_boundary_[m.to_[h]] = 1;
    } else if (m.vertex_halfedge_[v] < 0) {
      m.vertex_halfedge_[v] = h;
    }
  }
  for (int v = 0; v < num_vertices; ++v) {
    if (m.vertex_halfedge_[v] < 0) continue;
    int fan = 0;
    int h = m.vertex_halfedge_[v];
    do {
      ++fan;
      h = rotate(m, h);
    } while (h >= 0 && h != m.vertex_halfedge_[v] && fan <= corner_count[v]);
    if (fan != corner_count[v] || boundary_out[v] > 1) {
      throw TopologyError(fmt::format(
          "vertex {} is non-manifold: its {} faces form more than one fan (surfaces touch at a "
          "single vertex); split the vertex or remove one of the parts",
          v, corner_count[v]));
    }
  }
  return m;
}

Halfedges build_halfedges(int num_vertices, const std::vector<std::array<int, 3>>& triangles) {
  std::vector<int> start(triangles.size() + 1);
  std::vector<int> verts(triangles.size() * 3);
  for (size_t f = 0; f < triangles.size(); ++f) {
    start[f + 1] = static_cast<int>(3 * (f + 1));
    for (int k = 0; k < 3; ++k) verts[3 * f + k] = triangles[f][k];
  }
  return build_halfedges(num_vertices, start, verts);
}

std::vector<int> Halfedges::vertex_faces(int v) const {
  std::vector<int> out;
  const int h0 = vertex_halfedge_[v];
  if (h0 < 0) return out;
  int h = h0;
  do {
    out.push_back(face_[h]);
    h = rotate(*this, h);
  } while (h >= 0 && h != h0);
  return out;
}

std::vector<int> Halfedges::vertex_neighbors(int v) const {
  std::vector<int> out;
  const int h0 = vertex_halfedge_[v];
  if (h0 < 0) return out;
  int h = h0;
  int last = h0;
  do {
    out.push_back(to_[h]);
    last = h;
    h = rotate(*this, h);
  } while (h >= 0 && h != h0);
  if (h < 0) out.push_back(from_[prev(last)]);
  return out;
}

std::vector<std::vector<int>> Halfedges::boundary_loops() const {
  std::vector<std::vector<int>> loops;
  std::vector<char> seen(to_.size(), 0);
  for (int h = 0; h < num_halfedges(); ++h) {
    if (opposite_[h] >= 0 || seen[h]) continue;
    std::vector<int> loop;
    int g = h;
    while (!seen[g]) {
      seen[g] = 1;
      loop.push_back(from_[g]);
      g = vertex_halfedge_[to_[g]];
    }
    auto smallest = std::min_element(loop.begin(), loop.end());
    std::rotate(loop.begin(), smallest, loop.end());
    loops.push_back(std::move(loop));
  }
  std::sort(loops.begin(), loops.end());
  return loops;
}

std::vector<int> Halfedges::face_components(int* count) const {
  const int nf = num_faces();
  std::vector<int> comp(nf, -1);
  std::vector<int> stack;
  int c = 0;
  for (int f0 = 0; f0 < nf; ++f0) {
    if (comp[f0] >= 0) continue;
    comp[f0] = c;
    stack.push_back(f0);
    while (!stack.empty()) {
      const int f = stack.back();
      stack.pop_back();
      for (int k = 0; k < face_size(f); ++k) {
        const int g = neighbor(f, k);
        if (g >= 0 && comp[g] < 0) {
          comp[g] = c;
          stack.push_back(g);
        }
      }
    }
    ++c;
  }
  if (count) *count = c;
  return comp;
}

}  // namespace knitforge
