#include "knitforge/design/flatten/rasterize_pattern.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <fmt/format.h>

#include "knitforge/util/errors.h"

namespace knitforge {

namespace {

enum : uint8_t { kOut = 0, kFabric = 1, kGap = 2 };
enum : uint8_t { kNeedSRR = 1, kNeedSRL = 2, kNeedDec = 4, kNeedInc = 8 };

int popcount4(uint8_t v) { return (v & 1) + ((v >> 1) & 1) + ((v >> 2) & 1) + ((v >> 3) & 1); }

double cross2(const Vec2& a, const Vec2& b) { return a.x() * b.y() - a.y() * b.x(); }

// Grid of map cells with the per-row spans (see the file comment of the header).
struct Grid {
  int rows = 0;
  int cols = 0;
  std::vector<uint8_t> state;    // kOut / kFabric / kGap
  std::vector<int> left, right;  // span per map row
  std::vector<char> collapsed;   // Out cells collapsed in their column
  std::vector<uint8_t> need;     // shaping demands per cell
  std::vector<int> slot;         // pattern row (units of the stitch height) per cell
  uint8_t& at(int r, int c) { return state[static_cast<size_t>(r) * cols + c]; }
  uint8_t at(int r, int c) const { return state[static_cast<size_t>(r) * cols + c]; }
  size_t idx(int r, int c) const { return static_cast<size_t>(r) * cols + c; }
};

void analyse(Grid& g) {
  g.collapsed.assign(g.state.size(), 0);
  g.need.assign(g.state.size(), 0);
  for (int c = 0; c < g.cols; ++c) {
    int m = 0;
    while (m < g.rows) {
      if (g.at(m, c) == kFabric) {
        ++m;
        continue;
      }
      const int a = m;
      bool has_gap = false;
      while (m < g.rows && g.at(m, c) != kFabric) {
        if (g.at(m, c) == kGap) has_gap = true;
        ++m;
      }
      const int b = m - 1;
      if (a > 0 && b < g.rows - 1 && !has_gap) {
        for (int k = a; k <= b; ++k) g.collapsed[g.idx(k, c)] = 1;
      }
      // Gap runs inside [a, b]: Decrease below, Increase above.
      for (int k = a; k <= b; ++k) {
        if (g.at(k, c) != kGap) continue;
        if (k > 0 && g.at(k - 1, c) == kFabric) g.need[g.idx(k - 1, c)] |= kNeedDec;
        if (k + 1 < g.rows && g.at(k + 1, c) == kFabric) g.need[g.idx(k + 1, c)] |= kNeedInc;
      }
    }
  }
  for (int m = 0; m < g.rows; ++m) {
    if (g.right[m] + 1 < g.cols && g.collapsed[g.idx(m, g.right[m] + 1)]) {
      g.need[g.idx(m, g.right[m])] |= kNeedSRR;
    }
    if (g.left[m] - 1 >= 0 && g.collapsed[g.idx(m, g.left[m] - 1)]) {
      g.need[g.idx(m, g.left[m])] |= kNeedSRL;
    }
  }
}

// Extends the right end of the turn pair holding row m (rows 2i, 2i+1) by one.
bool extend_right_pair(Grid& g, int m) {
  const int p = m - (m % 2);
  if (p + 1 >= g.rows || g.right[p] + 1 >= g.cols || g.right[p] != g.right[p + 1]) return false;
  for (int r = p; r <= p + 1; ++r) {
    ++g.right[r];
    g.at(r, g.right[r]) = kFabric;
  }
  return true;
}

// Extends the left end of the turn pair holding row m (rows 2i+1, 2i+2) by one.
bool extend_left_pair(Grid& g, int m) {
  const int p = m % 2 == 1 ? m : m - 1;
  if (p < 0 || p + 1 >= g.rows || g.left[p] - 1 < 0 || g.left[p] != g.left[p + 1]) return false;
  for (int r = p; r <= p + 1; ++r) {
    --g.left[r];
    g.at(r, g.left[r]) = kFabric;
  }
  return true;
}

// Shortens the turn pair holding row m at its right end by one.
bool shrink_right_pair(Grid& g, int m) {
  const int p = m - (m % 2);
  if (p + 1 >= g.rows || g.right[p] != g.right[p + 1]) return false;
  for (int r = p; r <= p + 1; ++r) {
    if (g.right[r] - g.left[r] < 2 || g.at(r, g.right[r] - 1) != kFabric) return false;
  }
  for (int r = p; r <= p + 1; ++r) {
    g.at(r, g.right[r]) = kOut;
    --g.right[r];
  }
  return true;
}

// Shortens the turn pair holding row m at its left end by one.
bool shrink_left_pair(Grid& g, int m) {
  const int p = m % 2 == 1 ? m : m - 1;
  if (p < 0 || p + 1 >= g.rows || g.left[p] != g.left[p + 1]) return false;
  for (int r = p; r <= p + 1; ++r) {
    if (g.right[r] - g.left[r] < 2 || g.at(r, g.left[r] + 1) != kFabric) return false;
  }
  for (int r = p; r <= p + 1; ++r) {
    g.at(r, g.left[r]) = kOut;
    ++g.left[r];
  }
  return true;
}

using Bitmap = std::vector<std::vector<char>>;

// Fabric runs [first, last] of a bitmap row.
std::vector<std::pair<int, int>> runs_of(const std::vector<char>& row) {
  std::vector<std::pair<int, int>> runs;
  const int n = static_cast<int>(row.size());
  for (int c = 0; c < n;) {
    if (!row[c]) {
      ++c;
      continue;
    }
    const int s = c;
    while (c < n && row[c]) ++c;
    runs.emplace_back(s, c - 1);
  }
  return runs;
}

// A band: bitmap rows a..b split by a horizontal hole into a left segment
// [row start, lend[k]] (none when !has_l[k]) and a right segment
// [rstart[k], row end] (none when !has_r[k]); k = i - a. Knitted as all
// right segments (short-row pairs turning at the hole), one row crossing
// below the hole, then all left segments (seed §2.3.2).
struct Band {
  int a = 0;
  int b = 0;
  std::vector<int> lend, rstart;
  std::vector<char> has_l, has_r;
};

// Builds the band of rows a..b of `bits` from each row's runs: two runs are
// the left and the right segment; one run is the left or the right one by
// its position against the two-run rows' holes. Returns false when the rows
// do not split that way, when a column would lie on the left in one row and
// on the right in another (the sides are knitted one after the other), or
// when the hole is taller than wide in mm (then it is a vertical dart: short
// columns).
bool make_band(const Bitmap& bits, int a, int b, double sw, double bh, Band& band) {
  const int nb = static_cast<int>(bits.size());
  if (a < 1 || b > nb - 2 || a > b) return false;
  const int n = b - a + 1;
  band = Band{};
  band.a = a;
  band.b = b;
  band.lend.assign(n, -1);
  band.rstart.assign(n, -1);
  band.has_l.assign(n, 0);
  band.has_r.assign(n, 0);
  int hole_lo = std::numeric_limits<int>::max();  // intersection of the two-run rows' holes
  int hole_hi = std::numeric_limits<int>::min();
  int widest = 0;
  bool any_two = false;
  std::vector<std::vector<std::pair<int, int>>> runs(n);
  for (int k = 0; k < n; ++k) {
    runs[k] = runs_of(bits[a + k]);
    if (runs[k].empty() || runs[k].size() > 2) return false;
    if (runs[k].size() == 2) {
      const int lo = runs[k][0].second + 1;
      const int hi = runs[k][1].first - 1;
      hole_lo = any_two ? std::max(hole_lo, lo) : lo;
      hole_hi = any_two ? std::min(hole_hi, hi) : hi;
      widest = std::max(widest, hi - lo + 1);
      any_two = true;
      band.has_l[k] = band.has_r[k] = 1;
      band.lend[k] = runs[k][0].second;
      band.rstart[k] = runs[k][1].first;
    }
  }
  if (!any_two || widest * sw < n * bh) return false;
  bool any_l = false;
  bool any_r = false;
  int max_lend = -1;
  int min_rstart = std::numeric_limits<int>::max();
  for (int k = 0; k < n; ++k) {
    if (runs[k].size() == 1) {
      const auto [l, r] = runs[k][0];
      if (hole_lo <= hole_hi && r < hole_lo) {
        band.has_l[k] = 1;
        band.lend[k] = r;
      } else if (hole_lo <= hole_hi && l > hole_hi) {
        band.has_r[k] = 1;
        band.rstart[k] = l;
      } else {
        return false;  // the run crosses the hole: not split
      }
    }
    if (band.has_l[k]) {
      any_l = true;
      max_lend = std::max(max_lend, band.lend[k]);
    }
    if (band.has_r[k]) {
      any_r = true;
      min_rstart = std::min(min_rstart, band.rstart[k]);
    }
  }
  return any_l && any_r && max_lend < min_rstart;
}

// Bands of `bits` (sorted, disjoint, at least one plain row between two):
// (1) around each hole (non-fabric component not reaching the bitmap's
// border); (2) at the bottom / top above / below an added long row, the rows
// from the long row up to where the branches join. Before that, a vertical
// hole closed off only by an added long row (a vertical dart opening at the
// pattern's edge) is opened through the long row, so its gap stays open to
// the edge (short columns ending / starting there).
std::vector<Band> find_bands(Bitmap& bits, bool long_bottom, bool long_top, double sw, double bh) {
  const int nb = static_cast<int>(bits.size());
  const int nc = nb > 0 ? static_cast<int>(bits[0].size()) : 0;
  std::vector<Band> bands;
  for (int pass = 0; pass < 2; ++pass) {
    std::vector<char> seen(static_cast<size_t>(nb) * nc, 0);
    auto visited = [&](int i, int c) -> char& { return seen[static_cast<size_t>(i) * nc + c]; };
    for (int i0 = 0; i0 < nb; ++i0) {
      for (int c0 = 0; c0 < nc; ++c0) {
        if (bits[i0][c0] || visited(i0, c0)) continue;
        std::vector<std::pair<int, int>> stack = {{i0, c0}};
        std::vector<std::pair<int, int>> cells;
        visited(i0, c0) = 1;
        bool border = false;
        while (!stack.empty()) {
          const auto [i, c] = stack.back();
          stack.pop_back();
          cells.emplace_back(i, c);
          if (i == 0 || i == nb - 1 || c == 0 || c == nc - 1) border = true;
          const int di[4] = {1, -1, 0, 0};
          const int dc[4] = {0, 0, 1, -1};
          for (int k = 0; k < 4; ++k) {
            const int ni = i + di[k];
            const int nk = c + dc[k];
            if (ni < 0 || ni >= nb || nk < 0 || nk >= nc || bits[ni][nk] || visited(ni, nk)) continue;
            visited(ni, nk) = 1;
            stack.emplace_back(ni, nk);
          }
        }
        if (border) continue;
        int a = nb;
        int b = -1;
        int cmin = nc;
        int cmax = -1;
        for (const auto& [i, c] : cells) {
          a = std::min(a, i);
          b = std::max(b, i);
          cmin = std::min(cmin, c);
          cmax = std::max(cmax, c);
        }
        const bool vertical = (cmax - cmin + 1) * sw < (b - a + 1) * bh;
        if (pass == 0 && vertical) {
          for (const auto& [i, c] : cells) {
            if (long_bottom && a == 1 && i == 1) bits[0][c] = 0;
            if (long_top && b == nb - 2 && i == nb - 2) bits[nb - 1][c] = 0;
          }
        }
        Band band;
        if (pass == 1 && !vertical && make_band(bits, a, b, sw, bh, band)) bands.push_back(std::move(band));
      }
    }
  }
  // Branches at the ends under / over a long row: from the long row inwards,
  // rows of one run (the tip of one branch), then rows of two runs (both
  // branches), up to the first row that is not of two runs (they joined).
  for (int side = 0; side < 2; ++side) {
    if (!(side == 0 ? long_bottom : long_top) || nb < 3) continue;
    const int step = side == 0 ? 1 : -1;
    int i = side == 0 ? 1 : nb - 2;
    int first_two = -1;
    int last = -1;
    for (; i >= 1 && i <= nb - 2; i += step) {
      const size_t nr = runs_of(bits[i]).size();
      if (nr == 2) {
        if (first_two < 0) first_two = i;
      } else if (nr != 1 || first_two >= 0) {
        break;
      }
      last = i;
    }
    if (first_two < 0) continue;
    Band band;
    const int a = side == 0 ? 1 : last;
    const int b = side == 0 ? last : nb - 2;
    if (make_band(bits, a, b, sw, bh, band)) bands.push_back(std::move(band));
  }
  std::sort(bands.begin(), bands.end(), [](const Band& x, const Band& y) { return x.a < y.a; });
  std::vector<Band> kept;
  for (auto& band : bands) {
    if (!kept.empty() && band.a < kept.back().b + 2) continue;
    kept.push_back(std::move(band));
  }
  return kept;
}

}  // namespace

RasterizedPattern rasterize_pattern(const TriMesh& mesh, const std::vector<Vec2>& uv,
                                    const KnitParams& params, const RasterizeOptions& options) {
  const double sw = params.stitch_width;
  const double sh = params.stitch_height;
  if (!(sw > 0.0) || !(sh > 0.0) || !std::isfinite(sw) || !std::isfinite(sh)) {
    throw InvalidInput("rasterize_pattern: the stitch size must be positive and finite");
  }
  if (static_cast<int>(uv.size()) != mesh.num_vertices()) {
    throw InvalidInput(
        fmt::format("rasterize_pattern: {} 2D positions for {} vertices", uv.size(), mesh.num_vertices()));
  }
  if (options.long_row_band < 1) throw InvalidInput("rasterize_pattern: long_row_band must be >= 1");
  Vec2 lo(std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity());
  Vec2 hi = -lo;
  for (const auto& t : mesh.faces) {
    for (int v : t) {
      if (v < 0 || v >= mesh.num_vertices()) throw InvalidInput("rasterize_pattern: face index out of range");
      if (!uv[v].allFinite()) {
        throw InvalidInput(fmt::format("rasterize_pattern: 2D position of vertex {} is not finite", v));
      }
      lo = lo.cwiseMin(uv[v]);
      hi = hi.cwiseMax(uv[v]);
    }
  }
  if (mesh.faces.empty()) throw InvalidInput("rasterize_pattern: the pattern has no faces");
  const double bh = 2.0 * sh;
  const double W = hi.x() - lo.x();
  const double H = hi.y() - lo.y();
  const double max_cells = 5e7;
  if ((W / sw + 1.0) * (H / bh + 1.0) > max_cells) {
    throw InvalidInput(fmt::format(
        "rasterize_pattern: the pattern ({:.1f} x {:.1f} mm) needs more than {:.0f} cells at stitch "
        "size {} x {} mm; check the units (--units) or the stitch size",
        W, H, max_cells, sw, sh));
  }
  int nc = std::max(1, static_cast<int>(std::ceil(W / sw)));
  int nb = std::max(1, static_cast<int>(std::ceil(H / bh)));
  double x0 = lo.x() - 0.5 * (nc * sw - W);
  double y0 = lo.y() - 0.5 * (nb * bh - H);

  // 1. Bitmap: cell centres inside a triangle.
  std::vector<char> bits(static_cast<size_t>(nb) * nc, 0);
  for (const auto& t : mesh.faces) {
    const Vec2& a = uv[t[0]];
    const Vec2& b = uv[t[1]];
    const Vec2& c = uv[t[2]];
    const double area = cross2(b - a, c - a);
    if (!(std::abs(area) > 0.0)) continue;
    const double tminx = std::min({a.x(), b.x(), c.x()});
    const double tmaxx = std::max({a.x(), b.x(), c.x()});
    const double tminy = std::min({a.y(), b.y(), c.y()});
    const double tmaxy = std::max({a.y(), b.y(), c.y()});
    const int c0 = std::max(0, static_cast<int>(std::floor((tminx - x0) / sw - 0.5)));
    const int c1 = std::min(nc - 1, static_cast<int>(std::ceil((tmaxx - x0) / sw - 0.5)));
    const int r0 = std::max(0, static_cast<int>(std::floor((tminy - y0) / bh - 0.5)));
    const int r1 = std::min(nb - 1, static_cast<int>(std::ceil((tmaxy - y0) / bh - 0.5)));
    const double eps = -1e-12 * std::abs(area);
    for (int r = r0; r <= r1; ++r) {
      for (int col = c0; col <= c1; ++col) {
        const Vec2 p(x0 + (col + 0.5) * sw, y0 + (r + 0.5) * bh);
        double w0 = cross2(b - p, c - p);
        double w1 = cross2(c - p, a - p);
        double w2 = cross2(a - p, b - p);
        if (area < 0.0) {
          w0 = -w0;
          w1 = -w1;
          w2 = -w2;
        }
        if (w0 >= eps && w1 >= eps && w2 >= eps) bits[static_cast<size_t>(r) * nc + col] = 1;
      }
    }
  }
  // Trim empty rows and columns at the ends.
  int rb = 0;
  int re = nb - 1;
  auto row_empty = [&](int r) {
    for (int col = 0; col < nc; ++col) {
      if (bits[static_cast<size_t>(r) * nc + col]) return false;
    }
    return true;
  };
  while (rb <= re && row_empty(rb)) ++rb;
  while (re >= rb && row_empty(re)) --re;
  if (rb > re) {
    throw InvalidInput(fmt::format(
        "rasterize_pattern: the pattern ({:.1f} x {:.1f} mm) covers no stitch cell of {} x {} mm; "
        "use a smaller stitch size or check the units",
        W, H, sw, bh));
  }
  int cb = nc;
  int ce = -1;
  for (int r = rb; r <= re; ++r) {
    for (int col = 0; col < nc; ++col) {
      if (bits[static_cast<size_t>(r) * nc + col]) {
        cb = std::min(cb, col);
        ce = std::max(ce, col);
      }
    }
  }
  std::vector<std::vector<char>> rows;
  for (int r = rb; r <= re; ++r) {
    std::vector<char> row(bits.begin() + static_cast<long>(r) * nc + cb,
                          bits.begin() + static_cast<long>(r) * nc + ce + 1);
    if (std::find(row.begin(), row.end(), 1) == row.end()) {
      throw InvalidInput(fmt::format(
          "rasterize_pattern: the pattern is thinner than one row pair ({:.2f} mm) at y = {:.1f} mm; "
          "use a smaller stitch height or fewer / narrower darts there",
          bh, y0 + (r + 0.5) * bh));
    }
    rows.push_back(std::move(row));
  }
  x0 += cb * sw;
  y0 += rb * bh;
  nc = ce - cb + 1;

  RasterizedPattern out;
  for (const auto& row : rows) out.pattern_cells += static_cast<int>(std::count(row.begin(), row.end(), 1));

  auto span_of = [](const std::vector<char>& row) {
    int l = static_cast<int>(row.size());
    int r = -1;
    for (int col = 0; col < static_cast<int>(row.size()); ++col) {
      if (row[col]) {
        l = std::min(l, col);
        r = std::max(r, col);
      }
    }
    return std::pair<int, int>(l, r);
  };
  auto has_gap = [&](const std::vector<char>& row) {
    const auto [l, r] = span_of(row);
    for (int col = l; col <= r; ++col) {
      if (!row[col]) return true;
    }
    return false;
  };

  // 2. Long rows.
  bool added_bottom = false;
  bool added_top = false;
  if (options.long_rows) {
    for (int side = 0; side < 2; ++side) {
      const int n = static_cast<int>(rows.size());
      const int band = std::min(options.long_row_band, n);
      int ul = nc;
      int ur = -1;
      for (int k = 0; k < band; ++k) {
        const auto [l, r] = span_of(rows[side == 0 ? k : n - 1 - k]);
        ul = std::min(ul, l);
        ur = std::max(ur, r);
      }
      const auto& end_row = rows[side == 0 ? 0 : n - 1];
      const auto [l, r] = span_of(end_row);
      if (has_gap(end_row) || l > ul || r < ur) {
        std::vector<char> long_row(nc, 0);
        for (int col = ul; col <= ur; ++col) long_row[col] = 1;
        // A single-run end row next to a row of two branches is the tip of
        // one branch: the long row takes its place, so the notch between
        // the branches ends at the long row (and is knitted as a dart).
        const int inner = side == 0 ? 1 : n - 2;
        if (n >= 3 && runs_of(end_row).size() == 1 && runs_of(rows[inner]).size() == 2) {
          rows[side == 0 ? 0 : n - 1] = long_row;
          (side == 0 ? added_bottom : added_top) = true;
          ++out.added_long_rows;
          continue;
        }
        if (side == 0) {
          rows.insert(rows.begin(), long_row);
          y0 -= bh;
          added_bottom = true;
        } else {
          rows.push_back(long_row);
          added_top = true;
        }
        ++out.added_long_rows;
      }
    }
  }
  nb = static_cast<int>(rows.size());

  // 2b. Bands around horizontal holes and branches (see find_bands()).
  const std::vector<Band> bands = find_bands(rows, added_bottom, added_top, sw, bh);
  out.short_row_holes = static_cast<int>(bands.size());

  // 3. Map rows with aligned right ends and extended left ends; a band of
  //    rows around a horizontal hole is knitted right side first, then left.
  std::vector<int> bl(nb);
  std::vector<int> br(nb);
  for (int i = 0; i < nb; ++i) std::tie(bl[i], br[i]) = span_of(rows[i]);
  struct RowSpec {
    int i;           // bitmap row
    int lo, hi;      // natural span (cells from the bitmap row)
    int slot;        // pattern row (units of sh) of the row's cells ...
    int split = -1;  // ... and from this column on (>= 0) ...
    int slot2 = 0;   // ... this one (the row crossing a band)
  };
  std::vector<RowSpec> specs;
  {
    size_t next_band = 0;
    for (int i = 0; i < nb;) {
      if (next_band < bands.size() && bands[next_band].a == i + 1) {
        const Band& band = bands[next_band++];
        // Pattern rows: the right side is knitted half a row lower (its
        // rows 2k - 1, 2k), so the crossing row lies on top of it there
        // (2 k_last + 1) and under the left side elsewhere (2i + 1).
        specs.push_back({i, bl[i], br[i], 2 * i});
        int right_from = nc;
        int last_r = i;
        for (int k = band.a; k <= band.b; ++k) {
          if (!band.has_r[k - band.a]) continue;
          const int lo = band.rstart[k - band.a];
          right_from = std::min(right_from, lo);
          last_r = k;
          specs.push_back({k, lo, br[k], 2 * k - 1});
          specs.push_back({k, lo, br[k], 2 * k});
        }
        specs.push_back({i, bl[i], br[i], 2 * i + 1, right_from, 2 * last_r + 1});
        for (int k = band.a; k <= band.b; ++k) {
          if (!band.has_l[k - band.a]) continue;
          const int hi = band.lend[k - band.a];
          specs.push_back({k, bl[k], hi, 2 * k});
          specs.push_back({k, bl[k], hi, 2 * k + 1});
        }
        i = band.b + 1;
      } else {
        specs.push_back({i, bl[i], br[i], 2 * i});
        specs.push_back({i, bl[i], br[i], 2 * i + 1});
        ++i;
      }
    }
  }
  Grid g;
  g.rows = static_cast<int>(specs.size());
  g.cols = nc;
  g.state.assign(static_cast<size_t>(g.rows) * nc, kOut);
  g.slot.assign(static_cast<size_t>(g.rows) * nc, 0);
  g.left.resize(g.rows);
  g.right.resize(g.rows);
  for (int m = 0; m < g.rows; ++m) {
    // Rows m, m+1 share their right end when m goes left to right (even m),
    // their left end otherwise: each row starts where the previous ended.
    const RowSpec& s = specs[m];
    int l = s.lo;
    int r = s.hi;
    if (m % 2 == 0 && m + 1 < g.rows) r = std::max(r, specs[m + 1].hi);
    if (m % 2 == 1 && m > 0) r = std::max(r, specs[m - 1].hi);
    if (m % 2 == 1 && m + 1 < g.rows) l = std::min(l, specs[m + 1].lo);
    if (m % 2 == 0 && m > 0) l = std::min(l, specs[m - 1].lo);
    g.left[m] = l;
    g.right[m] = r;
    for (int col = 0; col < nc; ++col)
      g.slot[g.idx(m, col)] = s.split >= 0 && col >= s.split ? s.slot2 : s.slot;
    for (int col = l; col <= r; ++col) {
      if (col < s.lo || col > s.hi) {
        g.at(m, col) = kFabric;
        ++out.extended_cells;
      } else {
        g.at(m, col) = rows[s.i][col] ? kFabric : kGap;
      }
    }
  }

  // 5. Repairs.
  int repairs = 0;
  for (;;) {
    // A gap open to cells outside the rows (a notch in the bottom or top
    // edge below / above a narrower row) is filled: its short-column seam
    // would meet the short-row seams beside it and degenerate stitches.
    for (int c = 0; c < g.cols; ++c) {
      int m = 0;
      while (m < g.rows) {
        if (g.at(m, c) == kFabric) {
          ++m;
          continue;
        }
        const int a = m;
        bool gap = false;
        bool outside = false;
        for (; m < g.rows && g.at(m, c) != kFabric; ++m) {
          (g.at(m, c) == kGap ? gap : outside) = true;
        }
        if (gap && outside) {
          for (int k = a; k < m; ++k) {
            if (g.at(k, c) == kGap) {
              g.at(k, c) = kFabric;
              ++out.filled_gap_cells;
            }
          }
        }
      }
    }
    analyse(g);
    bool changed = false;
    // Cells that would need two shaping types.
    for (int m = 0; m < g.rows; ++m) {
      for (int c = 0; c < g.cols; ++c) {
        const uint8_t nd = g.need[g.idx(m, c)];
        if (popcount4(nd) < 2) continue;
        if ((nd & kNeedDec) && m + 1 < g.rows && g.at(m + 1, c) == kGap) {
          g.at(m + 1, c) = kFabric;
          ++out.filled_gap_cells;
        } else if ((nd & kNeedInc) && m > 0 && g.at(m - 1, c) == kGap) {
          g.at(m - 1, c) = kFabric;
          ++out.filled_gap_cells;
        } else if (!extend_right_pair(g, m) && !extend_left_pair(g, m)) {
          continue;
        }
        changed = true;
        ++repairs;
      }
    }
    if (!changed) {
      // Neighbouring decreases / increases in a course: consecutive stitches
      // of a row (Gap cells between them are skipped by the course).
      for (int m = 0; m < g.rows; ++m) {
        int prev = -1;
        for (int c = g.left[m]; c <= g.right[m]; ++c) {
          if (g.at(m, c) != kFabric) continue;
          if (prev >= 0) {
            for (int kind = 0; kind < 2; ++kind) {
              const uint8_t flag = kind == 0 ? kNeedDec : kNeedInc;
              const int gm = kind == 0 ? m + 1 : m - 1;
              if (!(g.need[g.idx(m, prev)] & flag) || !(g.need[g.idx(m, c)] & flag)) continue;
              // Alternate the side by row so a gap narrows symmetrically.
              int fill = m % 2 == 0 ? c : prev;
              if (gm < 0 || gm >= g.rows) continue;
              if (g.at(gm, fill) != kGap) fill = fill == c ? prev : c;
              if (g.at(gm, fill) != kGap) continue;
              g.at(gm, fill) = kFabric;
              g.need[g.idx(m, fill)] &= static_cast<uint8_t>(~flag);
              ++out.filled_gap_cells;
              changed = true;
              ++repairs;
            }
          }
          prev = c;
        }
      }
    }
    if (!changed) {
      // Four or more short-row ends stacked in a wale (the wale passes
      // Collapsed cells): move the upper turn pair sideways.
      for (int c = 0; c < g.cols && !changed; ++c) {
        int run = 0;
        for (int m = 0; m < g.rows && !changed; ++m) {
          const size_t k = g.idx(m, c);
          if (g.state[k] == kFabric) {
            const bool end = (g.need[k] & (kNeedSRR | kNeedSRL)) != 0;
            run = end ? run + 1 : 0;
            if (run >= 4) {
              const bool right = (g.need[k] & kNeedSRR) != 0;
              const int n = m - 1;  // the pair (n, m)
              if (right ? (extend_right_pair(g, n) || shrink_right_pair(g, n))
                        : (extend_left_pair(g, n) || shrink_left_pair(g, n))) {
                ++out.shifted_turns;
                changed = true;
                ++repairs;
              } else {
                run = 0;
              }
            }
          } else if (!g.collapsed[k]) {
            run = 0;
          }
        }
      }
    }
    if (!changed) break;
    if (repairs > options.max_repairs) {
      throw InvalidInput(
          fmt::format("rasterize_pattern: the map repairs did not settle after {} steps; try another stitch "
                      "size or fewer darts",
                      options.max_repairs));
    }
  }

  // 4. The map.
  KnittingMap map(g.rows, g.cols, CellType::Empty);
  for (int m = 0; m < g.rows; ++m) {
    for (int c = 0; c < g.cols; ++c) {
      const size_t k = g.idx(m, c);
      CellType t = CellType::Empty;
      if (g.state[k] == kFabric) {
        const uint8_t nd = g.need[k];
        t = (nd & kNeedSRR)   ? CellType::ShortRowRight
            : (nd & kNeedSRL) ? CellType::ShortRowLeft
            : (nd & kNeedDec) ? CellType::Decrease
            : (nd & kNeedInc) ? CellType::Increase
                              : CellType::Knit;
      } else if (g.state[k] == kGap || g.collapsed[k]) {
        t = CellType::Collapsed;
      }
      map.at(m, c) = t;
    }
  }
  out.map = std::move(map);
  out.origin = Vec2(x0, y0);
  out.cell_pattern_row = std::move(g.slot);
  out.bitmap_rows = nb;
  out.bitmap_cols = nc;
  return out;
}

}  // namespace knitforge
