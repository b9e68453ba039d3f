#include "knitforge/machine/knit_graph_to_map.h"

#include <algorithm>
#include <cmath>
#include <queue>
#include <set>
#include <tuple>

#include <fmt/core.h>

#include "knitforge/convert/map_knittability.h"
#include "knitforge/convert/map_to_stitch_mesh.h"
#include "knitforge/machine/knit_graph_compare.h"
#include "knitforge/util/errors.h"

namespace knitforge {

namespace {

struct Row {
  std::vector<int> stitches;  // indices into stitch_loops, in knitting order
  int8_t dir = 1;
  uint32_t carriers = 0;
};

bool on_back(const KnitLoop& l) { return !l.needle.is_front_side(); }

// Rows: runs of stitch loops in formation order with one carrier set and one
// direction, each further along the bed than the one before.
std::vector<Row> split_rows(const KnitGraph& g, const std::vector<int>& stitches) {
  std::vector<Row> rows;
  for (size_t i = 0; i < stitches.size(); ++i) {
    const KnitLoop& l = g.loops[static_cast<size_t>(stitches[i])];
    bool same = !rows.empty();
    if (same) {
      const Row& r = rows.back();
      const KnitLoop& prev = g.loops[static_cast<size_t>(stitches[static_cast<size_t>(r.stitches.back())])];
      same = r.dir == l.direction && r.carriers == l.carriers && (l.slot - prev.slot) * r.dir > 0;
    }
    if (!same) {
      rows.push_back({});
      rows.back().dir = l.direction;
      rows.back().carriers = l.carriers;
    }
    rows.back().stitches.push_back(static_cast<int>(i));
  }
  return rows;
}

// The tubular map of a plain tube (docs/tubes.md): each round's first half
// (`first` stitches, on the back bed when first_back, knitted in carriage
// direction dir) and second half side by side, the front half in columns
// 0..h-1 left to right; kept when the program knits exactly that map.
void tube_map(const KnitGraph& g, KnitGraphFabric& out, int dir, bool first_back, int first) {
  const int C = out.ring, h = C / 2;
  if (C < 4 || C % 2 != 0 || first != h) return;  // not the two equal halves of our layout
  // The row direction in column order: a front half going + is +1, a back
  // half going - is +1 too (the round comes back along the back bed).
  const int d = first_back ? -dir : dir;
  KnittingMap m(out.rounds, C, CellType::Knit);
  m.direction.assign(static_cast<size_t>(out.rounds), static_cast<int8_t>(d));
  // the first stitch's column and the seam line
  const int first_col = first_back ? (d > 0 ? h : C - 1) : (d > 0 ? 0 : h - 1);
  const int seam = d > 0 ? first_col : (first_col + 1) % C;
  m.seam.assign(static_cast<size_t>(out.rounds), seam);
  std::vector<int> loc(static_cast<size_t>(out.rounds) * C, -1);
  for (int r = 0; r < out.rounds; ++r) {
    const std::vector<int> order = row_columns(m, r);
    for (int k = 0; k < C; ++k)
      loc[static_cast<size_t>(r) * C + order[static_cast<size_t>(k)]] =
          out.loop_of_round_stitch[static_cast<size_t>(r) * C + k];
  }
  if (!check_knittability(m).ok() || !compare_knit_graph(g, m).ok()) return;
  out.map = std::move(m);
  out.loop_of_cell = loc;
  for (size_t i = 0; i < loc.size(); ++i) out.cell_of_loop[static_cast<size_t>(loc[i])] = static_cast<int>(i);
}

}  // namespace

KnitGraphFabric knit_graph_fabric(const KnitoutSimulation& sim) {
  const KnitGraph& g = sim.graph;
  KnitGraphFabric out;
  out.stitch_loops = fabric_loops(g);
  out.cell_of_loop.assign(static_cast<size_t>(g.num_loops()), -1);
  const std::vector<int>& S = out.stitch_loops;
  if (S.empty()) {
    out.reason = "the program makes no fabric stitches";
    return out;
  }
  std::vector<int> index(static_cast<size_t>(g.num_loops()), -1);  // loop -> stitch index
  for (size_t i = 0; i < S.size(); ++i) index[static_cast<size_t>(S[i])] = static_cast<int>(i);
  auto loop = [&](int s) -> const KnitLoop& { return g.loops[static_cast<size_t>(S[static_cast<size_t>(s)])]; };

  // Primary parent of every stitch: its wale continues through it.
  std::vector<int> primary(S.size(), -1);
  for (size_t s = 0; s < S.size(); ++s) {
    const KnitLoop& l = g.loops[static_cast<size_t>(S[s])];
    std::tuple<int, double, int> best{0, 0.0, 0};
    int k = 0;
    for (int p : g.parents_of(S[s])) {
      const int ps = index[static_cast<size_t>(p)];
      if (ps >= 0) {
        const std::tuple<int, double, int> key{g.loops[static_cast<size_t>(p)].transfers,
                                               std::abs(g.loops[static_cast<size_t>(p)].slot - l.slot), k};
        if (primary[s] < 0 || key < best) {
          primary[s] = ps;
          best = key;
        }
      }
      ++k;
    }
  }

  const std::vector<Row> rows = split_rows(g, S);
  std::vector<int> row_of(S.size(), -1);
  for (size_t r = 0; r < rows.size(); ++r)
    for (int s : rows[r].stitches) row_of[static_cast<size_t>(s)] = static_cast<int>(r);

  // --- tubes: rows alternate between the beds, none knitted through the row before
  {
    bool alternating = rows.size() >= 4;
    for (size_t r = 0; r < rows.size() && alternating; ++r) {
      const bool back = on_back(loop(rows[r].stitches.front()));
      for (int s : rows[r].stitches) alternating = alternating && on_back(loop(s)) == back;
      if (r > 0) alternating = alternating && back != on_back(loop(rows[r - 1].stitches.front()));
      for (int s : rows[r].stitches)
        if (primary[static_cast<size_t>(s)] >= 0 && row_of[static_cast<size_t>(primary[static_cast<size_t>(s)])] + 1 ==
                                                        static_cast<int>(r))
          alternating = false;
    }
    if (alternating) {
      const size_t n = rows[0].stitches.size() + rows[1].stitches.size();
      bool plain = rows.size() % 2 == 0;
      for (size_t r = 0; r + 1 < rows.size() && plain; r += 2)
        plain = rows[r].stitches.size() + rows[r + 1].stitches.size() == n;
      std::vector<int> ring_pos(S.size(), -1);
      std::vector<int> round_loops;
      for (size_t r = 0; r + 1 < rows.size() && plain; r += 2) {
        int j = 0;
        for (size_t h = r; h <= r + 1; ++h) {
          for (int s : rows[h].stitches) {
            ring_pos[static_cast<size_t>(s)] = j++;
            round_loops.push_back(S[static_cast<size_t>(s)]);
            // every stitch above the first round continues the stitch below it
            if (r > 0) plain = plain && primary[static_cast<size_t>(s)] >= 0 &&
                               ring_pos[static_cast<size_t>(primary[static_cast<size_t>(s)])] == j - 1;
          }
        }
      }
      if (plain) {
        out.kind = "tube";
        out.rounds = static_cast<int>(rows.size() / 2);
        out.ring = static_cast<int>(n);
        out.loop_of_round_stitch = std::move(round_loops);
        tube_map(g, out, rows[0].dir, on_back(loop(rows[0].stitches.front())),
                 static_cast<int>(rows[0].stitches.size()));
      } else {
        out.reason = "a tube knitted on both beds whose rounds change (shaped tubes are not drawn yet)";
      }
      return out;
    }
  }

  // --- sheets: wales and their left-to-right order
  std::vector<int> wale(S.size(), -1);
  std::vector<uint8_t> continued(S.size(), 0);
  int W = 0;
  for (size_t s = 0; s < S.size(); ++s) {
    // A parent continues one wale; a second stitch through it (the old loop
    // of a split, knitted again after it moved) starts a new wale.
    const int p = primary[s];
    if (p >= 0 && !continued[static_cast<size_t>(p)]) {
      continued[static_cast<size_t>(p)] = 1;
      wale[s] = wale[static_cast<size_t>(p)];
    } else {
      wale[s] = W++;
    }
  }
  std::vector<int> first_row(static_cast<size_t>(W), INT32_MAX), last_row(static_cast<size_t>(W), -1);
  std::vector<double> first_slot(static_cast<size_t>(W), 0.0);
  for (size_t s = 0; s < S.size(); ++s) {
    const int w = wale[s], r = row_of[s];
    if (r < first_row[static_cast<size_t>(w)]) {
      first_row[static_cast<size_t>(w)] = r;
      first_slot[static_cast<size_t>(w)] = loop(static_cast<int>(s)).slot;
    }
    last_row[static_cast<size_t>(w)] = std::max(last_row[static_cast<size_t>(w)], r);
  }
  std::vector<std::set<int>> right_of(static_cast<size_t>(W));  // edges a -> b: wale a left of wale b
  std::vector<int> indegree(static_cast<size_t>(W), 0);
  for (const Row& row : rows) {
    std::set<int> seen;
    for (size_t i = 0; i < row.stitches.size(); ++i) {
      const int w = wale[static_cast<size_t>(row.stitches[i])];
      if (!seen.insert(w).second) {
        out.reason = "one wale is knitted twice in one course";
        return out;
      }
      if (i == 0) continue;
      int a = wale[static_cast<size_t>(row.stitches[i - 1])], b = w;
      if (row.dir < 0) std::swap(a, b);
      if (right_of[static_cast<size_t>(a)].insert(b).second) ++indegree[static_cast<size_t>(b)];
    }
  }
  // Kahn's algorithm; among ready wales the one that starts first, then leftmost.
  auto later = [&](int a, int b) {
    return std::make_pair(first_row[static_cast<size_t>(a)], first_slot[static_cast<size_t>(a)]) >
           std::make_pair(first_row[static_cast<size_t>(b)], first_slot[static_cast<size_t>(b)]);
  };
  std::priority_queue<int, std::vector<int>, decltype(later)> ready(later);
  for (int w = 0; w < W; ++w)
    if (indegree[static_cast<size_t>(w)] == 0) ready.push(w);
  std::vector<int> col(static_cast<size_t>(W), -1);
  int next_col = 0;
  while (!ready.empty()) {
    const int w = ready.top();
    ready.pop();
    col[static_cast<size_t>(w)] = next_col++;
    for (int b : right_of[static_cast<size_t>(w)])
      if (--indegree[static_cast<size_t>(b)] == 0) ready.push(b);
  }
  if (next_col < W) {
    out.reason = "the wales cross (a cable or a tube): no left-to-right order of columns fits every course";
    return out;
  }

  // --- cells
  const int R = static_cast<int>(rows.size()), Cc = W;
  KnittingMap m(R, Cc, CellType::Empty);
  std::vector<int> loc(static_cast<size_t>(R) * Cc, -1);
  for (int r = 0; r < R; ++r) m.direction[static_cast<size_t>(r)] = rows[static_cast<size_t>(r)].dir;
  std::set<uint32_t> carrier_sets;
  for (size_t s = 0; s < S.size(); ++s) {
    const size_t i = static_cast<size_t>(row_of[s]) * Cc + col[static_cast<size_t>(wale[s])];
    m.cells[i] = CellType::Knit;
    loc[i] = static_cast<int>(s);
    carrier_sets.insert(loop(static_cast<int>(s)).carriers);
  }
  auto alive = [&](int r, int c, const std::vector<int>& wale_of_col) {
    const int w = wale_of_col[static_cast<size_t>(c)];
    return first_row[static_cast<size_t>(w)] <= r && r <= last_row[static_cast<size_t>(w)];
  };
  std::vector<int> wale_of_col(static_cast<size_t>(Cc));
  for (int w = 0; w < W; ++w) wale_of_col[static_cast<size_t>(col[static_cast<size_t>(w)])] = w;
  for (int r = 0; r < R; ++r) {
    int lo = Cc, hi = -1;
    for (int c = 0; c < Cc; ++c)
      if (is_stitch(m.at(r, c))) lo = std::min(lo, c), hi = std::max(hi, c);
    for (int c = 0; c < Cc; ++c) {
      if (is_stitch(m.at(r, c))) continue;
      if (alive(r, c, wale_of_col) || (c > lo && c < hi)) m.at(r, c) = CellType::Collapsed;
    }
  }
  // shaping stitches
  auto live_beyond = [&](int r, int c, int d) {
    for (int x = c + d; x >= 0 && x < Cc; x += d)
      if (alive(r, x, wale_of_col)) return true;
    return false;
  };
  for (int r = 0; r < R; ++r) {
    const Row& row = rows[static_cast<size_t>(r)];
    const int d = row.dir;
    // short-row turn after row r
    const int last = row.stitches.back();
    const int k = col[static_cast<size_t>(wale[static_cast<size_t>(last)])];
    if (r + 1 < R && live_beyond(r, k, d)) {
      const CellType t = d > 0 ? CellType::ShortRowRight : CellType::ShortRowLeft;
      m.at(r, k) = t;
      const int first_next = rows[static_cast<size_t>(r) + 1].stitches.front();
      if (col[static_cast<size_t>(wale[static_cast<size_t>(first_next)])] == k) m.at(r + 1, k) = t;
    }
  }
  // A wale's first (last) stitch is an Increase (Decrease) exactly when the
  // cells around it merge its bottom (top) corners: the courses below (above)
  // pass where it starts (ends). Each change can change the collapsed cells
  // around it, so repeat until nothing changes.
  for (int pass = 0; pass < 8; ++pass) {
    std::vector<int> cls;
    try {
      cls = map_corner_classes(canonical_cells(m));
    } catch (const InvalidInput&) {
      break;  // reported below
    }
    auto corner = [&](int i, int j) { return cls[static_cast<size_t>(i) * (Cc + 1) + j]; };
    bool changed = false;
    for (int w = 0; w < W; ++w) {
      const int c = col[static_cast<size_t>(w)];
      const int fr = first_row[static_cast<size_t>(w)], lr = last_row[static_cast<size_t>(w)];
      CellType& first = m.at(fr, c);
      if (fr > 0 && first == CellType::Knit && corner(fr, c) == corner(fr, c + 1)) {
        first = CellType::Increase;
        changed = true;
      }
      CellType& last = m.at(lr, c);
      if (lr + 1 < R && last == CellType::Knit && corner(lr + 1, c) == corner(lr + 1, c + 1)) {
        last = CellType::Decrease;
        changed = true;
      }
    }
    if (!changed) break;
  }
  if (carrier_sets.size() > 1) {
    for (size_t i = 0; i < loc.size(); ++i)
      if (loc[i] >= 0)
        m.set_yarn(static_cast<int>(i / Cc), static_cast<int>(i % Cc),
                   std::max(0, loop(loc[i]).first_carrier()));
  }
  try {
    m = canonical_cells(m);
  } catch (const InvalidInput& e) {
    out.reason = std::string("the fabric gives no valid knitting map: ") + e.what();
    return out;
  }
  const KnittabilityReport check = check_knittability(m);
  if (!check.ok()) {
    std::string first;
    for (const auto& v : check.violations)
      if (v.severity == Severity::Error) {
        first = v.message;
        break;
      }
    out.reason = "the fabric's map is not knittable by the seed's rules: " + first;
    return out;
  }
  const GraphComparison cmp = compare_knit_graph(g, m);
  if (!cmp.ok()) {
    out.reason = fmt::format("the fabric is no sheet a knitting map describes exactly ({} mismatch(es): {})",
                             cmp.mismatches, cmp.issues.empty() ? std::string() : cmp.issues.front().message);
    return out;
  }
  out.kind = "sheet";
  out.map = std::move(m);
  out.loop_of_cell.assign(loc.size(), -1);
  for (size_t i = 0; i < loc.size(); ++i) {
    if (loc[i] < 0) continue;
    out.loop_of_cell[i] = S[static_cast<size_t>(loc[i])];
    out.cell_of_loop[static_cast<size_t>(S[static_cast<size_t>(loc[i])])] = static_cast<int>(i);
  }
  return out;
}

}  // namespace knitforge
