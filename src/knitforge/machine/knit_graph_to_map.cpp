#include "knitforge/machine/knit_graph_to_map.h"

#include <algorithm>
#include <cmath>
#include <queue>
#include <set>
#include <tuple>

#include <fmt/core.h>

#include "knitforge/convert/map_knittability.h"
#include "knitforge/convert/map_to_stitch_mesh.h"
#include "knitforge/convert/pack_tube_columns.h"
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

// The first error of a knittability report.
std::string first_error(const KnittabilityReport& check) {
  for (const auto& v : check.violations)
    if (v.severity == Severity::Error) return v.message;
  return {};
}

// Makes `m` canonical (canonical_cells(); a tube's columns packed,
// pack_tube_columns()) and returns "" when the seed's rules pass and the
// program knits exactly it, else why not.
std::string accept_map(const KnitGraph& g, KnittingMap& m) {
  const bool tube = m.tubular();
  try {
    m = tube ? pack_tube_columns(m) : canonical_cells(m);
  } catch (const InvalidInput& e) {
    return fmt::format("the fabric gives no valid {}: {}", tube ? "tubular map" : "knitting map", e.what());
  }
  const KnittabilityReport check = check_knittability(m);
  if (!check.ok())
    return fmt::format("the fabric's {} is not knittable by the seed's rules: {}", tube ? "tubular map" : "map",
                       first_error(check));
  const GraphComparison cmp = compare_knit_graph(g, m);
  if (!cmp.ok())
    return fmt::format("the fabric is no {} exactly ({} mismatch(es): {})",
                       tube ? "tube a tubular map describes" : "sheet a knitting map describes", cmp.mismatches,
                       cmp.issues.empty() ? std::string() : cmp.issues.front().message);
  return {};
}

// Fills out's loop_of_cell and cell_of_loop for `map`, whose stitches in
// knitting order are the stitch loops in formation order (what
// compare_knit_graph() has checked).
void name_cells(const std::vector<int>& S, const KnittingMap& map, KnitGraphFabric& out) {
  out.loop_of_cell.assign(map.cells.size(), -1);
  size_t k = 0;
  for (int r = 0; r < map.rows; ++r)
    for (int c : row_columns(map, r)) {
      const size_t i = static_cast<size_t>(r) * map.cols + c;
      if (!is_stitch(map.cells[i]) || k >= S.size()) continue;
      out.loop_of_cell[i] = S[k];
      out.cell_of_loop[static_cast<size_t>(S[k++])] = static_cast<int>(i);
    }
}

