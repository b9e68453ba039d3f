#include "knitforge/convert/random_knitting_map.h"

#include <algorithm>

#include <fmt/core.h>

#include "knitforge/convert/map_knittability.h"
#include "knitforge/convert/map_to_stitch_mesh.h"
#include "knitforge/convert/stitch_mesh_to_map.h"
#include "knitforge/core/stitch_adjacency.h"
#include "knitforge/util/errors.h"

namespace knitforge {

namespace {

// splitmix64: portable and deterministic (std distributions are not).
struct Rng {
  uint64_t s;
  uint64_t next() {
    uint64_t z = (s += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
  }
  /// Uniform in [lo, hi] (hi >= lo).
  int uniform(int lo, int hi) { return lo + static_cast<int>(next() % static_cast<uint64_t>(hi - lo + 1)); }
  bool coin() { return (next() >> 63) != 0; }
};

// Thrown inside one construction attempt when the random choices dead-end.
struct Retry {};

struct ShortColumn {
  int a = 0, b = 0;  // present rows [a, b]
};

struct Layout {
  int sb = 0;  // rows in each shaping band (0 without shaping)
  int m = 0;   // columns added on each side in the bottom band
  int sr_lo = 2, sr_hi = 0;  // short-row turn indices allowed: [sr_lo, sr_hi]
  int band_lo = 1, band_hi = 0;  // columns allowed for short columns
};

Layout layout_of(const RandomMapOptions& o) {
  Layout L;
  if (o.boundary_shaping) {
    L.sb = o.rows >= 12 ? std::max(3, o.rows / 5) : 0;
    L.m = std::max(0, std::min((L.sb - 1) / 2, (o.cols - 6) / 4));
    if (L.m == 0) L.sb = 0;
  }
  L.sr_lo = L.sb > 0 ? std::max(2, L.sb + 1) : 2;
  L.sr_hi = L.sb > 0 ? std::min(o.rows - 2, o.rows - L.sb - 2) : o.rows - 2;
  // With short rows, keep increases and decreases 3 columns from the edge so
  // a short row can always turn beyond them.
  const int margin = o.short_row_ends > 0 ? 3 : 1;
  L.band_lo = L.m + margin;
  L.band_hi = o.cols - 1 - margin - L.m;
  return L;
}

KnittingMap build(const RandomMapOptions& o, const Layout& L, Rng& rng) {
  const int R = o.rows, C = o.cols;
  // Fabric extents per row.
  std::vector<int> lo(R), hi(R);
  lo[0] = L.m;
  hi[0] = C - 1 - L.m;
  {
    // Rows ending on the left (odd rows) may move lo, rows ending on the right hi.
    int left_rows = 0, right_rows = 0;
    for (int r = 1; r < L.sb; ++r) (r % 2 ? left_rows : right_rows) += 1;
    for (int r = 1; r < R; ++r) {
      lo[r] = lo[r - 1];
      hi[r] = hi[r - 1];
      const bool left = r % 2 == 1;
      if (r < L.sb) {
        int& rem = left ? left_rows : right_rows;
        const int need = left ? lo[r] : C - 1 - hi[r];
        if (need > 0 && (rem <= need || rng.coin())) (left ? lo[r] : hi[r]) += left ? -1 : 1;
        --rem;
      } else if (L.sb > 0 && r >= R - L.sb) {
        if (hi[r] - lo[r] > 4 && rng.coin() &&
            (left ? lo[r] < L.m : hi[r] > C - 1 - L.m)) {
          (left ? lo[r] : hi[r]) += left ? 1 : -1;
        }
      }
    }
  }

  // Short columns, placed left to right.
  std::vector<int> cand;
  for (int c = L.band_lo; c <= L.band_hi; ++c) cand.push_back(c);
  for (int i = 0; i < o.short_columns; ++i) std::swap(cand[i], cand[rng.uniform(i, static_cast<int>(cand.size()) - 1)]);
  std::vector<int> chosen(cand.begin(), cand.begin() + o.short_columns);
  std::sort(chosen.begin(), chosen.end());
  std::vector<char> is_short(C, 0);
  std::vector<ShortColumn> sc(C);
  auto present = [&](int r, int c) { return !is_short[c] || (r >= sc[c].a && r <= sc[c].b); };
  // Short columns span at least lmin rows; neighbouring ones share overlap rows.
  const int lmin = std::min(R - 1, std::max(3, R / 4));
  const int overlap = std::max(2, R / 8);
  for (int c : chosen) {
    bool placed = false;
    for (int tries = 0; tries < 400 && !placed; ++tries) {
      ShortColumn s;
      int kind = rng.uniform(0, 2);
      if (kind == 0 && R - 2 - lmin < 1) kind = 1;
      if (kind == 0) {
        s.a = rng.uniform(1, R - 1 - lmin);
        s.b = rng.uniform(s.a + lmin - 1, R - 2);
      } else if (kind == 1) {
        s.a = rng.uniform(1, R - lmin);
        s.b = R - 1;
      } else {
        s.a = 0;
        s.b = rng.uniform(lmin - 1, R - 2);
      }
      if (is_short[c - 1]) {
        const int ov = std::min(s.b, sc[c - 1].b) - std::max(s.a, sc[c - 1].a) + 1;
        if (ov < overlap) continue;
      }
      // No two increases (decreases) neighbours in a course, looking left
      // across columns that are absent in that row.
      auto clash = [&](int row, bool inc) {
        for (int x = c - 1; x >= 0; --x) {
          if (!is_short[x]) return false;
          if (row >= sc[x].a && row <= sc[x].b) return inc ? (sc[x].a == row && row > 0) : (sc[x].b == row && row < R - 1);
        }
        return false;
      };
      if (s.a > 0 && clash(s.a, true)) continue;
      if (s.b < R - 1 && clash(s.b, false)) continue;
      sc[c] = s;
      is_short[c] = 1;
      placed = true;
    }
    if (!placed) throw Retry{};
  }
  auto is_incdec = [&](int r, int c) {
    return is_short[c] && ((r == sc[c].a && r > 0) || (r == sc[c].b && r < R - 1));
  };
  // Inc/Dec cells per row, as [min, max] columns.
  std::vector<int> id_min(R, C), id_max(R, -1);
  for (int c = 0; c < C; ++c) {
    if (!is_short[c]) continue;
    for (int r : {sc[c].a, sc[c].b}) {
      if (is_incdec(r, c)) id_min[r] = std::min(id_min[r], c), id_max[r] = std::max(id_max[r], c);
    }
  }

  // Short-row turns: a random subset of the allowed turn indices.
  const int nturns = o.short_row_ends / 2;
  std::vector<int> idx;
  for (int i = L.sr_lo; i <= L.sr_hi; ++i) idx.push_back(i);
  for (int i = 0; i < nturns; ++i) std::swap(idx[i], idx[rng.uniform(i, static_cast<int>(idx.size()) - 1)]);
  std::vector<char> sr_turn(R + 1, 0);
  for (int i = 0; i < nturns; ++i) sr_turn[idx[i]] = 1;

  // Rows: start where the previous ended, end at the edge or at a turn. A
  // column takes a new turn pair only after its wale knitted a stitch that is
  // no short-row end since its last pair (else four ends would stack).
  std::vector<int> t(R + 1);
  t[0] = lo[0];
  std::vector<int> ks;
  std::vector<char> knit_since_turn(C, 1);
  auto may_turn = [&](int k) { return !is_short[k] && knit_since_turn[k]; };
  for (int r = 0; r < R; ++r) {
    const int d = r % 2 == 0 ? 1 : -1;
    const int s = t[r];
    if (!sr_turn[r + 1]) {
      t[r + 1] = d > 0 ? hi[r] : lo[r];
    } else {
      ks.clear();
      if (d > 0) {
        for (int k = s + 2; k <= hi[r] - 1; ++k) {
          if (!may_turn(k) || (sr_turn[r - 1] && t[r - 1] == k)) continue;
          if (id_max[r] > k - 2 || id_max[r + 1] > k - 2) continue;
          ks.push_back(k);
        }
      } else {
        for (int k = lo[r] + 1; k <= s - 2; ++k) {
          if (!may_turn(k) || (sr_turn[r - 1] && t[r - 1] == k)) continue;
          if (id_min[r] < k + 2 || id_min[r + 1] < k + 2) continue;
          ks.push_back(k);
        }
      }
      if (ks.empty()) throw Retry{};
      t[r + 1] = ks[rng.uniform(0, static_cast<int>(ks.size()) - 1)];
    }
    // the row's regular stitches (not its two ends when they are turns)
    const int a = std::min(s, t[r + 1]), b = std::max(s, t[r + 1]);
    for (int c = a; c <= b; ++c) {
      const bool end = (c == t[r + 1] && sr_turn[r + 1]) || (c == s && sr_turn[r]);
      if (end) knit_since_turn[c] = 0;
      else if (present(r, c)) knit_since_turn[c] = 1;
    }
  }

  KnittingMap map(R, C, CellType::Empty);
  for (int r = 0; r < R; ++r) {
    const int d = r % 2 == 0 ? 1 : -1;
    const int s = t[r], e = t[r + 1];
    const int a = std::min(s, e), b = std::max(s, e);
    for (int c = lo[r]; c <= hi[r]; ++c) {
      CellType cell = CellType::Collapsed;
      if (c >= a && c <= b && present(r, c)) {
        cell = CellType::Knit;
        if (c == e && sr_turn[r + 1]) {
          cell = d > 0 ? CellType::ShortRowRight : CellType::ShortRowLeft;
        } else if (c == s && sr_turn[r]) {
          cell = d > 0 ? CellType::ShortRowLeft : CellType::ShortRowRight;
        } else if (is_short[c] && r == sc[c].a && r > 0) {
          cell = CellType::Increase;
        } else if (is_short[c] && r == sc[c].b && r < R - 1) {
          cell = CellType::Decrease;
        }
      }
      map.at(r, c) = cell;
    }
  }
  return canonical_cells(map);
}

// Throws InvalidInput when the map is not canonical or not knittable.
void validate(const KnittingMap& map) {
  const StitchMesh mesh = map_to_stitch_mesh_topology(map, KnitParams{});
  if (!(stitch_mesh_to_map(mesh) == map)) throw InvalidInput("round trip differs");
  const StitchAdjacency adj(mesh);
  for (int s = 0; s < mesh.num_stitches(); ++s) {
    const int v = apex_vertex(mesh.stitches[s]);
    if (v >= 0 && adj.is_boundary_vertex(v)) throw InvalidInput("apex on the boundary");
    const int nx = adj.next_stitch(s);
    if ((s + 1 < mesh.num_stitches()) != (nx == s + 1)) throw InvalidInput("one-stroke order broken");
  }
  if (!check_knittability(map).ok()) throw InvalidInput("not knittable");
}

}  // namespace

KnittingMap random_knitting_map(const RandomMapOptions& o) {
  if (o.rows < 4 || o.cols < 6) {
    throw InvalidInput(fmt::format("random knitting map: {} x {} is too small (need rows >= 4, cols >= 6)", o.rows,
                                   o.cols));
  }
  if (o.short_row_ends < 0 || o.short_row_ends % 2 != 0) {
    throw InvalidInput(fmt::format("random knitting map: short_row_ends = {}; it must be even and >= 0 (short-row "
                                   "ends come in stacked pairs)",
                                   o.short_row_ends));
  }
  const Layout L = layout_of(o);
  const int max_ends = 2 * std::max(0, L.sr_hi - L.sr_lo + 1);
  if (o.short_row_ends > max_ends) {
    throw InvalidInput(fmt::format("random knitting map: {} short-row ends requested, at most {} fit in {} rows{} "
                                   "(one stacked pair per turn between two rows, first and last rows full)",
                                   o.short_row_ends, max_ends, o.rows,
                                   o.boundary_shaping ? " with boundary shaping" : ""));
  }
  const int max_cols = std::max(0, L.band_hi - L.band_lo + 1);
  if (o.short_columns < 0 || o.short_columns > max_cols) {
    throw InvalidInput(fmt::format("random knitting map: {} short columns requested, 0 to {} fit in {} columns",
                                   o.short_columns, max_cols, o.cols));
  }
  for (int attempt = 0; attempt < 50; ++attempt) {
    Rng rng{o.seed * 0x2545F4914F6CDD1Dull + static_cast<uint64_t>(attempt) * 0x9E3779B97F4A7C15ull};
    try {
      KnittingMap map = build(o, L, rng);
      validate(map);
      return map;
    } catch (const Retry&) {
      // dead end of the random choices: redraw
    } catch (const InvalidInput&) {
      // failed the final check: redraw
    }
  }
  throw InvalidInput(fmt::format("random knitting map: no valid {} x {} map with {} short-row ends and {} short "
                                 "columns found for seed {}; use fewer or another seed",
                                 o.rows, o.cols, o.short_row_ends, o.short_columns, o.seed));
}

}  // namespace knitforge
