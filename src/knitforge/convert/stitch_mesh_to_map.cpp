#include "knitforge/convert/stitch_mesh_to_map.h"

#include <algorithm>
#include <cstdint>
#include <limits>
#include <numeric>
#include <queue>
#include <tuple>

#include <fmt/core.h>

#include "knitforge/core/stitch_adjacency.h"
#include "knitforge/util/errors.h"
#include "knitforge/util/union_find.h"

namespace knitforge {

namespace {

// Component id per stitch, numbered 0..count-1 in order of the smallest stitch.
std::vector<int> components(UnionFind& uf, int n, int* count) {
  std::vector<int> id(n, -1), comp(n);
  int k = 0;
  for (int s = 0; s < n; ++s) {
    const int r = uf.find(s);
    if (id[r] < 0) id[r] = k++;
    comp[s] = id[r];
  }
  *count = k;
  return comp;
}

// Kahn's algorithm on a DAG given as an edge list; `key` orders the ready
// nodes (smallest first). Returns the position of each node, or an empty
// vector when a cycle remains.
template <typename Key>
std::vector<int> topological_order(int n, const std::vector<std::pair<int, int>>& edges,
                                   const std::vector<Key>& key) {
  std::vector<int> indeg(n, 0), start(n + 1, 0), adj(edges.size());
  for (const auto& e : edges) ++start[e.first + 1], ++indeg[e.second];
  for (int i = 0; i < n; ++i) start[i + 1] += start[i];
  std::vector<int> fill(start.begin(), start.end() - 1);
  for (const auto& e : edges) adj[fill[e.first]++] = e.second;
  using Item = std::pair<Key, int>;
  std::priority_queue<Item, std::vector<Item>, std::greater<Item>> ready;
  for (int i = 0; i < n; ++i) {
    if (indeg[i] == 0) ready.emplace(key[i], i);
  }
  std::vector<int> pos(n, -1);
  int next = 0;
  while (!ready.empty()) {
    const int u = ready.top().second;
    ready.pop();
    pos[u] = next++;
    for (int k = start[u]; k < start[u + 1]; ++k) {
      if (--indeg[adj[k]] == 0) ready.emplace(key[adj[k]], adj[k]);
    }
  }
  if (next != n) return {};
  return pos;
}

// The map of a tube (every stitch labelled with its wale; `wrap` marks the
// stitches whose Right edge closes a course). Columns are the labels minus
// the smallest; a row with a wrap edge is closed, its seam just after its
// last stitch (the largest index: stitches are numbered in knitting order).
KnittingMap tube_map(const StitchMesh& mesh, const StitchAdjacency& adj, const std::vector<int>& row_pos,
                     const std::vector<int>& row, const std::vector<char>& wrap) {
  const int n = mesh.num_stitches();
  int lo = std::numeric_limits<int>::max(), hi = 0;
  for (const Stitch& st : mesh.stitches) lo = std::min(lo, st.wale), hi = std::max(hi, st.wale);
  const int nrows = static_cast<int>(*std::max_element(row_pos.begin(), row_pos.end())) + 1;
  const int ncols = hi - lo + 1;
  if (static_cast<int64_t>(ncols) * nrows > int64_t{1} << 31)
    throw InvalidInput(fmt::format("stitch_mesh_to_map: the tube's map would be {} x {} cells", nrows, ncols));
  KnittingMap map(nrows, ncols, CellType::Empty);
  map.seam.assign(static_cast<size_t>(nrows), -1);
  std::vector<int> first(static_cast<size_t>(nrows), -1), owner(static_cast<size_t>(nrows) * ncols, -1);
  for (int s = 0; s < n; ++s) {
    const Stitch& st = mesh.stitches[s];
    const int r = row_pos[row[s]], c = st.wale - lo;
    int& o = owner[static_cast<size_t>(r) * ncols + c];
    if (o >= 0)
      throw InvalidInput(fmt::format("stitches {} and {} both fall into map cell (row {}, column {}) of the tube; "
                                     "their wale labels are not consistent",
                                     o, s, r, c));
    o = s;
    if (first[r] < 0) {
      first[r] = s;
      map.direction[r] = st.direction;
    } else if (mesh.stitches[first[r]].direction != st.direction) {
      throw InvalidInput(fmt::format("stitches {} and {} lie in the same row (map row {}) but have directions {} and "
                                     "{}; a row is knitted in one direction",
                                     first[r], s, r, static_cast<int>(mesh.stitches[first[r]].direction),
                                     static_cast<int>(st.direction)));
    }
    map.at(r, c) = to_cell_type(st.type);
    if (st.yarn != 0) map.set_yarn(r, c, st.yarn);
    if ((st.roles & kRoleClosingSeam) && r == nrows - 1) map.closed_end = true;
  }
  // the seam just after the round's last stitch (its largest index):
  // canonical_seam()
  std::vector<int> last(static_cast<size_t>(nrows), -1);
  for (int s = 0; s < n; ++s) last[static_cast<size_t>(row_pos[row[s]])] = s;
  for (int s = 0; s < n; ++s)
    if (wrap[s]) {
      const int r = row_pos[row[s]];
      const Stitch& l = mesh.stitches[last[static_cast<size_t>(r)]];
      map.seam[r] = l.direction > 0 ? (l.wale - lo + 1) % ncols : l.wale - lo;
    }
  auto collapse = [&](int r, int c, int s, int t) {
    CellType& cell = map.at(r, c);
    if (is_stitch(cell))
      throw InvalidInput(fmt::format("stitch {} lies in map cell (row {}, column {}) between the neighbours {} and "
                                     "{}; the wale labels of the tube are not consistent",
                                     owner[static_cast<size_t>(r) * ncols + c], r, c, s, t));
    cell = CellType::Collapsed;
  };
  for (int s = 0; s < n; ++s) {
    const int r = row_pos[row[s]], c = mesh.stitches[s].wale - lo;
    const int right = adj.neighbor(s, Side::Right);
    if (right >= 0) {
      const int rc = mesh.stitches[right].wale - lo;
      for (int cc = (c + 1) % ncols; cc != rc; cc = (cc + 1) % ncols) collapse(r, cc, s, right);
    }
    const int top = adj.neighbor(s, Side::Top);
    if (top >= 0) {
      if (mesh.stitches[top].wale != mesh.stitches[s].wale)
        throw InvalidInput(fmt::format("stitch {} and its Top neighbour {} have wale labels {} and {}; the wales of a "
                                       "tube must keep their labels",
                                       s, top, mesh.stitches[s].wale, mesh.stitches[top].wale));
      for (int rr = r + 1; rr < row_pos[row[top]]; ++rr) collapse(rr, c, s, top);
    }
  }
  return map;
}

}  // namespace

KnittingMap stitch_mesh_to_map(const StitchMesh& mesh) {
  const int n = mesh.num_stitches();
  if (n == 0) throw InvalidInput("stitch_mesh_to_map: the stitch mesh has no stitches");
  const StitchAdjacency adj(mesh);
  for (int s = 0; s < n; ++s) {
    for (int k = 0; k < 4; ++k) {
      const Side side = static_cast<Side>(k);
      const int t = adj.neighbor(s, side);
      if (t >= 0 && adj.neighbor_side(s, side) != opposite_side(side)) {
        throw InvalidInput(
            fmt::format("stitches {} and {} meet across side {} of stitch {} and side {} of stitch {}; "
                        "neighbours must meet "
                        "across opposite sides (Right against Left, Top against Bottom): check their types "
                        "and corner order",
                        s, t, k, s, static_cast<int>(adj.neighbor_side(s, side)), t));
      }
    }
  }

  // Row and column components.
  UnionFind urow(n), ucol(n);
  for (int s = 0; s < n; ++s) {
    const int r = adj.neighbor(s, Side::Right);
    if (r >= 0) urow.unite(s, r);
    const int t = adj.neighbor(s, Side::Top);
    if (t >= 0) ucol.unite(s, t);
  }
  int nrows = 0, ncols = 0;
  const std::vector<int> row = components(urow, n, &nrows);
  const std::vector<int> col = components(ucol, n, &ncols);

  // Row order: Bottom neighbour's row before the Top neighbour's row.
  std::vector<std::pair<int, int>> row_edges, col_edges;
  for (int s = 0; s < n; ++s) {
    const int t = adj.neighbor(s, Side::Top);
    if (t < 0) continue;
    if (row[s] == row[t]) {
      throw InvalidInput(
          fmt::format("stitch {} and its Top neighbour {} lie in the same row: the rows form a helix "
                      "(a course that climbs into itself), which cannot be knitted",
                      s, t));
    }
    row_edges.emplace_back(row[s], row[t]);
  }
  // Tie-break key per row: (smallest course label of its stitches, smallest
  // stitch index); labels of -1 (unknown) sort as "no preference".
  std::vector<std::pair<int, int>> row_key(nrows, {std::numeric_limits<int>::max(), n});
  for (int s = 0; s < n; ++s) {
    const int label =
        mesh.stitches[s].course >= 0 ? mesh.stitches[s].course : std::numeric_limits<int>::max();
    row_key[row[s]].first = std::min(row_key[row[s]].first, label);
    row_key[row[s]].second = std::min(row_key[row[s]].second, s);
  }
  const std::vector<int> row_pos = topological_order(nrows, row_edges, row_key);
  if (row_pos.empty()) {
    throw InvalidInput(
        "stitch_mesh_to_map: the rows form a cycle (a course is both below and above another one); "
        "the mesh cannot be knitted bottom to top");
  }


  for (int s = 0; s < n; ++s) {
    const int t = adj.neighbor(s, Side::Right);
    if (t < 0) continue;
    if (col[s] == col[t]) {
      throw InvalidInput(
          fmt::format("stitch {} and its Right neighbour {} lie in the same column: the columns form "
                      "a helix, which cannot be knitted",
                      s, t));
    }
    col_edges.emplace_back(col[s], col[t]);
  }
  // Tie-break key per column: (row of its lowest stitch, that stitch's index).
  std::vector<std::pair<int, int>> col_key(ncols, {nrows, n});
  for (int s = 0; s < n; ++s) {
    col_key[col[s]] = std::min(col_key[col[s]], std::pair<int, int>(row_pos[row[s]], s));
  }
  const std::vector<int> col_pos = topological_order(ncols, col_edges, col_key);
  if (col_pos.empty()) {
    // A tube: every stitch has a wale label and some Right neighbour has a
    // smaller or equal label (the course closes round the tube there). Wrap
    // edges close a course; the labels are the columns.
    bool tube = true;
    bool any_wrap = false;
    std::vector<char> wrap(static_cast<size_t>(n), 0);  // stitch s's Right edge closes its course
    for (int s = 0; s < n; ++s) {
      if (mesh.stitches[s].wale < 0) tube = false;
      const int t = adj.neighbor(s, Side::Right);
      if (t >= 0 && mesh.stitches[t].wale <= mesh.stitches[s].wale) wrap[s] = 1, any_wrap = true;
    }
    tube = tube && any_wrap;
    if (tube) return tube_map(mesh, adj, row_pos, row, wrap);
  }
  if (col_pos.empty()) {
    throw InvalidInput(
        "stitch_mesh_to_map: the columns form a cycle (a wale is both left and right of another "
        "one), e.g. a tube without wale labels; label the stitches' wales (Stitch::wale) or cut the mesh open "
        "along a wale");
  }

  // Per-stitch map cell. Wale labels, when every stitch has one and they agree
  // with the mesh, give the columns directly (a design route can put
  // vertically separate pieces of fabric, e.g. the two sides of a notch, in
  // the same columns); otherwise the computed column order is used.
  std::vector<int> srow(n), scol(n);
  for (int s = 0; s < n; ++s) {
    srow[s] = row_pos[row[s]];
    scol[s] = col_pos[col[s]];
  }
  {
    int lo = std::numeric_limits<int>::max(), hi = std::numeric_limits<int>::min();
    for (const Stitch& st : mesh.stitches) {
      lo = std::min(lo, st.wale);
      hi = std::max(hi, st.wale);
    }
    bool usable = lo >= 0 && static_cast<int64_t>(hi - lo + 1) * nrows <= int64_t{1} << 31;
    for (int s = 0; usable && s < n; ++s) {
      const int right = adj.neighbor(s, Side::Right), top = adj.neighbor(s, Side::Top);
      if (right >= 0 && mesh.stitches[right].wale <= mesh.stitches[s].wale) usable = false;
      if (top >= 0 && mesh.stitches[top].wale != mesh.stitches[s].wale) usable = false;
    }
    if (usable) {
      const int w = hi - lo + 1;
      std::vector<char> taken(static_cast<size_t>(w) * nrows, 0);
      for (int s = 0; usable && s < n; ++s) {
        char& t = taken[static_cast<size_t>(srow[s]) * w + (mesh.stitches[s].wale - lo)];
        if (t) usable = false;
        t = 1;
      }
      // The cells a neighbour pair skips (collapsed) must hold no stitch.
      auto free_cell = [&](int r, int c) { return !taken[static_cast<size_t>(r) * w + c]; };
      for (int s = 0; usable && s < n; ++s) {
        const int c = mesh.stitches[s].wale - lo;
        const int right = adj.neighbor(s, Side::Right), top = adj.neighbor(s, Side::Top);
        if (right >= 0) {
          for (int cc = c + 1; usable && cc < mesh.stitches[right].wale - lo; ++cc) usable = free_cell(srow[s], cc);
        }
        if (top >= 0) {
          for (int rr = srow[s] + 1; usable && rr < srow[top]; ++rr) usable = free_cell(rr, c);
        }
      }
    }
    if (usable) {
      ncols = hi - lo + 1;
      for (int s = 0; s < n; ++s) scol[s] = mesh.stitches[s].wale - lo;
    }
  }

  KnittingMap map(nrows, ncols, CellType::Empty);
  std::vector<int> owner(static_cast<size_t>(nrows) * ncols, -1);
  std::vector<int> row_stitch(nrows, -1);
  for (int s = 0; s < n; ++s) {
    const Stitch& st = mesh.stitches[s];
    const int r = srow[s], c = scol[s];
    int& o = owner[static_cast<size_t>(r) * ncols + c];
    if (o >= 0) {
      throw InvalidInput(
          fmt::format("stitches {} and {} both fall into map cell (row {}, column {}); the rows and "
                      "columns of the mesh are not consistent",
                      o, s, r, c));
    }
    o = s;
    int& rs = row_stitch[r];
    if (rs < 0) {
      rs = s;
      map.direction[r] = st.direction;
    } else if (mesh.stitches[rs].direction != st.direction) {
      throw InvalidInput(fmt::format(
          "stitches {} and {} lie in the same row (map row {}) but have directions {} and "
          "{}; a row is knitted in one direction",
          rs, s, r, static_cast<int>(mesh.stitches[rs].direction), static_cast<int>(st.direction)));
    }
    map.at(r, c) = to_cell_type(st.type);
    if (st.yarn != 0) map.set_yarn(r, c, st.yarn);
  }
  auto collapse = [&](int r, int c, int s, int t) {
    CellType& cell = map.at(r, c);
    if (is_stitch(cell)) {
      throw InvalidInput(
          fmt::format("stitch {} lies in map cell (row {}, column {}) between the neighbours {} and "
                      "{}; the rows and columns of the mesh are not consistent",
                      owner[static_cast<size_t>(r) * ncols + c], r, c, s, t));
    }
    cell = CellType::Collapsed;
  };
  for (int s = 0; s < n; ++s) {
    const int r = srow[s], c = scol[s];
    const int right = adj.neighbor(s, Side::Right);
    if (right >= 0) {
      for (int cc = c + 1; cc < scol[right]; ++cc) collapse(r, cc, s, right);
    }
    const int top = adj.neighbor(s, Side::Top);
    if (top >= 0) {
      for (int rr = r + 1; rr < srow[top]; ++rr) collapse(rr, c, s, top);
    }
  }
  return map;
}

}  // namespace knitforge
