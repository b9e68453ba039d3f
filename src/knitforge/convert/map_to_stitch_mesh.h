#pragma once
/// \file map_to_stitch_mesh.h
/// Knitting map -> stitch mesh (seed §1.3.2): the topology by a coarse
/// simulation of the knitting, then the relaxed 3D shape.
///
/// Topology (docs/representations.md, "Map cells and vertex merging"): the
/// grid corners V(i, j), i = 0..rows, j = 0..cols, are merged cell by cell
/// with a union-find (ShortRowLeft BL=TL, ShortRowRight BR=TR, Increase
/// BL=BR, Decrease TL=TR, Collapsed between two stitches of its row BL=BR and
/// TL=TR, Collapsed between two stitches of its column BL=TL and BR=TR).
/// "Between two stitches of its row" means: the nearest non-Collapsed cells
/// to the left and to the right in the row are stitches that have a Right
/// and a Left side respectively (so a ShortRowRight ends a row); likewise in
/// the column with Top and Bottom sides (a Decrease ends a wale, an Increase
/// starts one). Collapsed cells between neither behave as Empty.
///
/// Stitches are numbered in knitting order (row 0 first, each row in its
/// direction; row_columns()); vertices are numbered in order of first use by
/// the stitches.
///
/// Tubes (KnittingMap::seam, docs/tubes.md): in a closed row the grid line
/// cols is line 0 (V(i, cols) and V(i, 0) merge for the row's two grid rows),
/// so its last column is the Left/Right neighbour of its first; Collapsed
/// cells of a closed row are classified cyclically; a closed row's stitches
/// are numbered from its seam; the initial positions lie on a cylinder of
/// circumference cols * stitch_width round the y axis (front half facing +z);
/// closed rows have no outside increase/decrease roles.
/// Initial position of a vertex: the mean of its merged grid corners at
/// (j * stitch_width, i * stitch_height, 0).
///
/// Per stitch: course = map row, wale = map column, yarn = map yarn, direction
/// = row direction, and the boundary roles
///  - kRoleCastOn: the stitch has a Bottom side and no stitch across it;
///  - kRoleBindOff: the stitch has a Top side and no stitch across it;
///  - kRoleOutsideIncrease / kRoleOutsideDecrease: the stitch is the leftmost
///    (rightmost) stitch of its row, row r > 0, and the row's fabric extent
///    (first to last non-Empty cell after canonical_cells()) reaches further
///    left (right) than that of row r-1 (increase) or less far (decrease).

#include "knitforge/convert/relax_stitch_mesh.h"
#include "knitforge/core/knit_params.h"
#include "knitforge/core/knitting_map.h"
#include "knitforge/core/stitch_mesh.h"

#include <vector>

namespace knitforge {

/// The map with every Collapsed cell that lies neither between two stitches
/// of its row nor of its column (see the file comment) replaced by Empty,
/// and every closed row's seam made canonical (the grid line just after the
/// round's last stitch in the row's direction; the knitting order stays the
/// same): the canonical form stitch_mesh_to_map() produces. Other cells are
/// unchanged.
/// \throw InvalidInput as map_to_stitch_mesh_topology() for a Collapsed cell
///        inside both its row and its column, or inconsistent map sizes.
KnittingMap canonical_cells(const KnittingMap& map);

/// The vertex merging of map_to_stitch_mesh_topology() alone: for every grid
/// corner V(i, j), index i * (cols + 1) + j, the id of its merged class
/// (equal ids = one vertex). No stitch is checked for degeneracy, so a
/// caller can ask which corners of a cell the cells around it merge.
/// \throw InvalidInput as canonical_cells().
std::vector<int> map_corner_classes(const KnittingMap& map);

/// The stitch mesh topology of a knitting map with flat initial positions.
/// \throw InvalidInput naming the cell (row, column) when: the map's arrays
///        have the wrong sizes; a row direction is not +1 or -1; a row holds
///        no stitch; a row holds two separate runs of stitches (an Empty cell,
///        or a ShortRowRight / ShortRowLeft that is not the row's last /
///        first stitch, splits it); a closed row holds an Empty cell or a
///        short-row end; a Collapsed cell is inside both its row
///        and its column; a stitch degenerates (two of its corners merge); or
///        the stitches do not form an oriented manifold mesh.
StitchMesh map_to_stitch_mesh_topology(const KnittingMap& map, const KnitParams& params);

/// map_to_stitch_mesh_topology() followed by relax_stitch_mesh() with the
/// z warm-up of `options` (seed Fig. 1.5).
/// \throw as map_to_stitch_mesh_topology() and relax_stitch_mesh().
StitchMesh map_to_stitch_mesh(const KnittingMap& map, const KnitParams& params,
                              const RelaxOptions& options = {});

}  // namespace knitforge
