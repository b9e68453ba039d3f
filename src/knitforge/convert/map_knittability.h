#pragma once
/// \file map_knittability.h
/// Knittability check of a knitting map (seed §1.2.2: "to check if a
/// knitting map is valid, we may check the knittability of the stitch mesh
/// converted from it").

#include "knitforge/core/knit_params.h"
#include "knitforge/core/knittability.h"
#include "knitforge/core/knitting_map.h"

namespace knitforge {

/// Checks a knitting map. First the map-level problems that keep it from
/// being a stitch mesh at all, each reported with its cells (row, col) and
/// never thrown:
/// - invalid-direction: a row direction other than +1 / -1 (cell col = -1);
/// - invalid-yarn: a cell with a negative yarn index;
/// - empty-row: a row without any stitch (cell col = -1);
/// - split-row: two consecutive stitches of a row are not one run: an Empty
///   cell lies between them, or the left one has no Right side / the right
///   one no Left side (a short-row end inside the row); lists both cells;
/// - collapsed-crossing: a Collapsed cell between two stitches of its row and
///   between two stitches of its column (nearest non-Collapsed cells with the
///   facing sides, docs/representations.md).
/// Tubes (KnittingMap::seam, docs/tubes.md) add:
/// - tube-layout: an odd number of columns or fewer than 4; row 0 or the last
///   row open (cell col = -1); a tube closed at its end (closed_end) whose
///   last round's halves hold different numbers of stitches (no
///   closing_pairs());
/// - closed-row: a round holding a short-row end or an Empty cell (the cell);
///   the split-row check is left to this for rounds;
/// - tube-shaping: a half of a round with fewer than 2 stitches (cell col =
///   -1), an open row covering every column (its two end cells);
/// and the mesh check runs with KnittabilityOptions::closed_courses (a round
/// is no cyclic-row; between-row-continuity follows the knitting order).
/// When there are none, the map is converted with
/// map_to_stitch_mesh_topology() (a conversion failure, e.g. a stitch whose
/// corners merge or a non-manifold corner, is reported as map-topology with
/// the converter's message) and the mesh is checked with
/// check_knittability(const StitchMesh&); its violations list the map cells
/// of the stitches involved. Positions are in mm in the flat map layout
/// (cell (r, c) centred at ((c + 0.5) w, (r + 0.5) h, 0)).
///
/// \throw InvalidInput when the map's arrays have inconsistent sizes
///        (cells != rows * cols, direction != rows, yarn neither empty nor
///        rows * cols), rows or cols is negative, the stitch size is not
///        positive, or opt.max_violations < 0.
KnittabilityReport check_knittability(const KnittingMap& map, const KnitParams& params = {},
                                      const KnittabilityOptions& opt = {});

}  // namespace knitforge
