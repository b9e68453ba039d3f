#include "knitforge/core/knitting_map.h"

#include <algorithm>

#include <fmt/core.h>

#include "knitforge/util/errors.h"

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
  if (rows != o.rows || cols != o.cols || cells != o.cells || direction != o.direction || seam != o.seam ||
      closed_end != o.closed_end)
    return false;
  for (int r = 0; r < rows; ++r) {
    for (int c = 0; c < cols; ++c) {
      if (yarn_at(r, c) != o.yarn_at(r, c)) return false;
    }
  }
  return true;
}

void check_map_arrays(const KnittingMap& m) {
  if (m.rows < 0 || m.cols < 0) {
    throw InvalidInput(fmt::format("knitting map has negative size {} x {}", m.rows, m.cols));
  }
  const size_t n = static_cast<size_t>(m.rows) * static_cast<size_t>(m.cols);
  if (m.cells.size() != n) {
    throw InvalidInput(fmt::format("knitting map is {} x {} but holds {} cells (expected {})", m.rows, m.cols,
                                   m.cells.size(), n));
  }
  if (m.direction.size() != static_cast<size_t>(m.rows)) {
    throw InvalidInput(fmt::format("knitting map has {} rows but {} row directions", m.rows, m.direction.size()));
  }
  if (!m.yarn.empty() && m.yarn.size() != n) {
    throw InvalidInput(fmt::format("knitting map holds {} yarn indices; expected none or {}", m.yarn.size(), n));
  }
  if (m.closed_end && m.seam.empty())
    throw InvalidInput("knitting map: only a tube (a map with seams) can be closed at its end");
  if (!m.seam.empty()) {
    if (m.seam.size() != static_cast<size_t>(m.rows)) {
      throw InvalidInput(fmt::format("knitting map has {} rows but {} seam entries (expected none or one per row)",
                                     m.rows, m.seam.size()));
    }
    for (int r = 0; r < m.rows; ++r) {
      if (m.seam[static_cast<size_t>(r)] < -1 || m.seam[static_cast<size_t>(r)] >= m.cols) {
        throw InvalidInput(fmt::format("knitting map row {} has seam {}; expected -1 (open row) or a line 0..{}", r,
                                       m.seam[static_cast<size_t>(r)], m.cols - 1));
      }
    }
  }
  for (size_t i = 0; i < n; ++i) {
    if (static_cast<uint8_t>(m.cells[i]) > static_cast<uint8_t>(CellType::Empty)) {
      throw InvalidInput(fmt::format("knitting map cell (row {}, column {}) has an unknown type {}", i / m.cols,
                                     i % m.cols, static_cast<int>(m.cells[i])));
    }
  }
}

std::vector<int> row_columns(const KnittingMap& m, int r) {
  std::vector<int> out(static_cast<size_t>(m.cols));
  const int d = m.direction[static_cast<size_t>(r)];
  if (!m.closed(r)) {
    for (int k = 0; k < m.cols; ++k) out[static_cast<size_t>(k)] = d > 0 ? k : m.cols - 1 - k;
    return out;
  }
  const int s = m.seam[static_cast<size_t>(r)];
  for (int k = 0; k < m.cols; ++k) {
    out[static_cast<size_t>(k)] = d > 0 ? (s + k) % m.cols : ((s - 1 - k) % m.cols + m.cols) % m.cols;
  }
  return out;
}

std::vector<std::pair<int, int>> closing_pairs(const KnittingMap& map) {
  std::vector<std::pair<int, int>> pairs;
  if (!map.tubular() || map.rows == 0) return pairs;
  const int r = map.rows - 1, h = map.tube_half();
  std::vector<int> front, back;
  for (int c = 0; c < h; ++c)
    if (is_stitch(map.at(r, c))) front.push_back(c);
  for (int c = map.cols - 1; c >= h; --c)
    if (is_stitch(map.at(r, c))) back.push_back(c);
  if (front.empty() || front.size() != back.size()) return pairs;
  for (size_t i = 0; i < front.size(); ++i) pairs.emplace_back(front[i], back[i]);
  return pairs;
}

}  // namespace knitforge
