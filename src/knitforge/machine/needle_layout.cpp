#include "knitforge/machine/needle_layout.h"

#include <algorithm>
#include <cstdlib>

#include <fmt/core.h>

#include "knitforge/convert/map_to_stitch_mesh.h"
#include "knitforge/util/errors.h"

namespace knitforge {

namespace {


// alive[r*cols+c]: stitch cell, or Collapsed cell between two stitches of its column.
std::vector<uint8_t> alive_cells(const KnittingMap& m) {
  std::vector<uint8_t> alive(m.cells.size(), 0);
  for (int c = 0; c < m.cols; ++c) {
    // nearest non-Collapsed cell below each row
    CellType below = CellType::Empty;
    std::vector<CellType> below_of(m.rows);
    for (int r = 0; r < m.rows; ++r) {
      below_of[r] = below;
      if (m.at(r, c) != CellType::Collapsed) below = m.at(r, c);
    }
    CellType above = CellType::Empty;
    for (int r = m.rows - 1; r >= 0; --r) {
      const CellType t = m.at(r, c);
      const size_t i = static_cast<size_t>(r) * m.cols + c;
      if (is_stitch(t)) {
        alive[i] = 1;
      } else if (t == CellType::Collapsed) {
        alive[i] = has_side(below_of[r], Side::Top) && has_side(above, Side::Bottom);
      }
      if (t != CellType::Collapsed) above = t;
    }
  }
  return alive;
}

int clamp_shift(int d, int t) { return d >= 0 ? std::min(d, t) : -std::min(-d, t); }

}  // namespace

NeedleLayout plan_needle_layout(const KnittingMap& map, const NeedleLayoutOptions& opt) {
  if (opt.max_shift < 1) throw InvalidInput("needle layout: max_shift must be >= 1");
  if (opt.max_stack < 2) throw InvalidInput("needle layout: max_stack must be >= 2");
  if (opt.max_closure_loops < 1) throw InvalidInput("needle layout: max_closure_loops must be >= 1");
  if (map.rows < 1 || map.cols < 1) throw InvalidInput("needle layout: the knitting map is empty");
  // Validates sizes, directions, one run per row, collapsed crossings,
  // degenerate stitches and manifoldness, with messages naming the cell.
  map_to_stitch_mesh_topology(map, KnitParams{});

  const int R = map.rows, C = map.cols;
  const std::vector<uint8_t> alive = alive_cells(map);
  auto is_alive = [&](int r, int c) { return alive[static_cast<size_t>(r) * C + c] != 0; };

  NeedleLayout L;
  L.rows = R;
  L.cols = C;
  L.needle.assign(static_cast<size_t>(R) * C, kNoNeedle);
  L.transitions.resize(R);
  L.first_col.assign(R, -1);
  L.last_col.assign(R, -1);
  L.closure_col.assign(R, -1);
  L.inside_turn.assign(R, 0);

  for (int r = 0; r < R; ++r)
    for (int c = 0; c < C; ++c)
      if (is_stitch(map.at(r, c))) {
        if (L.first_col[r] < 0) L.first_col[r] = c;
        L.last_col[r] = c;
      }

  std::vector<int> pos(C, kNoNeedle);  // current needle of each alive wale
  std::vector<int> loops(C, 0);        // loops on that needle
  {
    std::vector<int> w;
    for (int c = 0; c < C; ++c)
      if (is_alive(0, c)) w.push_back(c);
    const int n0 = static_cast<int>(w.size());
    for (int i = 0; i < n0; ++i) pos[w[i]] = i - n0 / 2;
    L.min_needle = pos[w.front()];
    L.max_needle = pos[w.back()];
  }
  auto track = [&](int n) {
    L.min_needle = std::min(L.min_needle, n);
    L.max_needle = std::max(L.max_needle, n);
  };

  std::vector<int> A, B, cont;
  for (int r = 0; r < R; ++r) {
    A.clear();
    for (int c = 0; c < C; ++c)
      if (is_alive(r, c)) {
        A.push_back(c);
        L.needle[static_cast<size_t>(r) * C + c] = pos[c];
      }
    // knitting row r renews the loops of its stitches
    for (int c = L.first_col[r]; c <= L.last_col[r]; ++c)
      if (is_stitch(map.at(r, c))) loops[c] = 1;
    if (r + 1 == R) break;

    // short-row turn after row r?
    const int dir = map.direction[r];
    const int end_col = dir > 0 ? L.last_col[r] : L.first_col[r];
    int held = -1;
    if (dir > 0) {
      for (int c = end_col + 1; c < C && held < 0; ++c)
        if (is_alive(r, c)) held = c;
    } else {
      for (int c = end_col - 1; c >= 0 && held < 0; --c)
        if (is_alive(r, c)) held = c;
    }
    if (held >= 0) {
      L.inside_turn[r] = 1;
      if (opt.close_turns && loops[held] + 1 <= opt.max_closure_loops) {
        L.closure_col[r] = held;
        ++loops[held];
      } else {
        ++L.open_turns;
      }
    }

    // transition r -> r+1
    LayoutTransition& T = L.transitions[r + 1];
    B.clear();
    cont.clear();
    for (int c = 0; c < C; ++c)
      if (is_alive(r + 1, c)) {
        B.push_back(c);
        if (is_alive(r, c)) cont.push_back(c);
        else T.starts.push_back(c);
      }
    if (cont.empty())
      throw InvalidInput(fmt::format(
          "knitting map rows {} and {} share no wale: the fabric would fall apart on the machine",
          r, r + 1));
    int pivot = cont.front();
    for (int c : cont) {
      const int a = std::abs(pos[c]), b = std::abs(pos[pivot]);
      if (a < b || (a == b && pos[c] < pos[pivot])) pivot = c;
    }
    T.pivot_col = pivot;
    T.pivot_needle = pos[pivot];
    std::vector<int> newpos(C, kNoNeedle);
    {
      const int ip = static_cast<int>(std::find(B.begin(), B.end(), pivot) - B.begin());
      for (int i = 0; i < static_cast<int>(B.size()); ++i) newpos[B[i]] = pos[pivot] + (i - ip);
    }
    // ending wales -> merge targets, or bind-off chains for runs of them
    std::vector<std::pair<int, int>> movers;  // (col, displacement)
    auto merge = [&](int c, int target) {
      if (loops[target] + loops[c] > opt.max_stack)
        throw InvalidInput(fmt::format(
            "knitting map row {}, column {}: the wale ends here but its loops cannot be merged "
            "onto a neighbour without stacking more than {} loops on one needle; end fewer "
            "neighbouring wales in the same course (at most one per neighbour)",
            r, c, opt.max_stack));
      loops[target] += loops[c];
      loops[c] = 0;
      T.merges.push_back({c, target});
      movers.emplace_back(c, newpos[target] - pos[c]);
      ++L.decreases;
    };
    // Runs of ending wales: consecutive in A (the alive wales of row r).
    for (size_t i = 0; i < A.size();) {
      if (is_alive(r + 1, A[i])) {
        ++i;
        continue;
      }
      size_t j = i;
      while (j + 1 < A.size() && !is_alive(r + 1, A[j + 1])) ++j;
      const std::vector<int> run(A.begin() + static_cast<long>(i), A.begin() + static_cast<long>(j) + 1);
      const int left = i > 0 ? A[i - 1] : -1;               // continuing, by maximality
      const int right = j + 1 < A.size() ? A[j + 1] : -1;
      const size_t k = run.size();
      i = j + 1;
      if (k == 1 || (k == 2 && left >= 0 && right >= 0)) {
        for (int c : run) {
          // nearest continuing wales left and right
          const int first = c < pivot ? right : left;
          const int second = c < pivot ? left : right;
          int target = -1;
          for (int t : {first, second})
            if (target < 0 && t >= 0 && loops[t] + loops[c] <= opt.max_stack) target = t;
          merge(c, target >= 0 ? target : (first >= 0 ? first : second));
        }
        continue;
      }
      // In knitting order: u[0] comes first in row r.
      const int d = map.direction[r];
      std::vector<int> u = run;
      if (d < 0) std::reverse(u.begin(), u.end());
      const int before = d > 0 ? left : right, after = d > 0 ? right : left;
      LayoutBindOff b;
      if (after >= 0) {
        // The chain runs with the row, onto the last wale of the run.
        b.during_row = true;
        b.cols.assign(u.begin() + (before >= 0 ? 1 : 0), u.end() - 1);
        b.onto_col = u.back();
        if (before >= 0) merge(u.front(), before);
        merge(u.back(), after);
      } else {
        // The run ends the row at the fabric edge: the chain runs back.
        b.cols.assign(u.rbegin(), u.rend() - 1);
        b.onto_col = u.front();
        ++loops[u.front()];
        merge(u.front(), before);
      }
      for (int c : b.cols) loops[c] = 0;
      L.bound_off += static_cast<int>(b.cols.size());
      T.bind_offs.push_back(std::move(b));
    }
    for (int c : cont)
      if (newpos[c] != pos[c]) movers.emplace_back(c, newpos[c] - pos[c]);
    std::sort(movers.begin(), movers.end(),
              [&](const auto& a, const auto& b) { return pos[a.first] < pos[b.first]; });
    int maxd = 0;
    for (const auto& m : movers) maxd = std::max(maxd, std::abs(m.second));
    const int K = (maxd + opt.max_shift - 1) / opt.max_shift;
    for (int k = 1; k <= K; ++k) {
      LayoutStep step;
      for (const auto& [c, d] : movers) {
        const int from = pos[c] + clamp_shift(d, (k - 1) * opt.max_shift);
        const int to = pos[c] + clamp_shift(d, k * opt.max_shift);
        if (from != to) {
          step.moves.push_back({c, from, to});
          track(to);
        }
      }
      std::sort(step.moves.begin(), step.moves.end(),
                [](const LayoutMove& a, const LayoutMove& b) { return a.from < b.from; });
      L.loop_moves += static_cast<int>(step.moves.size());
      T.steps.push_back(std::move(step));
    }
    for (const auto& m : T.merges) pos[m.col] = kNoNeedle;
    for (const auto& b : T.bind_offs)
      for (int c : b.cols) pos[c] = kNoNeedle;
    for (int c : B) {
      pos[c] = newpos[c];
      track(pos[c]);
    }
    for (int c : T.starts) loops[c] = 0;
    L.increases += static_cast<int>(T.starts.size());
  }
  return L;
}

}  // namespace knitforge
