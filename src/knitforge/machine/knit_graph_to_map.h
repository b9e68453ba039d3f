#pragma once
/// \file knit_graph_to_map.h
/// The fabric a knitout program makes, as a knitting map (docs/machines.md,
/// "A fabric view of any program"): the inverse of the knitout writer for
/// sheets, and the rounds of a plain tube.
///
/// Stitches. The stitch loops of a simulated program (knitout_simulate.h)
/// are the loops formed in fabric sections (see knit_graph.h: a program
/// without section comments is all fabric) by `knit` or `split`, and tucks
/// on an empty needle made in a pass that also knits (an increase); tucks
/// on held needles, cast-on tuck passes and the loops of cast-on, bind-off
/// and waste sections are not stitches.
///
/// Sheets. Rows are runs of stitch loops in formation order made by one
/// carrier set in one direction, each further along the bed than the last
/// (a turn, a change of carrier set or a step back starts a new row). A
/// stitch's wale continues through its *primary* parent: among the parents
/// that are stitches, the one moved by the fewest transfers (ties: the one
/// formed nearest to it on the bed, then the first on the needle); the other
/// stitch parents end their wales there (decreases). Columns are the wales
/// in the left-to-right order every row agrees on (a topological order of
/// "left of" in each row; a cycle, e.g. a cable, is not a sheet). Cells:
/// the stitch cells are Knit, except
///  - the last stitch of a row that ends inside the fabric (a live wale
///    beyond it) and the first stitch of the next row on the same wale: a
///    short-row turn (ShortRowRight when the row went right, ShortRowLeft
///    when it went left);
///  - a wale's first stitch above the first row with live wales on both
///    sides: Increase (at the fabric edge it is an outside increase, Knit);
///  - a wale's last stitch below the last row whose loop is taken by another
///    wale, with live wales on both sides in the next row: Decrease;
/// a live wale with no stitch in a row (held through a short row) and a gap
/// inside a row are Collapsed, the rest Empty; canonical_cells() finishes.
/// The map is accepted only when check_knittability() passes and
/// compare_knit_graph() finds the program knits exactly this map.
///
/// Tubes. When the rows alternate between the two beds and every row's
/// stitches are on one bed (circular knitting: front pass, back pass, ...),
/// each front row and the back row after it form one round; the tube is
/// described by `rounds` x `ring` stitches (loop_of_round_stitch). Only
/// plain tubes (every round the same stitches) are described. When the two
/// halves of a round have equal stitch counts, the tube also comes as its
/// tubular map (KnittingMap::seam, docs/tubes.md: the front half in columns
/// 0..ring/2-1, the seam where the rounds start), kept only when
/// compare_knit_graph() finds the program knits exactly that map; `map`,
/// `loop_of_cell` and `cell_of_loop` are then set as for sheets.

#include <string>
#include <vector>

#include "knitforge/core/knitting_map.h"
#include "knitforge/machine/knitout_simulate.h"

namespace knitforge {

struct KnitGraphFabric {
  /// What the fabric is: "sheet" (map is valid), "tube" (rounds), or "" when
  /// it is neither (reason says why).
  std::string kind;
  std::string reason;
  std::vector<int> stitch_loops;  ///< the stitch loops, in formation order
  // --- sheets (and tubes with a map) ---
  KnittingMap map;                ///< canonical and knittable when kind == "sheet" (or a tube's map, see above)
  std::vector<int> loop_of_cell;  ///< rows*cols: the loop of each stitch cell, -1 elsewhere
  std::vector<int> cell_of_loop;  ///< per graph loop: row*cols+col of its cell, -1 when not a stitch
  // --- tubes ---
  int rounds = 0;                 ///< rounds of the tube
  int ring = 0;                   ///< stitches per round
  std::vector<int> loop_of_round_stitch;  ///< rounds*ring loops, each round in knitting order
};

/// The fabric of `sim` (see the file comment). Never throws on a program's
/// content: a fabric that is neither a sheet nor a plain tube comes back
/// with kind "" and the reason.
KnitGraphFabric knit_graph_fabric(const KnitoutSimulation& sim);

}  // namespace knitforge
