#pragma once
/// \file rasterize_pattern.h
/// From a flattened 2D pattern to a knittable knitting map (seed §2.3.2).
///
///  1. Bitmap: cells of sw x 2sh (sw x sh the stitch size); a cell is
///     fabric when its centre lies in the pattern.
///  2. Long rows (optional, seed: "to stabilize the casting-on and
///     binding-off"): when the first bitmap row is narrower than the rows
///     just above it or has gaps (branches), a full row over their extent is
///     added below it; the same at the top. When that end row is a single
///     run next to a row of two branches (the tip of one branch), the long
///     row takes its place, so the notch between the branches ends at it.
///  2b. Holes and branches. A hole is a 4-connected set of non-pattern cells
///     that does not reach the bitmap's border. A vertical one (taller than
///     wide in mm: a vertical dart) that is closed off only by an added long
///     row is opened through that row again: a vertical one-end dart opening
///     at the bottom / top edge, closed by short columns that start /
///     end there. A horizontal one (a horizontal two-end dart, or the notch
///     between branches under / over a long row) whose rows a..b each split
///     into a left and / or a right segment around it becomes a *band*
///     (seed: "each row contains two short-rows. We process all right-side
///     short-rows first and then jump to the left-side short-rows"):
///       map rows: (a-1) -> | right segments of rows a..b, each a short-row
///       pair <- -> turning at the hole | (a-1) <-, crossing under the hole
///       | left segments of rows a..b, each a pair -> <- | row b+1 ...
///     So the wales under the hole go from row a-1 straight to row b+1 (the
///     dart is closed), both sides get their rows as short rows, and every
///     row starts where the previous one ended. The map has 2 (b-a+1) more
///     rows than bitmap rows per band; cell_pattern_row says where each
///     cell lies in the pattern. A hole whose rows do not split that way,
///     or where a column is left of the hole in one row and right of it in
///     another, stays a gap (step 4).
///  3. Rows split in two: bitmap row i gives map rows 2i (knitted left to
///     right) and 2i+1 (right to left), both ending at the bitmap row's right
///     end, so the right ends are aligned; the left ends of rows 2i+1 and
///     2i+2 are extended to the smaller of the two (continuity: each row
///     starts where the previous one ended). In general (bands): map rows
///     m (->) and m+1 (<-) share their right end, m (<-) and m+1 (->) their
///     left end, extended to the longer of the two.
///  4. Darts become shaping stitches, per docs/representations.md:
///     - cells outside a row between fabric below and above in their column
///       (a horizontal dart's wedge, a band's hole, a widening or narrowing
///       side) are Collapsed: the wale passes a short row that is not there;
///       the row's end stitch next to them is a ShortRowRight / ShortRowLeft
///       (the two rows of a turn form the pair the checker wants);
///     - gaps inside a row (a vertical dart, a vertical hole) are Collapsed
///       between two stitches of the row: the row passes a short column that
///       is not there; the stitch below such a gap is a Decrease (its wale
///       ends), the one above an Increase.
///  5. Repairs, until none applies: a cell that would need two shaping types
///     gets its gap filled or its row pair extended; two neighbouring
///     increases / decreases in a row get one gap cell filled (the one
///     nearer the end of its gap run), so gaps narrow by at most one column
///     per row; two consecutive turn pairs in the same column (four stacked
///     short-row ends) get the upper pair extended by one stitch; a gap
///     whose column also holds cells outside the rows is filled.
///
/// What is still filled (RasterizedPattern::filled_gap_cells, said in
/// docs/flatten.md): gap cells where a vertical dart's legs open faster than
/// one column per map row (typically its mouth at the pattern's edge), and,
/// with long_rows off, notches between branches at the ends.
///
/// The result is checked with check_knittability() (convert/
/// map_knittability.h) by the caller; rasterize_pattern() itself only
/// guarantees a map with consistent arrays.
#include <vector>
#include "knitforge/core/knit_params.h"
#include "knitforge/core/knitting_map.h"
#include "knitforge/geometry/tri_mesh.h"
#include "knitforge/geometry/vec.h"

namespace knitforge {

struct RasterizeOptions {
  bool long_rows = true;     ///< add long rows at the bottom / top when needed (step 2)
  int long_row_band = 3;     ///< bitmap rows compared with the first / last one (>= 1)
  int max_repairs = 200000;  ///< cap on repair steps (InvalidInput beyond)
};

/// The knitting map and how it sits on the pattern.
struct RasterizedPattern {
  KnittingMap map;
  /// Pattern coordinates (mm) of the map's grid corner V(0, 0): map cell
  /// (r, c) covers [origin.x + c sw, + sw] x [origin.y + p sh, + sh] with
  /// p = cell_pattern_row[r * cols + c] (p = r when short_row_holes == 0).
  Vec2 origin = Vec2::Zero();
  int bitmap_rows = 0;  ///< including added long rows
  int bitmap_cols = 0;
  int pattern_cells = 0;     ///< bitmap cells inside the pattern
  int added_long_rows = 0;   ///< 0, 1 (bottom or top) or 2
  int extended_cells = 0;    ///< map cells added by the left-end extension
  int filled_gap_cells = 0;  ///< gap cells turned into fabric by repairs
  int shifted_turns = 0;     ///< turn pairs moved to avoid stacked short-row ends
  int short_row_holes = 0;   ///< bands: horizontal holes / branches knitted right side, then left (step 2b)
  /// Per map cell (row-major, rows x cols): the row of the pattern grid, in
  /// stitch heights from origin.y, where the cell's bottom lies. Equal to
  /// the map row when there is no band; inside a band the rows of one side
  /// are knitted after those of the other, so the map row and the pattern
  /// row differ there.
  std::vector<int> cell_pattern_row;
};

/// Rasterises the pattern uv of mesh (see the file comment).
/// \throw InvalidInput when the stitch size is not positive, uv has the
///        wrong size or non-finite entries, the pattern covers no cell
///        centre, a bitmap row between covered rows is empty (the pattern is
///        thinner than 2 stitch heights there: use a smaller stitch or a
///        finer mesh), or the repairs do not settle.
RasterizedPattern rasterize_pattern(const TriMesh& mesh, const std::vector<Vec2>& uv,
                                    const KnitParams& params, const RasterizeOptions& options = {});

}  // namespace knitforge
