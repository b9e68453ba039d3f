#include "knitforge/convert/pack_tube_columns.h"

#include <algorithm>

#include "knitforge/convert/map_to_stitch_mesh.h"
#include "knitforge/util/errors.h"

namespace knitforge {

namespace {

struct Wale {
  int col = 0;
  int first = 0, last = 0;  // first and last stitch row
  int until = 0;            // last row it keeps its column: a Decrease keeps it one row more
};

}  // namespace

KnittingMap pack_tube_columns(const KnittingMap& map) {
  if (!map.tubular()) throw InvalidInput("pack_tube_columns: the map is not a tube (no seam array)");
  const KnittingMap m = canonical_cells(map);  // validates, and Empty cells now break wales
  const int R = m.rows, C = m.cols, h = C / 2;

  // Wales, column by column (so in column order within each half).
  std::vector<Wale> wales;
  std::vector<int> wale_of(static_cast<size_t>(R) * C, -1);
  for (int c = 0; c < C; ++c) {
    int open = -1;  // the wale the next stitch above may continue
    for (int r = 0; r < R; ++r) {
      const CellType t = m.at(r, c);
      if (t == CellType::Empty) open = -1;
      if (!is_stitch(t)) continue;
      if (open < 0 || !has_side(t, Side::Bottom)) {
        open = static_cast<int>(wales.size());
        wales.push_back({c, r, r});
      }
      wales[static_cast<size_t>(open)].last = r;
      wale_of[static_cast<size_t>(r) * C + c] = open;
      if (!has_side(t, Side::Top)) open = -1;
    }
  }
  for (Wale& W : wales)
    W.until = W.last + (W.last + 1 < R && !has_side(m.at(W.last, W.col), Side::Top) ? 1 : 0);

  // Longest-path layering per half: each row's alive wales in column order
  // (a decreased wale's column stays free in the row above its Decrease, so
  // that no increase starts on its apex).
  std::vector<int> layer(wales.size(), 0);
  std::vector<std::vector<int>> before(wales.size());  // wales next to it on the left in some row
  for (int r = 0; r < R; ++r) {
    int prev = -1;
    for (size_t w = 0; w < wales.size(); ++w) {  // column order
      const Wale& W = wales[w];
      if (W.first > r || W.until < r) continue;
      if (prev >= 0 && (wales[static_cast<size_t>(prev)].col < h) == (W.col < h)) before[w].push_back(prev);
      prev = static_cast<int>(w);
    }
  }
  int width = 1;
  for (size_t w = 0; w < wales.size(); ++w) {  // edges go to larger columns: column order is topological
    for (int p : before[w]) layer[w] = std::max(layer[w], layer[static_cast<size_t>(p)] + 1);
    width = std::max(width, layer[w] + 1);
  }

  const int C2 = 2 * width;
  KnittingMap out(R, C2, CellType::Collapsed);
  out.direction = m.direction;
  out.closed_end = m.closed_end;
  out.seam.assign(static_cast<size_t>(R), -1);
  auto new_col = [&](int w) {
    const Wale& W = wales[static_cast<size_t>(w)];
    return (W.col < h ? 0 : width) + layer[static_cast<size_t>(w)];
  };
  for (int r = 0; r < R; ++r) {
    for (int c = 0; c < C; ++c) {
      const int w = wale_of[static_cast<size_t>(r) * C + c];
      if (w < 0) continue;
      out.at(r, new_col(w)) = m.at(r, c);
      if (!m.yarn.empty()) out.set_yarn(r, new_col(w), m.yarn_at(r, c));
    }
    if (!m.closed(r)) continue;  // the seam: before the round's first stitch
    for (int c : row_columns(m, r)) {
      const int w = wale_of[static_cast<size_t>(r) * C + c];
      if (w < 0) continue;
      const int nc = new_col(w);
      out.seam[static_cast<size_t>(r)] = m.direction[static_cast<size_t>(r)] > 0 ? nc : (nc + 1) % C2;
      break;
    }
  }
  return canonical_cells(out);
}

}  // namespace knitforge
