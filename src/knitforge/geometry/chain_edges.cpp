#include "knitforge/geometry/chain_edges.h"

#include <cstddef>

namespace knitforge {

std::vector<std::vector<int>> chain_edges(int num_nodes, const std::vector<std::pair<int, int>>& edges,
                                          bool isolated_nodes) {
  std::vector<std::vector<int>> inc(static_cast<size_t>(num_nodes));
  for (int e = 0; e < static_cast<int>(edges.size()); ++e) {
    inc[edges[e].first].push_back(e);
    inc[edges[e].second].push_back(e);
  }
  std::vector<char> used(edges.size(), 0);
  std::vector<std::vector<int>> out;
  auto walk = [&](int start, int e) {
    std::vector<int> path{start};
    int node = start;
    while (e >= 0) {
      used[e] = 1;
      node = edges[e].first == node ? edges[e].second : edges[e].first;
      path.push_back(node);
      e = -1;
      if (inc[node].size() == 2)
        for (int f : inc[node])
          if (!used[f]) e = f;
    }
    out.push_back(std::move(path));
  };
  for (int v = 0; v < num_nodes; ++v) {
    if (inc[v].empty() && isolated_nodes) out.push_back({v});
    if (inc[v].size() == 2) continue;
    for (int e : inc[v])
      if (!used[e]) walk(v, e);
  }
  for (int e = 0; e < static_cast<int>(edges.size()); ++e)
    if (!used[e]) walk(edges[e].first, e);
  return out;
}

}  // namespace knitforge