// The fabric as a tubular map (see the file comment, "Tubes"): sets out.map
// and returns "", or returns why it is none.
std::string tube_fabric(const KnitGraph& g, const std::vector<int>& S, const std::vector<int>& index,
                        const std::vector<int>& wale, int W, KnitGraphFabric& out) {
  const int n = static_cast<int>(S.size());
  auto loop = [&](int s) -> const KnitLoop& { return g.loops[static_cast<size_t>(S[static_cast<size_t>(s)])]; };
  auto back = [&](int s) { return on_back(loop(s)); };
  // The direction round the tube: a front stitch going + and a back stitch
  // going - both go +1 in column order.
  auto round_dir = [&](int s) { return back(s) ? -loop(s).direction : loop(s).direction; };

  std::vector<int> first(static_cast<size_t>(W), -1), last(static_cast<size_t>(W), -1);  // stitch indices
  for (int s = 0; s < n; ++s) {
    const size_t w = static_cast<size_t>(wale[static_cast<size_t>(s)]);
    if (first[w] < 0) first[w] = s;
    else if (back(first[w]) != back(s))
      return fmt::format("a wale moves to the other bed (the stitch of line {}): each half of a tube keeps its wales",
                         loop(s).line);
    last[w] = s;
  }

  // Strokes: runs with one carrier set going one way round the tube, each
  // stitch further round than the one before (on its bed, or across a fold).
  std::vector<std::pair<int, int>> strokes;  // [begin, end)
  for (int s = 0; s < n; ++s) {
    bool same = s > 0;
    if (same) {
      const KnitLoop &a = loop(s - 1), &b = loop(s);
      same = a.carriers == b.carriers && round_dir(s - 1) == round_dir(s) &&
             (back(s - 1) != back(s) || (b.needle.index - a.needle.index) * b.direction > 0);
    }
    if (!same) strokes.push_back({s, s});
    strokes.back().second = s + 1;
  }

  // Rows within a stroke: pieces that knit no wale twice and no stitch
  // through another of the piece. A piece is a round when it holds every
  // wale alive across it (alive: a stitch at or before its end and one at
  // or after its start), else a short row, which does not cross the left
  // fold (line 0) and is neither the first nor the last row.
  std::vector<int> started(static_cast<size_t>(n) + 1, 0), ended(static_cast<size_t>(n) + 1, 0);
  for (int w = 0; w < W; ++w) {
    ++started[static_cast<size_t>(first[static_cast<size_t>(w)]) + 1];
    ++ended[static_cast<size_t>(last[static_cast<size_t>(w)]) + 1];
  }
  for (size_t k = 0; k < static_cast<size_t>(n); ++k) started[k + 1] += started[k], ended[k + 1] += ended[k];
  auto is_round = [&](int i, int j) {
    return j - i + 1 == started[static_cast<size_t>(j) + 1] - ended[static_cast<size_t>(i)];
  };
  auto row_ok = [&](int i, int j) {
    if (is_round(i, j)) return true;
    if (i == 0 || j == n - 1) return false;
    for (int k = i + 1; k <= j; ++k)
      if (back(k - 1) != back(k) && back(k - 1) == (round_dir(k) > 0)) return false;  // across line 0
    return true;
  };
  std::vector<int> stamp(static_cast<size_t>(W), -1);
  int piece_id = 0;
  auto in = [](int x, int i, int j) { return x >= i && x <= j; };
  // Cuts [b, e) into maximal pieces from its end (backward) or its start.
  auto cut = [&](int b, int e, bool backward) {
    std::vector<std::pair<int, int>> pieces;
    for (int i = backward ? e - 1 : b; backward ? i >= b : i < e;) {
      const int id = piece_id++;
      int lo = i, hi = i;
      stamp[static_cast<size_t>(wale[static_cast<size_t>(i)])] = id;
      while (true) {
        const int k = backward ? lo - 1 : hi + 1;
        if (k < b || k >= e || stamp[static_cast<size_t>(wale[static_cast<size_t>(k)])] == id) break;
        bool through = false;  // a stitch of the piece knitted through k, or k through one of the piece
        if (backward) {
          const int child = loop(k).child;
          through = child >= 0 && in(index[static_cast<size_t>(child)], lo, hi);
        } else {
          for (int p : g.parents_of(S[static_cast<size_t>(k)])) through = through || in(index[static_cast<size_t>(p)], lo, hi);
        }
        if (through) break;
        stamp[static_cast<size_t>(wale[static_cast<size_t>(k)])] = id;
        (backward ? lo : hi) = k;
      }
      pieces.push_back({lo, hi});
      i = backward ? lo - 1 : hi + 1;
    }
    if (backward) std::reverse(pieces.begin(), pieces.end());
    return pieces;
  };
  std::vector<std::pair<int, int>> rows;  // inclusive stitch ranges
  for (const auto& [b, e] : strokes) {
    // Rounds as late as possible (a wedge's last short row, then rounds);
    // else as early as possible.
    bool ok = false;
    for (bool backward : {true, false}) {
      const auto pieces = cut(b, e, backward);
      ok = std::all_of(pieces.begin(), pieces.end(), [&](const auto& p) { return row_ok(p.first, p.second); });
      if (ok) {
        rows.insert(rows.end(), pieces.begin(), pieces.end());
        break;
      }
    }
    if (!ok)
      return fmt::format("the stitches of lines {} to {} go round the tube one way but are no rounds (every live "
                         "wale once) and short rows (part of the round, not across the left fold) one after another",
                         loop(b).line, loop(e - 1).line);
  }

  // Each bed's wales from left to right: an order every row agrees with.
  const int R = static_cast<int>(rows.size());
  std::vector<int> row_of(static_cast<size_t>(n));
  for (int r = 0; r < R; ++r)
    for (int s = rows[static_cast<size_t>(r)].first; s <= rows[static_cast<size_t>(r)].second; ++s)
      row_of[static_cast<size_t>(s)] = r;
  std::vector<std::set<int>> right_of(static_cast<size_t>(W));
  std::vector<int> indegree(static_cast<size_t>(W), 0);
  for (const auto& [i, j] : rows) {
    for (bool b : {false, true}) {
      std::vector<std::pair<int, int>> on_bed;  // needle, wale
      for (int s = i; s <= j; ++s)
        if (back(s) == b) on_bed.push_back({loop(s).needle.index, wale[static_cast<size_t>(s)]});
      std::sort(on_bed.begin(), on_bed.end());
      for (size_t k = 1; k < on_bed.size(); ++k)
        if (right_of[static_cast<size_t>(on_bed[k - 1].second)].insert(on_bed[k].second).second)
          ++indegree[static_cast<size_t>(on_bed[k].second)];
    }
  }
  auto later = [&](int a, int b) {  // ready wales: the one that starts first, then the leftmost
    const int sa = first[static_cast<size_t>(a)], sb = first[static_cast<size_t>(b)];
    return std::make_pair(row_of[static_cast<size_t>(sa)], loop(sa).needle.index) >
           std::make_pair(row_of[static_cast<size_t>(sb)], loop(sb).needle.index);
  };
  std::priority_queue<int, std::vector<int>, decltype(later)> ready(later);
  for (int w = 0; w < W; ++w)
    if (indegree[static_cast<size_t>(w)] == 0) ready.push(w);
  std::vector<int> bed_order[2];
  while (!ready.empty()) {
    const int w = ready.top();
    ready.pop();
    bed_order[back(first[static_cast<size_t>(w)]) ? 1 : 0].push_back(w);
    for (int b : right_of[static_cast<size_t>(w)])
      if (--indegree[static_cast<size_t>(b)] == 0) ready.push(b);
  }
  if (static_cast<int>(bed_order[0].size() + bed_order[1].size()) < W)
    return "the wales of a bed cross (a cable): no left-to-right order fits every row";

  // One column per wale (pack_tube_columns() packs them): the front wales
  // left to right, the back wales from the right fold to the left fold.
  const int h = static_cast<int>(std::max(bed_order[0].size(), bed_order[1].size())), C = 2 * h;
  std::vector<int> col(static_cast<size_t>(W));
  for (size_t k = 0; k < bed_order[0].size(); ++k) col[static_cast<size_t>(bed_order[0][k])] = static_cast<int>(k);
  for (size_t k = 0; k < bed_order[1].size(); ++k)
    col[static_cast<size_t>(bed_order[1][k])] = C - 1 - static_cast<int>(k);
  KnittingMap m(R, C, CellType::Collapsed);
  m.seam.assign(static_cast<size_t>(R), -1);
  std::set<uint32_t> carrier_sets;
  for (int r = 0; r < R; ++r) {
    const auto [i, j] = rows[static_cast<size_t>(r)];
    const int d = round_dir(i);
    m.direction[static_cast<size_t>(r)] = static_cast<int8_t>(d);
    int lo = C, hi = -1;
    for (int s = i; s <= j; ++s) {
      const int c = col[static_cast<size_t>(wale[static_cast<size_t>(s)])];
      m.at(r, c) = CellType::Knit;
      lo = std::min(lo, c), hi = std::max(hi, c);
      carrier_sets.insert(loop(s).carriers);
    }
    const int c0 = col[static_cast<size_t>(wale[static_cast<size_t>(i)])];
    if (is_round(i, j)) {
      m.seam[static_cast<size_t>(r)] = d > 0 ? c0 : (c0 + 1) % C;
    } else {
      if (lo == hi) return fmt::format("the short row of line {} has one stitch", loop(i).line);
      m.at(r, lo) = CellType::ShortRowLeft;
      m.at(r, hi) = CellType::ShortRowRight;
    }
  }
  for (int w = 0; w < W; ++w) {
    const int c = col[static_cast<size_t>(w)];
    CellType& f = m.at(row_of[static_cast<size_t>(first[static_cast<size_t>(w)])], c);
    if (f == CellType::Knit && row_of[static_cast<size_t>(first[static_cast<size_t>(w)])] > 0) f = CellType::Increase;
    CellType& l = m.at(row_of[static_cast<size_t>(last[static_cast<size_t>(w)])], c);
    if (l == CellType::Knit && row_of[static_cast<size_t>(last[static_cast<size_t>(w)])] < R - 1) l = CellType::Decrease;
  }
  if (carrier_sets.size() > 1)
    for (int s = 0; s < n; ++s)
      m.set_yarn(row_of[static_cast<size_t>(s)], col[static_cast<size_t>(wale[static_cast<size_t>(s)])],
                 std::max(0, loop(s).first_carrier()));
  // Closed at the end: a loop pulls through two loops of the last round
  // that are not neighbours in it (the closing seam; compare_knit_graph()
  // checks its pairs).
  {
    const auto [i, j] = rows.back();
    const int len = j - i + 1;
    for (int x = 0; x < g.num_loops() && !m.closed_end; ++x) {
      std::vector<int> at;
      for (int p : g.parents_of(x))
        if (in(index[static_cast<size_t>(p)], i, j)) at.push_back(index[static_cast<size_t>(p)] - i);
      for (size_t a = 0; a < at.size(); ++a)
        for (size_t b = a + 1; b < at.size(); ++b) {
          const int dist = std::abs(at[a] - at[b]);
          m.closed_end = m.closed_end || (dist != 1 && dist != len - 1);
        }
    }
    m.closed_end = m.closed_end && is_round(i, j);
  }

  const std::string why = accept_map(g, m);
  if (!why.empty()) return why;
  out.map = std::move(m);
  name_cells(S, out.map, out);
  // A plain tube: every row a round of the same stitches.
  bool plain = true;
  for (const auto& [i, j] : rows) plain = plain && is_round(i, j) && j - i == rows[0].second - rows[0].first;
  if (plain) {
    out.rounds = R;
    out.ring = rows[0].second - rows[0].first + 1;
    out.loop_of_round_stitch = S;
  }
  return {};
}

