#include "knitforge/convert/sample_knitting_map.h"

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

KnittingMap sample_knitting_map(std::string_view name) {
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

std::vector<std::string> sample_map_names() { return {"rectangle", "cup", "random"}; }

}  // namespace knitforge
