#include "knitforge/design/tube/tube_short_rows.h"

#include <algorithm>
#include <cmath>
#include <tuple>

#include "knitforge/convert/map_to_stitch_mesh.h"
#include "knitforge/util/errors.h"

namespace knitforge {

namespace {

// Place of each live wale round its round: its fraction of the arc length
// from the seam, front half on [0, 1/2), back half on [1/2, 1) (sample_round()).
std::vector<double> wale_fractions(const std::vector<int>& live, int half) {
  const int n = static_cast<int>(live.size());
  const int front = static_cast<int>(std::count_if(live.begin(), live.end(), [&](int c) { return c < half; }));
  std::vector<double> f(static_cast<size_t>(n));
  for (int i = 0; i < n; ++i)
    f[static_cast<size_t>(i)] = i < front ? 0.5 * i / front : 0.5 + 0.5 * (i - front) / (n - front);
  return f;
}

// One map row: a round of full-round interval k, or a short row of the
// wedge before it (wale indices lo..hi of round k's live wales).
// Fraction of the arc length from the round's start to its point nearest p.
double fraction_of(const RoundCurve& round, const Vec3& p) {
  double best = 1e300, at = 0.0, walked = 0.0;
  const size_t n = round.points.size();
  for (size_t i = 0; i < n; ++i) {
    const double dist = (round.points[i] - p).squaredNorm();
    if (dist < best) best = dist, at = walked;
    walked += (round.points[(i + 1) % n] - round.points[i]).norm();
  }
  return round.length > 0.0 ? at / round.length : 0.0;
}

struct PlannedRow {
  int k = 0;
  bool round = true;
  int direction = 1, lo = 0, hi = 0, seam = -1;
};

}  // namespace

TubeShortRows tube_short_rows(const TriMesh& mesh, const TubeField& field, const TubeShortRowOptions& o) {
  const double sh = o.params.stitch_height;
  if (!(sh > 0.0) || !(o.params.stitch_width > 0.0))
    throw InvalidInput("tube short rows: the stitch width and height must be positive");
  TubeShortRows out;
  // 1. The table, then again with the seam on the inside line.
  {
    const TubeSpacing first = tube_spacing(mesh, field, o.table_levels, o.table_fractions);
    double at = static_cast<double>(first.inside_fraction) / first.fractions;
    if (!o.seam_choices.empty()) {
      const double outside = static_cast<double>(first.outside_fraction) / first.fractions;
      // The outside line three quarters of the way round from the seam: the
      // middle of the back half, where a wedge's first short row (from the
      // seam back to the wedge) is shortest without the wedge reaching the
      // seam.
      double off = 2.0;
      for (const Vec3& p : o.seam_choices) {
        const double f = fraction_of(first.curves[0], p);
        const double rel = outside - f - std::floor(outside - f);
        if (std::abs(rel - 0.75) < off - 1e-9) off = std::abs(rel - 0.75), at = f;
      }
    }
    const Vec3 start = round_point_at(first.curves[0], at);
    out.spacing = tube_spacing(mesh, field, o.table_levels, o.table_fractions, start);
  }
  const TubeSpacing& sp = out.spacing;
  const Vec3 start = sp.curves[0].points[0];

  // 2. Full rounds by the smallest distance.
  const double total = sp.inside.back();
  const int K = std::max(1, static_cast<int>(std::lround(total / sh)));
  out.levels.resize(static_cast<size_t>(K) + 1);
  out.levels.front() = 0.0;
  out.levels.back() = 1.0;
  for (int k = 1; k < K; ++k) out.levels[static_cast<size_t>(k)] = sp.level_of_inside(total * k / K);
  out.rounds = tube_round_curves(mesh, field, out.levels, start);
  out.wales = round_wales(out.rounds, o.params, o.equal_halves);
  const int N = out.wales.columns, H = N / 2;
  const auto& live = out.wales.live;

  // 3. Wedges.
  std::vector<PlannedRow> rows;
  // Wedge rows each wale has had so far (a new wale takes its left neighbour's).
  std::vector<int> extra(static_cast<size_t>(N), 0);
  const double h_in = total / K;  // the full rounds' spacing on the inside line
  int seam = -1, first_seam = -1;
  rows.push_back({0, true, 1, 0, 0, -1});
  for (int k = 1; k < K; ++k) {
    const std::vector<int>& lk = live[static_cast<size_t>(k)];
    const int n = static_cast<int>(lk.size());
    for (int i = 0; i < n; ++i) {
      const std::vector<int>& lb = live[static_cast<size_t>(k) - 1];
      if (!std::binary_search(lb.begin(), lb.end(), lk[static_cast<size_t>(i)]))
        extra[static_cast<size_t>(lk[static_cast<size_t>(i)])] = extra[static_cast<size_t>(lk[static_cast<size_t>((i + n - 1) % n)])];
    }
    const std::vector<double> fr = wale_fractions(lk, H);
    const double u1 = out.levels[static_cast<size_t>(k) + 1];
    std::vector<int> depth(static_cast<size_t>(n), 0);
    std::vector<double> excess(static_cast<size_t>(n), 0.0);
    int peak = 0;
    for (int i = 0; i < n; ++i) {
      const double f = fr[static_cast<size_t>(i)];
      excess[static_cast<size_t>(i)] =
          (sp.along_at(f, u1) - sp.inside_at(u1)) / h_in - extra[static_cast<size_t>(lk[static_cast<size_t>(i)])];
      depth[static_cast<size_t>(i)] = std::max(0, static_cast<int>(std::floor((excess[static_cast<size_t>(i)] + 1.0) / 2.0)));
      if (std::tie(depth[static_cast<size_t>(i)], excess[static_cast<size_t>(i)]) >
          std::tie(depth[static_cast<size_t>(peak)], excess[static_cast<size_t>(peak)]))
        peak = i;
    }
    std::vector<std::pair<int, int>> arcs;  // nested, outermost first (wale indices)
    for (int t = 1; t <= depth[static_cast<size_t>(peak)]; ++t) {
      int l = peak, r = peak;
      while (l > 0 && depth[static_cast<size_t>(l - 1)] >= t) --l;
      while (r + 1 < n && depth[static_cast<size_t>(r + 1)] >= t) ++r;
      // Never the first or the last wale (beside the seam): the wedge's first
      // short row runs from the seam back to it and may not cover the round.
      l = std::max(l, 1);
      r = std::min(r, n - 2);
      // Strictly inside the arc before: two turn pairs in one wale cannot
      // both be closed (rule stacked-short-row-ends); the rest waits for
      // the next rounds.
      if (!arcs.empty()) {
        l = std::max(l, arcs.back().first + 1);
        r = std::min(r, arcs.back().second - 1);
      }
      if (r - l < 1) break;
      arcs.emplace_back(l, r);
    }
    if (arcs.empty()) {
      rows.push_back({k, true, 1, 0, 0, -1});
      continue;
    }
    // Where the round before ends: the wedge starts there.
    int in = arcs[0].second;
    if (seam >= 0) {
      std::vector<int> cells = live[static_cast<size_t>(k) - 1];
      cells.insert(cells.end(), lk.begin(), lk.end());
      std::sort(cells.begin(), cells.end());
      auto it = std::lower_bound(cells.begin(), cells.end(), seam);
      const int last = it == cells.begin() ? cells.back() : *(it - 1);
      auto at = std::lower_bound(lk.begin(), lk.end(), last);
      if (at == lk.end() || *at != last || at == lk.begin()) {  // ended on a decrease, or at the fold: later
        rows.push_back({k, true, 1, 0, 0, -1});
        continue;
      }
      in = static_cast<int>(at - lk.begin());
    }
    arcs[0].first = std::min(arcs[0].first, in - 1);
    const int m = static_cast<int>(arcs.size());
    std::vector<PlannedRow> wedge;
    wedge.push_back({k, false, -1, arcs[0].first, in, -1});
    for (int t = 0; t + 1 < m; ++t) {
      wedge.push_back({k, false, 1, arcs[static_cast<size_t>(t)].first, arcs[static_cast<size_t>(t) + 1].second, -1});
      wedge.push_back({k, false, -1, arcs[static_cast<size_t>(t) + 1].first, arcs[static_cast<size_t>(t) + 1].second, -1});
    }
    wedge.push_back({k, false, 1, arcs[static_cast<size_t>(m) - 1].first, arcs[0].second, -1});
    for (const PlannedRow& w : wedge)
      for (int i = w.lo; i <= w.hi; ++i) ++extra[static_cast<size_t>(lk[static_cast<size_t>(i)])];
    rows.insert(rows.end(), wedge.begin(), wedge.end());
    rows.push_back({k, true, 1, 0, 0, -1});
    if (first_seam < 0) first_seam = (lk[static_cast<size_t>(in)] + 1) % N;
    seam = (lk[static_cast<size_t>(arcs[0].second)] + 1) % N;
    ++out.wedges;
    out.short_rows += static_cast<int>(wedge.size());
    out.turns += static_cast<int>(wedge.size()) - 1;
  }
  if (out.wedges == 0) return out;

  // 4. The map.
  const int R = static_cast<int>(rows.size());
  KnittingMap& map = out.plan;
  map = KnittingMap(R, N, CellType::Collapsed);
  map.seam.assign(static_cast<size_t>(R), -1);
  int s = first_seam;
  for (int r = 0; r < R; ++r) {
    const PlannedRow& p = rows[static_cast<size_t>(r)];
    const std::vector<int>& lk = live[static_cast<size_t>(p.k)];
    map.direction[static_cast<size_t>(r)] = p.direction;
    if (p.round) {
      const std::vector<int>& up = live[static_cast<size_t>(p.k) + 1];
      for (int c = 0; c < N; ++c) {
        const bool a = std::binary_search(lk.begin(), lk.end(), c), b = std::binary_search(up.begin(), up.end(), c);
        map.at(r, c) = a && b ? CellType::Knit : a ? CellType::Decrease : b ? CellType::Increase : CellType::Collapsed;
      }
      map.seam[static_cast<size_t>(r)] = s;
    } else {
      for (int i = p.lo; i <= p.hi; ++i) map.at(r, lk[static_cast<size_t>(i)]) = CellType::Knit;
      map.at(r, lk[static_cast<size_t>(p.lo)]) = CellType::ShortRowLeft;
      map.at(r, lk[static_cast<size_t>(p.hi)]) = CellType::ShortRowRight;
      if (p.direction > 0) s = (lk[static_cast<size_t>(p.hi)] + 1) % N;
    }
  }

  // 5. Topology and positions.
  out.mesh = map_to_stitch_mesh_topology(map, o.params);
  // Stitches of each column below each grid row (a new wale starts with its
  // left neighbour's count).
  std::vector<std::vector<int>> below(static_cast<size_t>(R) + 1, std::vector<int>(static_cast<size_t>(N), 0));
  for (int r = 0; r < R; ++r) {
    std::vector<int>& b = below[static_cast<size_t>(r)];
    for (int c = 0; c < N; ++c) {
      if (map.at(r, c) != CellType::Increase) continue;
      int l = (c + N - 1) % N;
      while (l != c && !is_stitch(map.at(r, l))) l = (l + N - 1) % N;
      b[static_cast<size_t>(c)] = b[static_cast<size_t>(l)];
    }
    for (int c = 0; c < N; ++c)
      below[static_cast<size_t>(r) + 1][static_cast<size_t>(c)] = b[static_cast<size_t>(c)] + (is_stitch(map.at(r, c)) ? 1 : 0);
  }
  std::vector<std::vector<double>> fractions;
  for (const auto& l : live) fractions.push_back(wale_fractions(l, H));
  // Rows knitted at fraction f from rim to rim: the last round's wales'
  // counts, interpolated.
  auto rows_at = [&](double f) {
    const std::vector<int>& lK = live[static_cast<size_t>(K)];
    const std::vector<double>& fK = fractions[static_cast<size_t>(K)];
    const int n = static_cast<int>(lK.size());
    int a = n - 1;
    for (int i = 0; i < n; ++i)
      if (fK[static_cast<size_t>(i)] <= f) a = i;
    const int b = (a + 1) % n;
    double fa = fK[static_cast<size_t>(a)], fb = fK[static_cast<size_t>(b)];
    if (fb <= fa) fb += 1.0;
    double x = f;
    if (x < fa) x += 1.0;
    const double t = fb > fa ? (x - fa) / (fb - fa) : 0.0;
    return (1 - t) * below[static_cast<size_t>(R)][static_cast<size_t>(lK[static_cast<size_t>(a)])] +
           t * below[static_cast<size_t>(R)][static_cast<size_t>(lK[static_cast<size_t>(b)])];
  };
  // A wale's corner after `cum` of the n rows knitted at its place lies
  // cum / n of the way along the surface from rim to rim there.
  auto corner = [&](int i, int j) -> Vec3 {
    const int k = i < R ? rows[static_cast<size_t>(i)].k : K;
    const std::vector<int>& lk = live[static_cast<size_t>(k)];
    const int n = static_cast<int>(lk.size());
    int right = static_cast<int>(std::lower_bound(lk.begin(), lk.end(), j) - lk.begin());
    if (right == n) right = 0;
    const int left = (right + n - 1) % n;
    const double f = fractions[static_cast<size_t>(k)][static_cast<size_t>(right)];
    auto at = [&](int idx) {
      const double fc = fractions[static_cast<size_t>(k)][static_cast<size_t>(idx)];
      const double cum = below[static_cast<size_t>(i)][static_cast<size_t>(lk[static_cast<size_t>(idx)])];
      return sp.point(f, sp.level_at(f, std::min(1.0, cum / rows_at(fc)) * sp.along_at(f, 1.0)));
    };
    return 0.5 * (at(left) + at(right));
  };
  const std::vector<int> classes = map_corner_classes(map);
  std::vector<int> vertex_of_class(classes.size(), -1);
  const int VC = N + 1;
  for (const Stitch& st : out.mesh.stitches) {
    const int r = st.course, c = st.wale;
    const int bl = r * VC + c, br = r * VC + c + 1, tr = (r + 1) * VC + c + 1, tl = (r + 1) * VC + c;
    int g[4] = {bl, br, tr, tl};
    switch (st.type) {
      case StitchType::Knit: break;
      case StitchType::ShortRowLeft: break;
      case StitchType::ShortRowRight: g[2] = tl; break;
      case StitchType::Increase: g[1] = tr, g[2] = tl; break;
      case StitchType::Decrease: break;
    }
    for (int q = 0; q < st.corners(); ++q) vertex_of_class[static_cast<size_t>(classes[static_cast<size_t>(g[q])])] = st.v[static_cast<size_t>(q)];
  }
  std::vector<Vec3> sum(out.mesh.vertices.size(), Vec3::Zero());
  std::vector<int> count(out.mesh.vertices.size(), 0);
  for (int i = 0; i <= R; ++i) {
    for (int j = 0; j <= N; ++j) {
      const int v = vertex_of_class[static_cast<size_t>(classes[static_cast<size_t>(i * VC + j)])];
      if (v < 0) continue;
      sum[static_cast<size_t>(v)] += corner(i, j % N);
      ++count[static_cast<size_t>(v)];
    }
  }
  for (size_t v = 0; v < sum.size(); ++v)
    if (count[v] > 0) out.mesh.vertices[v] = sum[v] / count[v];
  return out;
}

}  // namespace knitforge
