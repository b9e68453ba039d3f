#include "knitforge/machine/tube_layout.h"

#include <algorithm>
#include <cstdlib>

#include <fmt/core.h>

#include "knitforge/util/errors.h"

namespace knitforge {

TubeLayout plan_tube_layout(const KnittingMap& map, const TubeLayoutOptions& opt) {
  if (!map.tubular()) throw InvalidInput("tube layout: the knitting map is not a tube (it has no seam column)");
  if (opt.max_racking < 2)
    throw InvalidInput(fmt::format("tube layout: racking limit {}; shaping a tube on every other needle needs "
                                   "racking 2 (one slot)",
                                   opt.max_racking));
  if (opt.max_stack < 2) throw InvalidInput("tube layout: max_stack must be >= 2");
  if (opt.max_closure_loops < 1) throw InvalidInput("tube layout: max_closure_loops must be >= 1");
  if (map.rows < 1 || map.cols < 4 || map.cols % 2 != 0)
    throw InvalidInput(fmt::format("tube layout: a tube needs at least one row and an even number (>= 4) of "
                                   "columns; the map is {} x {}",
                                   map.rows, map.cols));
  const WaleTakers takers(map);  // validates the map, naming the cell
  const std::vector<uint8_t> alive = alive_wales(map);
  const int R = map.rows, C = map.cols, h = map.tube_half();
  const int shift = opt.max_racking / 2;  // slots per transfer step
  auto is_alive = [&](int r, int c) { return alive[static_cast<size_t>(r) * C + c] != 0; };
  // The wales of one bed alive at row r, in slot order (front: columns left
  // to right; back: from the left fold, i.e. column cols-1, to column h).
  auto bed_wales = [&](int r, bool back) {
    std::vector<int> w;
    if (!back) {
      for (int c = 0; c < h; ++c)
        if (is_alive(r, c)) w.push_back(c);
    } else {
      for (int c = C - 1; c >= h; --c)
        if (is_alive(r, c)) w.push_back(c);
    }
    return w;
  };
  auto needle_of = [&](int c, int slot) { return c >= h ? 2 * slot + 1 : 2 * slot; };

  TubeLayout L;
  L.rows = R;
  L.cols = C;
  L.needle.assign(static_cast<size_t>(R) * C, kNoNeedle);
  L.transitions.resize(static_cast<size_t>(R));
  L.closure_col.assign(static_cast<size_t>(R), -1);
  L.inside_turn.assign(static_cast<size_t>(R), 0);

  std::vector<int> pos(static_cast<size_t>(C), kNoNeedle);  // slot of each alive wale
  std::vector<int> loops(static_cast<size_t>(C), 0);
  std::vector<int> last_row(static_cast<size_t>(C), -1);
  std::vector<std::vector<int>> tucks_on(static_cast<size_t>(C));
  for (bool back : {false, true}) {
    const std::vector<int> w = bed_wales(0, back);
    const int n = static_cast<int>(w.size());
    for (int i = 0; i < n; ++i) pos[static_cast<size_t>(w[static_cast<size_t>(i)])] = i - n / 2;
  }
  bool first_track = true;
  auto track = [&](int n) {
    if (first_track) L.min_needle = L.max_needle = n, first_track = false;
    L.min_needle = std::min(L.min_needle, n);
    L.max_needle = std::max(L.max_needle, n);
  };

  for (int r = 0; r < R; ++r) {
    for (int c = 0; c < C; ++c)
      if (is_alive(r, c)) {
        const int n = needle_of(c, pos[static_cast<size_t>(c)]);
        L.needle[static_cast<size_t>(r) * C + c] = n;
        track(n);
      }
    for (int c = 0; c < C; ++c)
      if (is_stitch(map.at(r, c))) {
        loops[static_cast<size_t>(c)] = 1;
        last_row[static_cast<size_t>(c)] = r;
        tucks_on[static_cast<size_t>(c)].clear();
      }
    if (r + 1 == R) break;

    // A short row that turns: the first held wale beyond its end closes it.
    const int d = map.direction[static_cast<size_t>(r)];
    if (!map.closed(r) && map.direction[static_cast<size_t>(r) + 1] != d) {
      L.inside_turn[static_cast<size_t>(r)] = 1;
      int end = -1;
      for (int c : row_columns(map, r))
        if (is_stitch(map.at(r, c))) end = c;
      int held = -1;
      for (int k = 1; k < C && held < 0; ++k) {
        const int c = ((end + d * k) % C + C) % C;
        if (is_stitch(map.at(r, c))) break;
        if (is_alive(r, c)) held = c;
      }
      if (held >= 0 && opt.close_turns && loops[static_cast<size_t>(held)] + 1 <= opt.max_closure_loops) {
        L.closure_col[static_cast<size_t>(r)] = held;
        ++loops[static_cast<size_t>(held)];
        tucks_on[static_cast<size_t>(held)].push_back(r);
      } else {
        ++L.open_turns;
      }
    }

    TubeTransition& T = L.transitions[static_cast<size_t>(r) + 1];
    std::vector<int> newpos(static_cast<size_t>(C), kNoNeedle);
    std::vector<std::pair<int, int>> movers;  // (wale, slot displacement)
    std::vector<int> ended;
    for (bool back : {false, true}) {
      const std::vector<int> A = bed_wales(r, back), B = bed_wales(r + 1, back);
      std::vector<int> cont;
      for (int c : B) {
        if (is_alive(r, c)) cont.push_back(c);
        else T.starts.push_back(c);
      }
      if (cont.empty()) {
        if (!A.empty() || !B.empty())
          L.problems.push_back({r, A.empty() ? B.front() : A.front(),
                                fmt::format("tube rows {} and {} share no wale on the {} bed: its half of the tube "
                                            "would fall apart; keep at least one wale of each half going on",
                                            r, r + 1, back ? "back" : "front")});
        for (int c : A) ended.push_back(c);
        continue;
      }
      int pivot = cont.front();
      for (int c : cont) {
        const int a = std::abs(pos[static_cast<size_t>(c)]), b = std::abs(pos[static_cast<size_t>(pivot)]);
        if (a < b || (a == b && pos[static_cast<size_t>(c)] < pos[static_cast<size_t>(pivot)])) pivot = c;
      }
      const int ip = static_cast<int>(std::find(B.begin(), B.end(), pivot) - B.begin());
      for (int i = 0; i < static_cast<int>(B.size()); ++i)
        newpos[static_cast<size_t>(B[static_cast<size_t>(i)])] = pos[static_cast<size_t>(pivot)] + (i - ip);
      for (int c : cont)
        if (newpos[static_cast<size_t>(c)] != pos[static_cast<size_t>(c)])
          movers.emplace_back(c, newpos[static_cast<size_t>(c)] - pos[static_cast<size_t>(c)]);
      // Ending wales merge onto a wale of their bed that takes their loop.
      for (size_t i = 0; i < A.size(); ++i) {
        const int c = A[i];
        if (is_alive(r + 1, c)) continue;
        ended.push_back(c);
        const std::vector<int> t = takers.takers(last_row[static_cast<size_t>(c)], c, r);
        // the nearest continuing wales before and after c in slot order
        int before = -1, after = -1;
        for (size_t j = i; j-- > 0;)
          if (is_alive(r + 1, A[j])) {
            before = A[j];
            break;
          }
        for (size_t j = i + 1; j < A.size(); ++j)
          if (is_alive(r + 1, A[j])) {
            after = A[j];
            break;
          }
        const bool towards_after = pos[static_cast<size_t>(c)] < pos[static_cast<size_t>(pivot)];
        int target = -1;
        for (int w : {towards_after ? after : before, towards_after ? before : after}) {
          if (target >= 0 || w < 0 || !std::binary_search(t.begin(), t.end(), w)) continue;
          if (loops[static_cast<size_t>(w)] + loops[static_cast<size_t>(c)] <= opt.max_stack) target = w;
        }
        if (target < 0) {
          L.problems.push_back(
              {last_row[static_cast<size_t>(c)], c,
               t.empty()
                   ? fmt::format("tube row {}, column {}: the wale ends but no later stitch takes its loop (a free "
                                 "top); a tube has no edge to bind it off along: end it with a decrease",
                                 last_row[static_cast<size_t>(c)], c)
                   : fmt::format("tube row {}, column {}: the wale ends but no neighbouring wale on the {} bed can "
                                 "take its loop (it lies across the fold, or its needle would hold more than {} "
                                 "loops); move the decrease away from the fold or end fewer wales there",
                                 last_row[static_cast<size_t>(c)], c, back ? "back" : "front", opt.max_stack)});
          continue;
        }
        loops[static_cast<size_t>(target)] += loops[static_cast<size_t>(c)];
        loops[static_cast<size_t>(c)] = 0;
        T.merges.push_back({c, target});
        movers.emplace_back(c, newpos[static_cast<size_t>(target)] - pos[static_cast<size_t>(c)]);
      }
    }
    std::sort(T.starts.begin(), T.starts.end());
    std::sort(T.merges.begin(), T.merges.end(),
              [](const LayoutMerge& a, const LayoutMerge& b) { return a.col < b.col; });
    L.decreases += static_cast<int>(T.merges.size());
    L.increases += static_cast<int>(T.starts.size());

    int maxd = 0;
    for (const auto& m : movers) maxd = std::max(maxd, std::abs(m.second));
    const int K = (maxd + shift - 1) / shift;
    auto clamp_shift = [](int dd, int t) { return dd >= 0 ? std::min(dd, t) : -std::min(-dd, t); };
    for (int k = 1; k <= K; ++k) {
      std::vector<TubeMove> step;
      for (const auto& [c, dd] : movers) {
        const int p = pos[static_cast<size_t>(c)];
        const int from = needle_of(c, p + clamp_shift(dd, (k - 1) * shift));
        const int to = needle_of(c, p + clamp_shift(dd, k * shift));
        if (from != to) {
          step.push_back({c, c >= h, from, to});
          track(to);
          // the loop waits on the other bed's needle `from` (same number)
        }
      }
      std::sort(step.begin(), step.end(), [](const TubeMove& a, const TubeMove& b) {
        return a.back != b.back ? !a.back : a.from < b.from;
      });
      L.loop_moves += static_cast<int>(step.size());
      T.steps.push_back(std::move(step));
    }
    for (int c : ended) pos[static_cast<size_t>(c)] = kNoNeedle;
    for (int c = 0; c < C; ++c)
      if (is_alive(r + 1, c)) pos[static_cast<size_t>(c)] = newpos[static_cast<size_t>(c)];
    for (int c : T.starts) {
      loops[static_cast<size_t>(c)] = 0;
      tucks_on[static_cast<size_t>(c)].clear();
    }
  }
  return L;
}

}  // namespace knitforge
