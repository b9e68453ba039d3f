#include "knitforge/core/knitting_map.h"

#include <algorithm>

namespace knitforge {

KnittingMap::KnittingMap(int r, int c, CellType fill)
    : rows(r), cols(c), cells(static_cast<size_t>(r) * c, fill), direction(r) {
  for (int i = 0; i < r; ++i) direction[i] = i % 2 == 0 ? 1 : -1;
}

void KnittingMap::set_yarn(int r, int c, int y) {
  if (yarn.empty()) {
    if (y == 0) return;
    yarn.assign(cells.size(), 0);
  }
  yarn[static_cast<size_t>(r) * cols + c] = y;
}

int KnittingMap::num_stitches() const {
  return static_cast<int>(std::count_if(cells.begin(), cells.end(), [](CellType t) { return is_stitch(t); }));
}

bool KnittingMap::operator==(const KnittingMap& o) const {
  if (rows != o.rows || cols != o.cols || cells != o.cells || direction != o.direction) return false;
  for (int r = 0; r < rows; ++r) {
    for (int c = 0; c < cols; ++c) {
      if (yarn_at(r, c) != o.yarn_at(r, c)) return false;
    }
  }
  return true;
}

}  // namespace knitforge
