#pragma once
/// \file knit_graph_to_map.h
/// The fabric a knitout program makes, as a knitting map (docs/machines.md,
/// "A fabric view of any program"): the inverse of the knitout writer for
/// sheets and for tubes knitted in the round (shaped, short rows, closed).
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
/// Tubes (docs/tubes.md). A fabric with stitches on both beds is first read
/// as a tube, in the tubular map's terms (KnittingMap::seam): the front bed
/// is the front half, the back bed the back half, and a stitch goes +1 round
/// the tube when it is knitted + on the front or - on the back.
///  - Wales as for sheets; a wale that changes beds is no tube's.
///  - Rows: the stitches fall into strokes, runs with one carrier set going
///    one way round, each further round than the last (on its bed, or
///    across a fold). A stroke is cut into rows that knit no wale twice and
///    no stitch through another of the same row: a *round* holds every wale
///    alive across it (a stitch at or before its end and one at or after its
///    start; the others are held), a *short row* (open row) holds part of
///    them, does not cross the left fold (line 0) and is neither the first
///    nor the last row. The cut takes the longest rows from the stroke's end
///    (rounds as late as possible: a wedge's last short row, then the
///    rounds from the new seam), else from its start.
///  - Columns: each bed's wales in the left-to-right order every row agrees
///    on (a cycle is a cable), the front half left to right, the back half
///    from the right fold to the left fold, then packed by
///    pack_tube_columns() (each half in the fewest columns: where a column
///    without stitches lies is not part of the fabric).
///  - Cells: a round's seam is the line before its first stitch; a short
///    row's two ends are ShortRowLeft and ShortRowRight; a wale's first
///    stitch above row 0 is an Increase (a tuck on an empty needle), its
///    last below the last row a Decrease; the rest Knit, Collapsed where a
///    wale is held or a column empty, canonical_cells() finishes.
///  - Closed end (KnittingMap::closed_end): some loop pulls through two
///    loops of the last round that are not neighbours in it (a closing seam
///    across the beds; compare_knit_graph() checks its pairs).
/// The map is kept only when check_knittability() passes and
/// compare_knit_graph() finds the program knits exactly it; kind "tube",
/// `map`, `loop_of_cell` and `cell_of_loop` as for sheets. For knitforge's
/// own tube programs it is the tube writer's inverse up to packed columns:
/// knit_graph_fabric(write_knitout(M)) == pack_tube_columns(M), with
/// increases, decreases, short rows, moving seams and closed ends (tested).
/// When every row is a round of the same stitches (a plain tube) the tube is
/// also described as `rounds` x `ring` stitches (loop_of_round_stitch); so
/// is a program knitting plain rounds front pass, back pass, ... whose map
/// is refused (then `reason` says why there is no map). Otherwise a two-bed
/// fabric is tried as a sheet (a double knit), and when it is neither the
/// reason gives both: "neither a tube (...) nor a sheet (...)". Not
/// covered, as for sheets: rounds knitted by several carriers at once
/// (jacquard). Untested: a decrease moved across a fold (the tube writer
/// never makes one).

#include <string>
#include <vector>

#include "knitforge/core/knitting_map.h"
#include "knitforge/machine/knitout_simulate.h"

namespace knitforge {

struct KnitGraphFabric {
  /// What the fabric is: "sheet" (map is valid), "tube" (map is its tubular
  /// map, or only rounds x ring for plain rounds without one), or "" when it
  /// is neither (reason says why).
  std::string kind;
  std::string reason;
  std::vector<int> stitch_loops;  ///< the stitch loops, in formation order
  // --- sheets (and tubes with a map) ---
  KnittingMap map;                ///< canonical and knittable when set (every sheet, every tube but plain rounds without a map)
  std::vector<int> loop_of_cell;  ///< rows*cols: the loop of each stitch cell, -1 elsewhere
  std::vector<int> cell_of_loop;  ///< per graph loop: row*cols+col of its cell, -1 when not a stitch
  // --- plain tubes (every row a round of the same stitches; 0 otherwise) ---
  int rounds = 0;                 ///< rounds of the tube
  int ring = 0;                   ///< stitches per round
  std::vector<int> loop_of_round_stitch;  ///< rounds*ring loops, each round in knitting order
};

/// The fabric of `sim` (see the file comment). Never throws on a program's
/// content: a fabric that is neither a sheet nor a tube comes back with
/// kind "" and the reason.
KnitGraphFabric knit_graph_fabric(const KnitoutSimulation& sim);

}  // namespace knitforge