// The rounds of a plain tube knitted one bed after the other (front pass,
// back pass, ...), each stitch above the first round through the one below
// it, when the tube is no tubular map (e.g. a program that leaves its
// loops on the needles): sets out.rounds, ring, loop_of_round_stitch.
bool plain_rounds(const KnitGraph& g, const std::vector<int>& S, const std::vector<int>& primary,
                  const std::vector<Row>& rows, const std::vector<int>& row_of, KnitGraphFabric& out) {
  auto loop = [&](int s) -> const KnitLoop& { return g.loops[static_cast<size_t>(S[static_cast<size_t>(s)])]; };
  bool alternating = rows.size() >= 4 && rows.size() % 2 == 0;
  for (size_t r = 0; r < rows.size() && alternating; ++r) {
    const bool back = on_back(loop(rows[r].stitches.front()));
    for (int s : rows[r].stitches) alternating = alternating && on_back(loop(s)) == back;
    if (r > 0)  // the other bed, going the other way: round the tube
      alternating = alternating && back != on_back(loop(rows[r - 1].stitches.front())) && rows[r].dir != rows[r - 1].dir;
    for (int s : rows[r].stitches)
      if (primary[static_cast<size_t>(s)] >= 0 &&
          row_of[static_cast<size_t>(primary[static_cast<size_t>(s)])] + 1 == static_cast<int>(r))
        alternating = false;
  }
  if (!alternating) return false;
  const size_t n = rows[0].stitches.size() + rows[1].stitches.size();
  std::vector<int> ring_pos(S.size(), -1);
  std::vector<int> round_loops;
  for (size_t r = 0; r + 1 < rows.size(); r += 2) {
    if (rows[r].stitches.size() + rows[r + 1].stitches.size() != n) return false;
    int j = 0;
    for (size_t h = r; h <= r + 1; ++h) {
      for (int s : rows[h].stitches) {
        ring_pos[static_cast<size_t>(s)] = j++;
        round_loops.push_back(S[static_cast<size_t>(s)]);
        // every stitch above the first round continues the stitch below it
        const int p = primary[static_cast<size_t>(s)];
        if (r > 0 && (p < 0 || ring_pos[static_cast<size_t>(p)] != j - 1)) return false;
      }
    }
  }
  out.kind = "tube";
  out.rounds = static_cast<int>(rows.size() / 2);
  out.ring = static_cast<int>(n);
  out.loop_of_round_stitch = std::move(round_loops);
  return true;
}

