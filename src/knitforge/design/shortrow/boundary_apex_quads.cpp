#include "knitforge/design/shortrow/boundary_apex_quads.h"

#include <set>
#include <vector>

#include "knitforge/core/stitch_adjacency.h"

namespace knitforge {

namespace {

bool is_short_row_end(StitchType t) {
  return t == StitchType::ShortRowLeft || t == StitchType::ShortRowRight;
}

/// The stitches around vertex v reached from the Top neighbour of `last`
/// through edges at v, without entering the fan.
std::vector<int> faces_beyond(const StitchMesh& mesh, const StitchAdjacency& adj, int v, int last,
                              const std::vector<int>& fan) {
  const Halfedges& he = adj.halfedges();
  std::vector<int> out;
  const int start = adj.neighbor(last, Side::Top);
  if (start < 0) return out;
  std::set<int> seen(fan.begin(), fan.end());
  std::vector<int> stack{start};
  seen.insert(start);
  while (!stack.empty()) {
    const int f = stack.back();
    stack.pop_back();
    out.push_back(f);
    const Stitch& st = mesh.stitches[f];
    const int n = st.corners();
    for (int c = 0; c < n; ++c) {
      if (st.v[c] != v) continue;
      for (int e : {c, (c + n - 1) % n}) {
        const int g = he.neighbor(f, e);
        if (g >= 0 && !seen.count(g)) {
          seen.insert(g);
          stack.push_back(g);
        }
      }
    }
  }
  return out;
}

/// One pass: converts the fans found with the current adjacency, at most one
/// per apex vertex. Returns the number of fans converted.
int convert_pass(StitchMesh& mesh, std::set<int>& refused, BoundaryApexQuadStats& stats) {
  const StitchAdjacency adj(mesh);
  const int n = mesh.num_stitches();
  std::vector<char> done(n, 0);
  std::set<int> apex_used;
  struct Fan {
    std::vector<int> stitches;  // bottom to top
    int apex;
    StitchType type;
  };
  std::vector<Fan> fans;
  for (int s = 0; s < n; ++s) {
    const Stitch& st = mesh.stitches[s];
    if (done[s] || !is_short_row_end(st.type)) continue;
    const int apex = apex_vertex(st);
    if (!adj.is_boundary_vertex(apex) || refused.count(apex)) continue;
    auto same_fan = [&](int t) {
      return t >= 0 && mesh.stitches[t].type == st.type && apex_vertex(mesh.stitches[t]) == apex;
    };
    int bottom = s;
    for (int guard = 0; guard < n && same_fan(adj.neighbor(bottom, Side::Bottom)); ++guard) {
      bottom = adj.neighbor(bottom, Side::Bottom);
    }
    Fan fan{{}, apex, st.type};
    for (int t = bottom, guard = 0; t >= 0 && guard < n; ++guard) {
      fan.stitches.push_back(t);
      done[t] = 1;
      const int up = adj.neighbor(t, Side::Top);
      t = same_fan(up) && !done[up] ? up : -1;
    }
    if (apex_used.count(apex)) continue;  // next pass
    apex_used.insert(apex);
    fans.push_back(std::move(fan));
  }

  int converted = 0;
  for (const Fan& fan : fans) {
    const int k = static_cast<int>(fan.stitches.size());
    const bool left = fan.type == StitchType::ShortRowLeft;
    // Far-side chain q_0..q_k.
    std::vector<int> q(k + 1);
    for (int i = 0; i < k; ++i) {
      const Stitch& st = mesh.stitches[fan.stitches[i]];
      q[i] = left ? st.v[1] : st.v[0];
      q[i + 1] = left ? st.v[2] : st.v[2];
    }
    const bool bottom_shared = adj.neighbor(fan.stitches.front(), Side::Bottom) >= 0;
    const bool top_shared = adj.neighbor(fan.stitches.back(), Side::Top) >= 0;
    const Vec3 p = mesh.vertices[fan.apex];
    std::vector<int> copy(k + 1);
    if (bottom_shared && top_shared) {
      // The fan sits between stitches at both ends (an apex in the middle of
      // a boundary wale): the stitches on the top side get their own copy
      // p_k, and the copies are spread along the chain around p's place.
      const std::vector<int> above = faces_beyond(mesh, adj, fan.apex, fan.stitches.back(), fan.stitches);
      if (above.empty()) {
        refused.insert(fan.apex);
        ++stats.left_alone;
        continue;
      }
      const Vec3 mid = mesh.vertices[q[k / 2]];
      copy[0] = fan.apex;
      for (int i = 1; i <= k; ++i) {
        copy[i] = mesh.num_vertices();
        mesh.vertices.push_back(p + (mesh.vertices[q[i]] - mid));
      }
      mesh.vertices[fan.apex] = p + (mesh.vertices[q[0]] - mid);
      for (int f : above) {
        Stitch& st = mesh.stitches[f];
        for (int c = 0; c < st.corners(); ++c) {
          if (st.v[c] == fan.apex) st.v[c] = copy[k];
        }
      }
    } else {
      const int keep = bottom_shared ? 0 : k;
      for (int i = 0; i <= k; ++i) {
        if (i == keep) {
          copy[i] = fan.apex;
        } else {
          copy[i] = mesh.num_vertices();
          mesh.vertices.push_back(p + (mesh.vertices[q[i]] - mesh.vertices[q[keep]]));
        }
      }
    }
    for (int i = 0; i < k; ++i) {
      Stitch& st = mesh.stitches[fan.stitches[i]];
      st.type = StitchType::Knit;
      if (left) {
        st.v = {copy[i], q[i], q[i + 1], copy[i + 1]};
      } else {
        st.v = {q[i], copy[i], copy[i + 1], q[i + 1]};
      }
    }
    ++stats.fans;
    stats.triangles += k;
    ++converted;
  }
  return converted;
}

}  // namespace

BoundaryApexQuadStats boundary_apex_quads(StitchMesh& mesh) {
  BoundaryApexQuadStats stats;
  std::set<int> refused;
  while (convert_pass(mesh, refused, stats) > 0) {
  }
  return stats;
}

}  // namespace knitforge
