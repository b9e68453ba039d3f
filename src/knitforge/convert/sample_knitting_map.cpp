#include "knitforge/convert/sample_knitting_map.h"

#include <cstdint>

#include <fmt/core.h>

#include "knitforge/convert/map_to_stitch_mesh.h"
#include "knitforge/convert/random_knitting_map.h"
#include "knitforge/util/errors.h"

namespace knitforge {

namespace {

// Builds a single-yarn map from the column extent [first, last] of each row
// in knitting order. Directions alternate from +1; a row end inside the
// fabric (not on column 0 or cols-1) becomes a short-row end stitch, which
// the next row shares as its start (the turn is a stacked pair). Cells left
// of or right of a row are Collapsed and then canonicalised.
KnittingMap map_from_row_extents(int cols, const std::vector<std::pair<int, int>>& extents) {
  const int rows = static_cast<int>(extents.size());
  KnittingMap map(rows, cols, CellType::Collapsed);
  for (int r = 0; r < rows; ++r) {
    const auto [first, last] = extents[r];
    for (int c = first; c <= last; ++c) map.at(r, c) = CellType::Knit;
    if (first > 0) map.at(r, first) = CellType::ShortRowLeft;
    if (last < cols - 1) map.at(r, last) = CellType::ShortRowRight;
  }
  return canonical_cells(map);
}

}  // namespace

KnittingMap cup_knitting_map(const CupMapOptions& o) {
  if (o.turns < 1) throw InvalidInput(fmt::format("cup map: turns must be >= 1 (got {})", o.turns));
  if (o.border_rows < 2 || o.border_rows % 2 != 0) {
    throw InvalidInput(fmt::format("cup map: border_rows must be even and >= 2 (got {})", o.border_rows));
  }
  if (o.wales < 4 * o.turns + 6) {
    throw InvalidInput(fmt::format("cup map: {} turns per side need at least {} wales (got {})", o.turns,
                                   4 * o.turns + 6, o.wales));
  }
  const int n = o.wales;
  std::vector<std::pair<int, int>> rows;
  for (int r = 0; r < o.border_rows; ++r) rows.emplace_back(0, n - 1);
  // Each row starts where the previous one turned. Rows going right (even
  // index) turn at `right`, rows going left at `left`.
  int left = 0, right = n - 1;
  auto add_pair = [&](int new_right, int new_left) {
    rows.emplace_back(left, new_right);  // knitted left to right, turns at new_right
    right = new_right;
    rows.emplace_back(new_left, right);  // knitted right to left, turns at new_left
    left = new_left;
  };
  for (int i = 1; i <= o.turns; ++i) add_pair(n - 1 - 2 * i, 2 * i);       // in
  for (int i = o.turns; i >= 1; --i) add_pair(n - 2 * i, 2 * i - 1);      // back out
  rows.emplace_back(left, n - 1);
  rows.emplace_back(0, n - 1);
  for (int r = 0; r < o.border_rows - 2; ++r) rows.emplace_back(0, n - 1);
  return map_from_row_extents(n, rows);
}

KnittingMap tube_knitting_map(const TubeMapOptions& o) {
  if (o.round < 8 || o.round % 2 != 0 || o.round > 100000)
    throw InvalidInput(fmt::format("tube map: round must be even, 8..100000 stitches (got {})", o.round));
  if (o.rows < 2 || o.rows > 100000)
    throw InvalidInput(fmt::format("tube map: rows must be 2..100000 (got {})", o.rows));
  if (o.every < 2) throw InvalidInput(fmt::format("tube map: every must be >= 2 rounds (got {})", o.every));
  if (o.decrease_rounds < 0 || static_cast<int64_t>(o.decrease_rounds) * o.every > o.rows - 2)
    throw InvalidInput(fmt::format("tube map: {} decrease rounds every {} rounds need at least {} rows (got {})",
                                   o.decrease_rounds, o.every, static_cast<int64_t>(o.decrease_rounds) * o.every + 2,
                                   o.rows));
  const int C = o.round, h = C / 2;
  if (h - 2 * o.decrease_rounds < 4)
    throw InvalidInput(fmt::format("tube map: {} decrease rounds leave {} wales on each half of a {}-stitch round; "
                                   "keep at least 4",
                                   o.decrease_rounds, h - 2 * o.decrease_rounds, C));
  KnittingMap map(o.rows, C, CellType::Knit);
  map.direction.assign(static_cast<size_t>(o.rows), 1);
  map.seam.assign(static_cast<size_t>(o.rows), 0);
  for (int k = 1; k <= o.decrease_rounds; ++k) {
    const int r = k * o.every;
    for (int half = 0; half < 2; ++half) {
      std::vector<int> live;
      for (int c = half * h; c < (half + 1) * h; ++c)
        if (map.at(r, c) == CellType::Knit) live.push_back(c);
      const int n = static_cast<int>(live.size());
      for (int q : {n / 4, (3 * n) / 4}) {
        const int c = live[static_cast<size_t>((q + k) % n)];
        map.at(r, c) = CellType::Decrease;
        for (int rr = r + 1; rr < o.rows; ++rr) map.at(rr, c) = CellType::Collapsed;
      }
    }
  }
  return canonical_cells(map);  // seams where a round whose first column ended starts
}

KnittingMap sample_knitting_map(std::string_view name) {
  if (name == "tube") return tube_knitting_map();
  if (name == "tapered-tube") {
    TubeMapOptions o;
    o.round = 32;
    o.rows = 24;
    o.decrease_rounds = 4;
    o.every = 4;
    return tube_knitting_map(o);
  }
  if (name == "rectangle") {
    KnittingMap map(30, 40, CellType::Knit);
    return map;
  }
  if (name == "cup") return cup_knitting_map();
  if (name == "random") {
    RandomMapOptions o;
    o.rows = 40;
    o.cols = 40;
    o.short_row_ends = 24;
    o.short_columns = 4;
    o.seed = 1;
    return random_knitting_map(o);
  }
  std::string names;
  for (const auto& n : sample_map_names()) names += (names.empty() ? "" : ", ") + n;
  throw InvalidInput(fmt::format("unknown sample map '{}' (known: {})", name, names));
}

std::vector<std::string> sample_map_names() { return {"rectangle", "cup", "random", "tube", "tapered-tube"}; }

}  // namespace knitforge