// The fabric as a sheet's map (see the file comment, "Sheets"): sets
// out.map and returns "", or returns why it is none.
std::string sheet_fabric(const KnitGraph& g, const std::vector<int>& S, const std::vector<Row>& rows,
                         const std::vector<int>& row_of, const std::vector<int>& wale, int W, KnitGraphFabric& out) {
  auto loop = [&](int s) -> const KnitLoop& { return g.loops[static_cast<size_t>(S[static_cast<size_t>(s)])]; };
  // wales in their left-to-right order
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
      if (!seen.insert(w).second) return "one wale is knitted twice in one course";
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
  if (next_col < W) return "the wales cross (a cable or a tube): no left-to-right order of columns fits every course";

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
  const std::string why = accept_map(g, m);
  if (!why.empty()) return why;
  out.map = std::move(m);
  name_cells(S, out.map, out);
  return {};
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
  // Wales: a parent continues one wale; a second stitch through it (the old
  // loop of a split, knitted again after it moved) starts a new wale.
  std::vector<int> wale(S.size(), -1);
  std::vector<uint8_t> continued(S.size(), 0);
  int W = 0;
  for (size_t s = 0; s < S.size(); ++s) {
    const int p = primary[s];
    if (p >= 0 && !continued[static_cast<size_t>(p)]) {
      continued[static_cast<size_t>(p)] = 1;
      wale[s] = wale[static_cast<size_t>(p)];
    } else {
      wale[s] = W++;
    }
  }

  const std::vector<Row> rows = split_rows(g, S);
  std::vector<int> row_of(S.size(), -1);
  for (size_t r = 0; r < rows.size(); ++r)
    for (int s : rows[r].stitches) row_of[static_cast<size_t>(s)] = static_cast<int>(r);

  // Tubes: stitches on both beds.
  std::string tube_reason;
  bool beds[2] = {false, false};
  for (int l : S) beds[on_back(g.loops[static_cast<size_t>(l)]) ? 1 : 0] = true;
  if (beds[0] && beds[1]) {
    tube_reason = tube_fabric(g, S, index, wale, W, out);
    if (tube_reason.empty()) {
      out.kind = "tube";
      return out;
    }
    if (plain_rounds(g, S, primary, rows, row_of, out)) {
      out.reason = "no tubular map: " + tube_reason;
      return out;
    }
  }
  const std::string sheet_reason = sheet_fabric(g, S, rows, row_of, wale, W, out);
  if (sheet_reason.empty()) {
    out.kind = "sheet";
    return out;
  }
  out.map = KnittingMap();
  out.reason = tube_reason.empty() ? sheet_reason
                                   : fmt::format("neither a tube ({}) nor a sheet ({})", tube_reason, sheet_reason);
  return out;
}

}  // namespace knitforge
