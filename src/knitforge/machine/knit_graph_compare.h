#pragma once
/// \file knit_graph_compare.h
/// "It knits what was designed": checks that the knit graph a simulated
/// program makes (knitout_simulate.h) is the fabric of a knitting map
/// (docs/machines.md, "The simulator").
///
/// Fabric loops: the loops formed in fabric sections (not after a `; cast-on`,
/// `; bind-off` or `; waste` comment until the next `; course`/`; row`
/// comment, see knit_graph.h) by `knit` or `split`, plus `tuck`s on an empty
/// needle in a pass that also knits (the first loop of a wale, e.g. an
/// increase). Tucks on a needle that holds loops (short-row turn closures),
/// passes of tucks only (a tuck cast-on) and every loop of the other
/// sections are not fabric loops. The k-th fabric loop in
/// formation (yarn) order is matched to the k-th stitch of
/// map_to_stitch_mesh_topology(map) (knitting order).
///
/// Checks, per matched pair (loop L, stitch S at map cell (row, column)):
///  - count: as many fabric loops as map stitches;
///  - direction: L was formed in the direction of S's map row;
///  - course: when the next stitch is S's course neighbour, the next loop
///    lies further along the bed in that direction (by slot: a back needle
///    counts at its position under the racking; same course, in order);
///    when the next stitch starts another course, the row turns there too;
///  - wale: L's fabric parents are exactly {loop of S's Bottom neighbour}
///    (none when S has no Bottom neighbour: cast-on row, increase) plus the
///    loops of stitches whose wale ends (no Top neighbour: a Decrease, or an
///    outside decrease at the fabric edge) with a top corner on S's bottom
///    edge (a decrease's loop is pulled through by the neighbouring wale),
///    plus the loop of the previous stitch of S's course when that stitch
///    ends its wale with a free top (no later stitch touches it): an edge
///    bind-off chain, knit and pass over (needle_layout.h);
///  - decreases: the loop of a stitch without Top neighbour whose top
///    corner is on the bottom edge of a later stitch is pulled through by the
///    fabric loop of such a stitch.
/// Tubes (KnittingMap::seam, docs/tubes.md): the stitches of the back half
/// must be knitted on the back bed ("bed"), in the machine direction opposite
/// to their row's ("direction"); the course check compares consecutive
/// stitches on one bed (each in its machine direction) and skips the step
/// across a fold. A tube's end ("closing"): when the map is closed at its
/// end (KnittingMap::closed_end), the loops of each closing pair
/// (closing_pairs()) are pulled through together by one loop that takes
/// nothing else (the closing seam, knitted in the bind-off section); when it
/// is open, no loop pulls through two loops of the last round that are not
/// neighbours in it (an open tube's chain bind-off joins neighbours only).
/// Maps whose rows are knitted with several yarns at once (jacquard) are not
/// covered: formation order is then not the map's knitting order.

#include <string>
#include <vector>

#include "knitforge/core/knitting_map.h"
#include "knitforge/machine/knit_graph.h"

namespace knitforge {

/// One disagreement between the knit graph and the map.
struct GraphMismatch {
  std::string kind;   ///< "count", "bed", "direction", "course", "wale", "decrease", "closing"
  int stitch = -1;    ///< map stitch index (knitting order), -1 when none
  int row = -1, col = -1;  ///< its map cell
  int loop = -1;      ///< knit graph loop, -1 when none
  int line = 0;       ///< knitout line that formed the loop, 0 when none
  std::string message;
};

struct GraphComparison {
  int map_stitches = 0;
  int fabric_loops = 0;
  int mismatches = 0;                 ///< total (issues keeps the first max_issues)
  std::vector<GraphMismatch> issues;
  bool ok() const { return mismatches == 0; }
  /// Verdict and the kept mismatches, one per line.
  std::string text() const;
};

struct CompareOptions {
  int max_issues = 50;  ///< mismatches kept in GraphComparison::issues (<= 0: all)
};

/// The fabric loops of `graph` (see the file comment), in formation order.
std::vector<int> fabric_loops(const KnitGraph& graph);

/// Compares `graph` with the fabric of `map` (see the file comment).
/// \throw InvalidInput as map_to_stitch_mesh_topology() when the map is invalid.
GraphComparison compare_knit_graph(const KnitGraph& graph, const KnittingMap& map,
                                   const CompareOptions& options = {});

}  // namespace knitforge
