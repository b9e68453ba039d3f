#pragma once
/// \file knitting_map.h
/// KnittingMap: the knitting instructions as a rectangular grid (seed §1.2.1).
///
/// Row r is the r-th course knitted (row 0 at the bottom is knitted first),
/// column c counts from the left. Every map row holds one course or short row:
/// its stitches, in the row's direction, are knitted one after another.
/// Collapsed cells are grid positions the fabric skips (a wale passing a
/// short row that does not reach it, or a row passing a short column that has
/// not started or has ended); Empty cells lie outside the fabric.

#include <cstdint>
#include <vector>

#include "knitforge/core/stitch.h"

namespace knitforge {

struct KnittingMap {
  int rows = 0;
  int cols = 0;
  std::vector<CellType> cells;    ///< rows*cols, row-major, row 0 = first course
  std::vector<int8_t> direction;  ///< per row: +1 left to right, -1 right to left
  std::vector<int> yarn;          ///< empty (every cell yarn 0) or rows*cols yarn indices

  KnittingMap() = default;
  /// A rows x cols map filled with `fill`; directions alternate, row 0 going
  /// left to right (the seed's convention).
  KnittingMap(int rows, int cols, CellType fill = CellType::Empty);

  bool contains(int r, int c) const { return r >= 0 && r < rows && c >= 0 && c < cols; }
  CellType at(int r, int c) const { return cells[static_cast<size_t>(r) * cols + c]; }
  CellType& at(int r, int c) { return cells[static_cast<size_t>(r) * cols + c]; }
  int yarn_at(int r, int c) const { return yarn.empty() ? 0 : yarn[static_cast<size_t>(r) * cols + c]; }
  /// Sets the yarn of a cell, allocating the per-cell yarn array on first use.
  void set_yarn(int r, int c, int y);

  /// Number of stitch cells (not Collapsed or Empty).
  int num_stitches() const;

  bool operator==(const KnittingMap& o) const;
};

/// Checks that the map's arrays agree with rows x cols (cells, one direction
/// per row, no or rows*cols yarn indices) and every cell has a known type.
/// \throw InvalidInput saying which array is wrong, or the cell (row, column).
void check_map_arrays(const KnittingMap& map);

}  // namespace knitforge
