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
///
/// Tubes (docs/tubes.md). A map with a non-empty `seam` array is *tubular*:
/// its columns go once round the tube, columns 0..cols/2-1 are the front half
/// (the front needle bed, left to right) and cols/2..cols-1 the back half
/// (the back bed, continuing the round from the right fold back to the left
/// fold), drawn side by side as knitting software draws a tube. A row with
/// seam[r] >= 0 is *closed*: a round whose cells are read as a loop (column
/// cols-1 is followed by column 0). Its stitches are knitted from the seam
/// line seam[r] (the grid line left of column seam[r]; line 0 is the left
/// fold) once round in the row's direction: for +1 the first stitch is the
/// first at or right of column seam[r], for -1 the first at or left of
/// column seam[r]-1 (cyclically). A row with seam[r] == -1 is open (a short
/// row on part of the round, e.g. a heel) and is read as in a sheet. A map
/// with an empty `seam` array is a sheet: every row open.

#include <cstdint>
#include <utility>
#include <vector>

#include "knitforge/core/stitch.h"

namespace knitforge {

struct KnittingMap {
  int rows = 0;
  int cols = 0;
  std::vector<CellType> cells;    ///< rows*cols, row-major, row 0 = first course
  std::vector<int8_t> direction;  ///< per row: +1 left to right, -1 right to left
  std::vector<int> yarn;          ///< empty (every cell yarn 0) or rows*cols yarn indices
  /// Empty for a sheet; for a tube one entry per row: -1 open row, else the
  /// seam line (0..cols-1) where the closed row (round) starts.
  std::vector<int> seam;
  /// A tube closed after its last round (docs/tubes.md, "Closed tubes": a
  /// beanie's crown, a sock's toe): the last round's loops are joined
  /// pairwise across the beds (closing_pairs()) and bound off, a seam
  /// across the top. False for a sheet and an open-ended tube.
  bool closed_end = false;

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

  /// True when the map is a tube (a non-empty seam array).
  bool tubular() const { return !seam.empty(); }
  /// True when row r is a closed row (a round of a tube).
  bool closed(int r) const { return !seam.empty() && seam[static_cast<size_t>(r)] >= 0; }
  /// The first column of a tube's back half (cols / 2).
  int tube_half() const { return cols / 2; }
  /// True when column c of a tube lies on the back bed.
  bool on_back(int c) const { return tubular() && c >= cols / 2; }

  bool operator==(const KnittingMap& o) const;
};

/// Checks that the map's arrays agree with rows x cols (cells, one direction
/// per row, no or rows*cols yarn indices, no or rows seams, each -1 or a
/// line 0..cols-1; closed_end only on a tube) and every cell has a known type.
/// \throw InvalidInput saying which array is wrong, or the cell (row, column).
void check_map_arrays(const KnittingMap& map);

/// The pairs a closed tube's last round is joined in (KnittingMap::
/// closed_end): its front wales (stitch cells of columns 0..cols/2-1) from
/// the left fold to the right, each with the back wale opposite it when the
/// tube is laid flat, the back wales also counted from the left fold (the
/// largest column first). {front column, back column} per pair, left to
/// right. Empty unless the halves of the last row hold equally many stitches
/// (at least one each).
std::vector<std::pair<int, int>> closing_pairs(const KnittingMap& map);

/// The columns of row r in knitting order: every column of the row (stitch
/// or not) in the order the carriage passes it. Open rows: 0..cols-1 for
/// direction +1, cols-1..0 for -1. Closed rows: once round from the seam
/// line in the row's direction (see KnittingMap). Callers skip the cells
/// that are not stitches.
/// \pre check_map_arrays(map) passes and the row direction is +1 or -1.
std::vector<int> row_columns(const KnittingMap& map, int r);

}  // namespace knitforge
