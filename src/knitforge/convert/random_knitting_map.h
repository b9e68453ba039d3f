#pragma once
/// \file random_knitting_map.h
/// Random canonical, knittable knitting maps for tests and benchmarks.
///
/// The map is built course by course (docs/convert.md, "Random maps"):
///  - every map row is one course or short row, directions alternate
///    (row 0 left to right) and each row starts in the column where the
///    previous one ended (one-stroke continuity, seed §1.2.2);
///  - a short-row turn at column k between rows r and r+1 puts two stacked
///    short-row-end triangles at (r, k) and (r+1, k) (ShortRowRight when the
///    turn is on the right, ShortRowLeft on the left); turns are never at the
///    fabric edge (no boundary apex), the same side/column never turns twice
///    in succession, and a column takes a new turn pair only after its wale
///    knitted a regular stitch since its last one (no four stacked short-row
///    ends); rows 0 and rows-1 are full courses;
///  - a short column occupies one map column between an Increase (its start)
///    and a Decrease (its end); either end may instead run to the bottom or
///    top edge, never both. Short columns keep away from the fabric edge
///    (see short_columns) and span at least a quarter of the rows;
///    neighbouring short columns overlap in rows so their left to right
///    order is fixed by the mesh; no two increases (or two decreases) are
///    neighbours in a course;
///  - optional boundary shaping widens the fabric by outside increases in the
///    bottom band of rows and narrows it by outside decreases in the top band
///    (max(3, rows/5) rows each; short rows then stay in the middle rows);
///  - cells the fabric skips are Collapsed when they lie between two stitches
///    of their row or column, otherwise Empty (canonical form, see
///    docs/representations.md), so map -> stitch mesh -> map is the identity.
/// The result is checked (stitch mesh topology, round trip and
/// check_knittability()) before it is returned; a construction that fails
/// the check is redrawn from the next random stream.
///
/// Deterministic: the same options (including the seed) give the same map.

#include <cstdint>

#include "knitforge/core/knitting_map.h"

namespace knitforge {

struct RandomMapOptions {
  uint64_t seed = 1;         ///< random seed (explicit; no hidden randomness)
  int rows = 20;             ///< map rows (courses and short rows), >= 4
  int cols = 20;             ///< map columns, >= 6 (more with shaping)
  /// Number of short-row-end stitches (triangles), even: every short-row turn
  /// makes a stacked pair. At most 2 * (rows - 3); with boundary shaping
  /// 2 * (rows - 2 * b - 2), b = max(3, rows / 5) the rows of each shaped
  /// band. Very narrow maps may not fit that many (InvalidInput).
  int short_row_ends = 0;
  /// Number of short columns (each one column, one Increase and/or one
  /// Decrease). Short columns stay 1 column away from the fabric edge (3 when
  /// short rows are requested, so a short row can always turn beyond their
  /// increases and decreases): at most cols - 2 (cols - 6 with short rows),
  /// less the shaping width on each side with boundary shaping.
  int short_columns = 0;
  /// Widen the fabric in the bottom fifth and narrow it in the top fifth by
  /// outside increases / decreases at the course ends (the fabric starts
  /// narrower and reaches column 0 and cols-1 at the end of the bottom band).
  /// Needs rows >= 12 and cols >= 10; smaller maps are left unshaped.
  bool boundary_shaping = false;
};

/// A random canonical, knittable knitting map (see the file comment).
/// \throw InvalidInput when rows/cols are too small or the requested numbers
///        of short-row ends or short columns do not fit (the message says the
///        maximum), or no valid map was found for this seed (retry another).
KnittingMap random_knitting_map(const RandomMapOptions& options);

}  // namespace knitforge
