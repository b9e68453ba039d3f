#include "knitforge/machine/needle_layout.h"

#include <algorithm>
#include <cstdlib>

#include <fmt/core.h>
#include <fmt/format.h>

#include "knitforge/convert/map_to_stitch_mesh.h"
#include "knitforge/util/errors.h"

namespace knitforge {

namespace {

int clamp_shift(int d, int t) { return d >= 0 ? std::min(d, t) : -std::min(-d, t); }

}  // namespace

std::vector<uint8_t> alive_wales(const KnittingMap& m) {
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

WaleTakers::WaleTakers(const KnittingMap& map) : cols_(map.cols) {
  // Validates sizes, directions, one run per row, collapsed crossings,
  // degenerate stitches and manifoldness, with messages naming the cell.
  mesh_ = map_to_stitch_mesh_topology(map, KnitParams{});
  cell_stitch_.assign(map.cells.size(), -1);
  bottom_users_.resize(static_cast<size_t>(mesh_.num_vertices()));
  for (int s = 0; s < mesh_.num_stitches(); ++s) {
    const Stitch& st = mesh_.stitches[static_cast<size_t>(s)];
    cell_stitch_[static_cast<size_t>(st.course) * cols_ + st.wale] = s;
    for (int v : bottom_vertices(st)) bottom_users_[static_cast<size_t>(v)].push_back(s);
  }
}

std::vector<int> WaleTakers::takers(int row, int col, int after_row) const {
  std::vector<int> w;
  const int s = cell_stitch_[static_cast<size_t>(row) * cols_ + col];
  if (s < 0) return w;
  for (int v : top_vertices(mesh_.stitches[static_cast<size_t>(s)])) {
    for (int u : bottom_users_[static_cast<size_t>(v)]) {
      const Stitch& t = mesh_.stitches[static_cast<size_t>(u)];
      if (t.course > after_row && t.wale != col) w.push_back(t.wale);
    }
  }
  std::sort(w.begin(), w.end());
  w.erase(std::unique(w.begin(), w.end()), w.end());
  return w;
}

NeedleLayout plan_needle_layout(const KnittingMap& map, const NeedleLayoutOptions& opt) {
  if (opt.max_shift < 1) throw InvalidInput("needle layout: max_shift must be >= 1");
  if (opt.max_stack < 2) throw InvalidInput("needle layout: max_stack must be >= 2");
  if (opt.max_closure_loops < 1) throw InvalidInput("needle layout: max_closure_loops must be >= 1");
  if (map.rows < 1 || map.cols < 1) throw InvalidInput("needle layout: the knitting map is empty");
  if (map.tubular())
    throw InvalidInput("needle layout: the knitting map is a tube; its layout is plan_tube_layout() (tube_layout.h)");
  const WaleTakers takers(map);

  const int R = map.rows, C = map.cols;
  const std::vector<uint8_t> alive = alive_wales(map);
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
  std::vector<int> last_row(C, -1);    // row of each wale's latest stitch
  std::vector<std::vector<int>> tucks_on(C);  // rows whose closure tuck sits on the wale's needle
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
  // Takes back closure tucks on wale c's needle (latest first) until `need`
  // loops fewer sit there or none is left; returns how many were taken back.
  auto give_up_tucks = [&](int c, int need) {
    int n = 0;
    while (n < need && !tucks_on[c].empty()) {
      const int q = tucks_on[c].back();
      tucks_on[c].pop_back();
      L.closure_col[q] = -1;
      ++L.open_turns;
      --loops[c];
      ++n;
    }
    return n;
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
      if (is_stitch(map.at(r, c))) {
        loops[c] = 1;
        last_row[c] = r;
        tucks_on[c].clear();
      }
    if (r + 1 == R) break;

    // short-row turn after row r?
    const int dir = map.direction[r];
    const int end_col = dir > 0 ? L.last_col[r] : L.first_col[r];
    const int start_col = dir > 0 ? L.first_col[r] : L.last_col[r];
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
        tucks_on[held].push_back(r);
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

    // Ending wales, their takers (continuing wales whose later stitches touch
    // their top; empty = a free top), and the merge candidates in order.
    std::vector<int> ending;
    std::vector<std::vector<int>> cand;
    std::vector<uint8_t> is_free;
    for (int c : A) {
      if (is_alive(r + 1, c)) continue;
      std::vector<int> t;
      for (int w : takers.takers(last_row[c], c, r))
        if (std::binary_search(cont.begin(), cont.end(), w)) t.push_back(w);
      auto right_it = std::upper_bound(cont.begin(), cont.end(), c);
      const int right = right_it == cont.end() ? -1 : *right_it;
      const int left = right_it == cont.begin() ? -1 : *(right_it - 1);
      const int first = c < pivot ? right : left;
      const int second = c < pivot ? left : right;
      std::vector<int> order;
      for (int w : {first, second}) {
        if (w >= 0 && (t.empty() || std::find(t.begin(), t.end(), w) != t.end())) order.push_back(w);
      }
      ending.push_back(c);
      cand.push_back(order);
      is_free.push_back(t.empty());
    }
    // Free ending wales (no later stitch touches their top) cannot merge onto
    // a neighbour without knitting a fabric the map does not describe: they
    // are bound off by chains. Runs of them along row r, in its direction.
    std::vector<int> chained;  // wales bound off by a chain at this transition
    {
      std::vector<int> order;  // row r's stitches in knitting order
      for (int c = start_col; c >= L.first_col[r] && c <= L.last_col[r]; c += dir)
        if (is_stitch(map.at(r, c))) order.push_back(c);
      auto free_ending = [&](int c) {
        const auto it = std::find(ending.begin(), ending.end(), c);
        return it != ending.end() && is_free[static_cast<size_t>(it - ending.begin())];
      };
      for (size_t i = 0; i < order.size();) {
        if (!free_ending(order[i])) {
          ++i;
          continue;
        }
        size_t j = i;
        while (j < order.size() && free_ending(order[j])) ++j;
        if (j == order.size()) {
          // the row's last stitch ends its wale: the next course cannot start
          // there (check_knittability() reports it as between-row-continuity)
          L.problems.push_back({r, order[i],
                                fmt::format("knitting map row {}: its last stitches (from column {}) end their "
                                            "wales, so the next course cannot start where this one ends",
                                            r, order[i])});
          break;
        }
        LayoutChain ch;
        ch.row = r;
        ch.cols.assign(order.begin() + static_cast<long>(i), order.begin() + static_cast<long>(j));
        ch.onto_col = order[j];
        for (int c : ch.cols) {
          chained.push_back(c);
          loops[c] = 0;
        }
        L.chained += static_cast<int>(ch.cols.size());
        L.chains.push_back(std::move(ch));
        i = j;
      }
    }
    std::vector<LayoutMerge> merges;

    // Assigns merge targets to the ending wales not chained; returns false
    // when some fit nowhere (listed in fails). Loop counts change on success.
    auto assign = [&](std::vector<int>& fails) {
      std::vector<int> trial = loops;
      merges.clear();
      fails.clear();
      for (size_t i = 0; i < ending.size(); ++i) {
        const int c = ending[i];
        if (std::find(chained.begin(), chained.end(), c) != chained.end()) continue;
        int target = -1;
        for (int t : cand[i])
          if (target < 0 && trial[t] + trial[c] <= opt.max_stack) target = t;
        if (target < 0) {
          fails.push_back(c);
          continue;
        }
        trial[target] += trial[c];
        trial[c] = 0;
        merges.push_back({c, target});
      }
      if (fails.empty()) loops = trial;
      return fails.empty();
    };
    std::vector<int> fails;
    if (!assign(fails)) {
      // Take back closure tucks that make the stacks overflow.
      for (int c : fails) {
        const auto i = static_cast<size_t>(std::find(ending.begin(), ending.end(), c) - ending.begin());
        for (int t : cand[i]) {
          const int over = loops[t] + loops[c] - opt.max_stack;
          if (over > 0 && over <= static_cast<int>(tucks_on[c].size() + tucks_on[t].size())) {
            const int n = give_up_tucks(c, over);
            give_up_tucks(t, over - n);
            break;
          }
        }
      }
      if (!assign(fails)) {
        for (int c : fails) {
          L.problems.push_back(
              {r, c,
               fmt::format("knitting map row {}, column {}: the wale ends here but its loops cannot be merged onto "
                           "the neighbouring wale that takes them without stacking more than {} loops on one needle; "
                           "end fewer neighbouring wales in the same course",
                           r, c, opt.max_stack)});
        }
        // go on with the best merges so the rest of the layout is planned
        for (size_t i = 0; i < ending.size(); ++i) {
          const int c = ending[i];
          if (std::find(fails.begin(), fails.end(), c) != fails.end() && !cand[i].empty())
            merges.push_back({c, cand[i].front()});
        }
        for (const auto& m : merges) {
          loops[m.onto_col] += loops[m.col];
          loops[m.col] = 0;
        }
      }
    }
    std::sort(merges.begin(), merges.end(), [](const LayoutMerge& a, const LayoutMerge& b) { return a.col < b.col; });
    T.merges = merges;
    L.decreases += static_cast<int>(merges.size() + chained.size());

    std::vector<std::pair<int, int>> movers;  // (col, displacement)
    for (const auto& m : merges) movers.emplace_back(m.col, newpos[m.onto_col] - pos[m.col]);
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
    for (int c : chained) pos[c] = kNoNeedle;
    for (int c : B) {
      pos[c] = newpos[c];
      track(pos[c]);
    }
    for (int c : T.starts) {
      loops[c] = 0;
      tucks_on[c].clear();
    }
    L.increases += static_cast<int>(T.starts.size());
  }
  return L;
}

}  // namespace knitforge
