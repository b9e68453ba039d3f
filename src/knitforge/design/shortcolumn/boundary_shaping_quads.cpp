#include "knitforge/design/shortcolumn/boundary_shaping_quads.h"

#include <map>
#include <optional>
#include <utility>
#include <vector>

#include "knitforge/core/stitch_adjacency.h"

namespace knitforge {

namespace {

using Edge = std::pair<int, int>;
Edge key(int a, int b) { return a < b ? Edge{a, b} : Edge{b, a}; }

/// The stitches around vertex a reached from stitch `from` across its edge
/// (a, w) and onwards around a, until the boundary (or back at `from`).
std::vector<int> fan_from(const StitchMesh& mesh, const std::map<Edge, std::vector<int>>& by_edge, int from, int a,
                          int w) {
  std::vector<int> fan;
  int prev = from, other = w;
  for (int guard = 0; guard < mesh.num_stitches(); ++guard) {
    const auto it = by_edge.find(key(a, other));
    if (it == by_edge.end()) break;
    int next = -1;
    for (int t : it->second)
      if (t != prev) next = t;
    if (next < 0 || next == from) break;
    fan.push_back(next);
    // The other edge of `next` at a.
    const Stitch& st = mesh.stitches[static_cast<size_t>(next)];
    const int n = st.corners();
    int c = 0;
    while (c < n && st.v[static_cast<size_t>(c)] != a) ++c;
    const int before = st.v[static_cast<size_t>((c + n - 1) % n)], after = st.v[static_cast<size_t>((c + 1) % n)];
    other = before == other ? after : before;
    prev = next;
  }
  return fan;
}

}  // namespace

BoundaryShapingQuadStats boundary_shaping_quads(StitchMesh& mesh) {
  BoundaryShapingQuadStats stats;
  // Every change below adds a vertex and changes corners of stitches, so the
  // adjacency is built again before the next stitch is looked at (a change
  // is rare: one per shaping stitch at the fabric's edge).
  std::optional<StitchAdjacency> built;
  const int n = mesh.num_stitches();
  for (int s = 0; s < n; ++s) {
    if (mesh.stitches[s].type != StitchType::Increase && mesh.stitches[s].type != StitchType::Decrease) continue;
    if (!built) built.emplace(mesh);
    const StitchAdjacency& adj = *built;
    Stitch& st = mesh.stitches[s];
    const int a = apex_vertex(st);
    if (!adj.is_boundary_vertex(a)) continue;
    const bool left = adj.neighbor(s, Side::Left) >= 0;
    const bool right = adj.neighbor(s, Side::Right) >= 0;
    if (left && right) {
      // The boundary passes the apex between the two neighbours: split the
      // apex, the right neighbours take the copy, and the triangle becomes a
      // quad whose top (bottom) edge is half its other edge.
      std::map<Edge, std::vector<int>> by_edge;
      for (int t = 0; t < n; ++t) {
        const Stitch& u = mesh.stitches[static_cast<size_t>(t)];
        for (int k = 0; k < u.corners(); ++k)
          by_edge[key(u.v[static_cast<size_t>(k)], u.v[static_cast<size_t>((k + 1) % u.corners())])].push_back(t);
      }
      const bool inc = st.type == StitchType::Increase;
      // Increase (A, TR, TL): right edge A-TR; Decrease (BL, BR, A): right edge BR-A.
      const std::vector<int> fan = fan_from(mesh, by_edge, s, a, st.v[1]);
      const Vec3 p = mesh.vertices[static_cast<size_t>(a)];
      const Vec3 half = 0.25 * (inc ? mesh.vertices[static_cast<size_t>(st.v[1])] - mesh.vertices[static_cast<size_t>(st.v[2])]
                                    : mesh.vertices[static_cast<size_t>(st.v[1])] - mesh.vertices[static_cast<size_t>(st.v[0])]);
      const int copy = mesh.num_vertices();
      mesh.vertices.push_back(p + half);
      mesh.vertices[static_cast<size_t>(a)] = p - half;
      for (int t : fan) {
        Stitch& u = mesh.stitches[static_cast<size_t>(t)];
        for (int k = 0; k < u.corners(); ++k)
          if (u.v[static_cast<size_t>(k)] == a) u.v[static_cast<size_t>(k)] = copy;
      }
      Stitch& me = mesh.stitches[static_cast<size_t>(s)];
      if (inc) me.v = {a, copy, me.v[1], me.v[2]};
      else me.v = {me.v[0], me.v[1], copy, a};
      me.type = StitchType::Knit;
      ++stats.split_apexes;
      ++(inc ? stats.increases : stats.decreases);
      built.reset();
      continue;
    }
    const Vec3 p = mesh.vertices[a];
    const int copy = mesh.num_vertices();
    if (st.type == StitchType::Increase) {
      const int tr = st.v[1], tl = st.v[2];
      if (!right) {
        mesh.vertices.push_back(p + mesh.vertices[tr] - mesh.vertices[tl]);
        st.v = {a, copy, tr, tl};
      } else {
        mesh.vertices.push_back(p + mesh.vertices[tl] - mesh.vertices[tr]);
        st.v = {copy, a, tr, tl};
      }
      ++stats.increases;
    } else {
      const int bl = st.v[0], br = st.v[1];
      if (!right) {
        mesh.vertices.push_back(p + mesh.vertices[br] - mesh.vertices[bl]);
        st.v = {bl, br, copy, a};
      } else {
        mesh.vertices.push_back(p + mesh.vertices[bl] - mesh.vertices[br]);
        st.v = {bl, br, a, copy};
      }
      ++stats.decreases;
    }
    st.type = StitchType::Knit;
    built.reset();
  }
  return stats;
}

}  // namespace knitforge
