#pragma once
/// \file pack_tube_columns.h
/// The canonical columns of a tubular knitting map (docs/tubes.md): the same
/// fabric with each half's wales in as few columns as their order allows.
///
/// Where a tube's map puts a column that holds no stitch in some rounds (a
/// wale not yet started by an increase, or ended by a decrease, or a column
/// that stays empty because the other half is wider) is not part of the
/// fabric: the stitches, their knitting order and their neighbours are the
/// same wherever those Collapsed cells lie. A knitting program therefore
/// fixes a tube's map only up to that choice; this function makes it (as
/// knit_graph_fabric() reads a program back, machine/knit_graph_to_map.h).
///
/// Wales. A column's stitch cells form one wale from one stitch to the next
/// one above it unless the lower is a Decrease or the upper an Increase, or
/// an Empty cell lies between (Collapsed cells between are the wale held
/// through short rows). A wale is alive from its first to its last stitch
/// row, and a wale ended by a Decrease keeps its column one row more (so
/// that no increase starts on a decrease's apex). Within each half, two
/// wales alive in one row keep their order.
///
/// Columns. Each half's wales get the smallest columns that keep, in every
/// row, the alive wales in their order with one column each: a wale's
/// column (counted from the half's first column, the left fold for the
/// front half and the right fold for the back half) is the length of the
/// longest chain of wales before it, each alive with the next in some row
/// and next to it there (a longest-path layering). Wales that are never
/// alive together may share a column. Both halves are as wide as the wider
/// one needs; the narrower ends in columns that hold no stitch. Every row
/// keeps its direction, every closed row its first stitch and so its seam
/// (made canonical), the yarn of every cell and closed_end; the result is
/// canonical_cells() of that layout. The stitches, their knitting order,
/// types and neighbours in map_to_stitch_mesh_topology() are unchanged
/// (tested). Packing a packed map changes nothing.

#include "knitforge/core/knitting_map.h"

namespace knitforge {

/// The tube with its columns packed (see the file comment).
/// \throw InvalidInput when the map is not tubular, or not a valid map
///        (map_to_stitch_mesh_topology()).
KnittingMap pack_tube_columns(const KnittingMap& map);

}  // namespace knitforge
