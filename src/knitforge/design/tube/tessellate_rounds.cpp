#include "knitforge/design/tube/tessellate_rounds.h"

#include <algorithm>
#include <cmath>
#include <iterator>
#include <limits>

#include <fmt/format.h>

#include "knitforge/util/errors.h"

namespace knitforge {

namespace {

constexpr double kGolden = 0.6180339887498949;

int max_change(int half) { return std::max(1, half / 4); }

// Cyclic distance between positions a and b on a ring of n.
double ring_distance(double a, double b, int n) {
  const double d = std::fmod(std::abs(a - b), static_cast<double>(n));
  return std::min(d, n - d);
}

// Indices of `live` (one half's wales, sorted) to end: up to d of them,
// evenly spaced from `phase` (a fraction of the half), never the first or
// the last, never two side by side.
std::vector<int> choose_decreases(int c, int d, double phase) {
  std::vector<int> chosen;
  std::vector<char> taken(static_cast<size_t>(c), 0);
  for (int j = 0; j < d; ++j) {
    const double want = std::fmod((j + 0.5) * c / d + phase * c, static_cast<double>(c));
    int best = -1;
    double best_d = 0.0;
    for (int i = 1; i + 1 < c; ++i) {
      if (taken[static_cast<size_t>(i)] || taken[static_cast<size_t>(i - 1)] || taken[static_cast<size_t>(i + 1)])
        continue;
      const double dist = ring_distance(i, want, c);
      if (best < 0 || dist < best_d) best = i, best_d = dist;
    }
    if (best < 0) break;
    taken[static_cast<size_t>(best)] = 1;
    chosen.push_back(best);
  }
  // The nearest-first choice can block itself when d nears (c - 1) / 2:
  // then every other wale from 1, shifted by the phase within the room left.
  const int most = (c - 1) / 2;
  if (static_cast<int>(chosen.size()) < std::min(d, most)) {
    const int n = std::min(d, most), room = c - 1 - 2 * n;
    const int offset = std::min(room, static_cast<int>(std::floor(phase * (room + 1))));
    chosen.clear();
    for (int j = 0; j < n; ++j) chosen.push_back(1 + offset + 2 * j);
  }
  return chosen;
}

// New columns for up to d increases in a half [lo, hi) with live wales
// `live` (sorted, non-empty): one per gap, interior gaps first.
std::vector<int> choose_increases(const std::vector<int>& live, int lo, int hi, int d, double phase) {
  const int c = static_cast<int>(live.size());
  std::vector<int> out;
  std::vector<char> used(static_cast<size_t>(c) + 1, 0);  // gap g: before live[g] (g = 0: from lo; g = c: to hi)
  auto free_col = [&](int g) -> int {
    const int a = g == 0 ? lo - 1 : live[static_cast<size_t>(g - 1)];
    const int b = g == c ? hi : live[static_cast<size_t>(g)];
    if (b - a < 2) return -1;
    if (g == 0) return b - 1;  // next to the wale, as far from the fold as the gap allows
    if (g == c) return a + 1;
    return (a + b) / 2;
  };
  for (int pass = 0; pass < 2 && static_cast<int>(out.size()) < d; ++pass) {
    for (int j = static_cast<int>(out.size()); j < d; ++j) {
      const double want = std::fmod((j + 0.5) * c / d + phase * c, static_cast<double>(c));
      int best = -1;
      double best_d = 0.0;
      for (int g = pass == 0 ? 1 : 0; g <= (pass == 0 ? c - 1 : c); ++g) {
        if (used[static_cast<size_t>(g)] || free_col(g) < 0) continue;
        const double dist = ring_distance(g - 0.5, want, c);
        if (best < 0 || dist < best_d) best = g, best_d = dist;
      }
      if (best < 0) break;
      used[static_cast<size_t>(best)] = 1;
      out.push_back(free_col(best));
    }
  }
  return out;
}

}  // namespace

RoundWales round_wales(const std::vector<RoundCurve>& rounds, const KnitParams& params, bool equal_halves) {
  if (rounds.size() < 2) throw InvalidInput("tube tessellation: needs at least two rounds (the two rims)");
  if (!(params.stitch_width > 0.0) || !(params.stitch_height > 0.0))
    throw InvalidInput("tube tessellation: the stitch width and height must be positive");
  const int K = static_cast<int>(rounds.size()) - 1;  // rows of stitches
  RoundWales t;
  t.ideal.resize(rounds.size());
  int most = 0;
  for (size_t k = 0; k < rounds.size(); ++k) {
    t.ideal[k] = std::max(8, static_cast<int>(std::lround(rounds[k].length / params.stitch_width)));
    // The rims take their inner round's count (below), so they do not widen the map.
    if (K < 2 || (k > 0 && static_cast<int>(k) < K)) most = std::max(most, t.ideal[k]);
  }
  const int H = (most + 1) / 2, N = 2 * H;
  t.columns = N;

  // Live columns per round, per half.
  std::vector<std::vector<int>> live(rounds.size());
  auto spread = [&](int count, int lo) {
    std::vector<int> cols;
    for (int i = 0; i < count; ++i) cols.push_back(lo + static_cast<int>(std::floor((i + 0.5) * H / count)));
    return cols;
  };
  const int m1 = K >= 2 ? t.ideal[1] : t.ideal[0];
  {
    std::vector<int> f = spread((m1 + 1) / 2, 0), b = spread(m1 / 2, H);
    f.insert(f.end(), b.begin(), b.end());
    live[0] = f;
  }
  if (K >= 1) live[1] = live[0];
  // A closed tube: the most stitches round k may hold for the crown ring's
  // count to be reached at round K - 1 (a half of h can fall to h - (h - 1)
  // / 2 in one round, so round k - 1 may hold 2 m_k - 2).
  std::vector<int> cap(rounds.size(), std::numeric_limits<int>::max());
  if (equal_halves && K >= 2) {
    cap[static_cast<size_t>(K - 1)] = t.ideal[static_cast<size_t>(K)];
    for (int k = K - 2; k >= 1; --k)
      cap[static_cast<size_t>(k)] = std::min(1 << 20, 2 * cap[static_cast<size_t>(k + 1)] - 2);
  }
  int shaping_rows = 0;
  for (int k = 1; k + 1 < K; ++k) {
    // A closed tube's last row may not shape (rule boundary-apex), so the
    // round below the crown ring takes the ring's count (cap).
    const int want = std::min(t.ideal[static_cast<size_t>(k + 1)], cap[static_cast<size_t>(k + 1)]);
    std::vector<int> next;
    bool shaped = false;
    int front_next = 0;
    for (int half = 0; half < 2; ++half) {
      const int lo = half * H, hi = lo + H;
      std::vector<int> cols;
      for (int c : live[static_cast<size_t>(k)])
        if (c >= lo && c < hi) cols.push_back(c);
      const int c = static_cast<int>(cols.size());
      const int target = half == 0 ? (want + 1) / 2 : equal_halves ? front_next : want / 2;
      // A closed tube may decrease every other wale where its rounds narrow
      // fast (the crown): its last round must reach the asked count.
      const int fall = equal_halves ? std::max(max_change(c), (c - 1) / 2) : max_change(c);
      const int delta = std::clamp(target - c, -fall, max_change(c));
      const double phase = std::fmod(kGolden * (shaping_rows + 1) + 0.5 * half, 1.0);
      if (delta < 0 && c + delta >= 2) {
        std::vector<char> drop(static_cast<size_t>(c), 0);
        for (int i : choose_decreases(c, -delta, phase)) drop[static_cast<size_t>(i)] = 1;
        std::vector<int> kept;
        for (int i = 0; i < c; ++i)
          if (!drop[static_cast<size_t>(i)]) kept.push_back(cols[static_cast<size_t>(i)]);
        shaped = shaped || kept.size() != cols.size();
        cols = kept;
      } else if (delta > 0 && c > 0) {
        const std::vector<int> add = choose_increases(cols, lo, hi, delta, phase);
        shaped = shaped || !add.empty();
        cols.insert(cols.end(), add.begin(), add.end());
        std::sort(cols.begin(), cols.end());
      }
      next.insert(next.end(), cols.begin(), cols.end());
      if (half == 0) front_next = static_cast<int>(cols.size());
    }
    if (shaped) ++shaping_rows;
    live[static_cast<size_t>(k + 1)] = next;
  }
  if (K >= 2) live[static_cast<size_t>(K)] = live[static_cast<size_t>(K - 1)];
  if (equal_halves) {
    int front = 0;
    for (int c : live.back()) front += c < H ? 1 : 0;
    const int back = static_cast<int>(live.back().size()) - front;
    if (front != back)
      throw InvalidInput(fmt::format(
          "tube tessellation: the last round's halves hold {} and {} stitches, the closing seam needs them "
          "equal; "
          "the rounds narrow faster than the decreases can follow (at most every other wale per round): more "
          "crown stitches or a surface that narrows more slowly",
          front, back));
  }
  for (size_t k = 0; k < rounds.size(); ++k) t.stitches.push_back(static_cast<int>(live[k].size()));
  for (size_t k = 0; k + 1 < rounds.size(); ++k) {
    std::vector<int> gone, started;
    std::set_difference(live[k].begin(), live[k].end(), live[k + 1].begin(), live[k + 1].end(),
                        std::back_inserter(gone));
    std::set_difference(live[k + 1].begin(), live[k + 1].end(), live[k].begin(), live[k].end(),
                        std::back_inserter(started));
    t.decreases += static_cast<int>(gone.size());
    t.increases += static_cast<int>(started.size());
  }
  t.live = std::move(live);
  return t;
}

RoundsTessellation tessellate_rounds(const std::vector<RoundCurve>& rounds, const KnitParams& params,
                                     bool equal_halves) {
  RoundWales w = round_wales(rounds, params, equal_halves);
  const int K = static_cast<int>(rounds.size()) - 1, H = w.columns / 2, N = w.columns;
  const std::vector<std::vector<int>>& live = w.live;
  RoundsTessellation t;
  t.columns = N;
  t.ideal = std::move(w.ideal);

  // Vertices: one per stitch of each round.
  std::vector<int> first(rounds.size() + 1, 0);
  for (size_t k = 0; k < rounds.size(); ++k) {
    const int m = static_cast<int>(live[k].size());
    int front = 0;
    for (int c : live[k]) front += c < H ? 1 : 0;
    t.stitches.push_back(m);
    const std::vector<Vec3> pts = sample_round(rounds[k], m, front);
    t.mesh.vertices.insert(t.mesh.vertices.end(), pts.begin(), pts.end());
    first[k + 1] = first[k] + m;
  }
  // Stitches, row by row in column order from the seam.
  for (int r = 0; r < K; ++r) {
    const std::vector<int>& lb = live[static_cast<size_t>(r)];
    const std::vector<int>& lt = live[static_cast<size_t>(r + 1)];
    const int mb = static_cast<int>(lb.size()), mt = static_cast<int>(lt.size());
    auto bv = [&](int i) { return first[static_cast<size_t>(r)] + i % mb; };
    auto tv = [&](int j) { return first[static_cast<size_t>(r + 1)] + j % mt; };
    int i = 0, j = 0;
    while (i < mb || j < mt) {
      const int cb = i < mb ? lb[static_cast<size_t>(i)] : N, ct = j < mt ? lt[static_cast<size_t>(j)] : N;
      Stitch s;
      s.course = r;
      s.direction = 1;
      if (cb == ct) {
        s.type = StitchType::Knit;
        s.wale = cb;
        s.v = {bv(i), bv(i + 1), tv(j + 1), tv(j)};
        ++i, ++j;
      } else if (cb < ct) {
        s.type = StitchType::Decrease;
        s.wale = cb;
        s.v = {bv(i), bv(i + 1), tv(j), -1};
        ++i;
        ++t.decreases;
      } else {
        s.type = StitchType::Increase;
        s.wale = ct;
        s.v = {bv(i), tv(j + 1), tv(j), -1};
        ++j;
        ++t.increases;
      }
      t.mesh.stitches.push_back(s);
    }
  }
  return t;
}

}  // namespace knitforge
