#pragma once
/// \file tube_layout.h
/// Where every wale of a tubular knitting map (KnittingMap::seam,
/// docs/tubes.md) sits on the two needle beds, course by course, and which
/// transfers move it there: the tube counterpart of needle_layout.h, used by
/// the knitout writer for tubes.
///
/// Beds. The front half (columns 0..cols/2-1) is knitted on the front bed,
/// the back half (cols/2..cols-1) on the back bed, each on **every other
/// needle**: a front wale at slot p sits on front needle 2p, a back wale at
/// slot p on back needle 2p+1. The needles between are empty on both beds,
/// so a loop can always be parked on the other bed (a front loop on back
/// needle 2p, a back loop on front needle 2p+1) and brought back racked:
/// shaping transfers stay possible at every row, as on a sheet. Front wales
/// take slots in column order (left to right), back wales in reverse column
/// order (column cols/2 at the right fold, column cols-1 at the left fold), so
/// the round runs front left to right, then back right to left.
///
/// Wales alive at a row (alive_wales(): a stitch, or a loop held through a
/// short row) keep consecutive slots on their bed. Between row r and r+1,
/// each bed changes as a sheet does (needle_layout.h), independently:
///  - a starting wale (an Increase) gets an empty slot between its
///    neighbours; its first stitch is a tuck on that empty needle;
///  - an ending wale (a Decrease) merges onto a continuing wale of the same
///    bed that takes its loop (WaleTakers), the neighbour towards the bed's
///    pivot first (the other one when that needle would hold more than
///    max_stack loops); across the fold the loop is never moved;
///  - the pivot (the continuing wale nearest slot 0) stays; the others close
///    up or open round it.
/// A slot displacement d moves a loop 2d needles: a front loop goes to the
/// back bed at racking 0 and returns at racking 2d; a back loop goes to the
/// front at racking 0 and returns at racking -2d. Displacements larger than
/// max_racking/2 slots are split into steps as in needle_layout.h; in each
/// step the moves of both beds share the racking passes.
///
/// Short rows (open rows of the tube): the row knits part of the round and
/// turns when the next row runs the other way; the first held wale beyond
/// its end (cyclically, in the row's direction) is its closure wale, tucked
/// as on a sheet while its needle then holds at most max_closure_loops loops.
///
/// Problems (recorded, not thrown, as in needle_layout.h): a bed whose every
/// wale ends at once, an ending wale no wale of its bed takes (a decrease
/// whose only neighbour lies across the fold), a merge beyond max_stack,
/// a wale ending with a free top (a tube has no edge to chain along).
///
/// Needle numbers are relative (course 0 centred on needle 0); writers add
/// an offset (any integer: the beds keep their parity).

#include <cstdint>
#include <vector>

#include "knitforge/core/knitting_map.h"
#include "knitforge/machine/needle_layout.h"

namespace knitforge {

/// One loop stack moving in a tube transfer step (needle numbers on its bed).
struct TubeMove {
  int col = -1;       ///< the wale whose loops move
  bool back = false;  ///< the wale lies on the back bed
  int from = 0;       ///< needle before the step
  int to = 0;         ///< needle after the step (same bed)
};

/// The layout change between row r-1 and row r of a tube.
struct TubeTransition {
  std::vector<int> starts;          ///< wales starting at row r
  std::vector<LayoutMerge> merges;  ///< wales ending after row r-1, onto a wale of their bed
  /// Transfer steps in order, each a list of moves sorted by (bed, from).
  std::vector<std::vector<TubeMove>> steps;
};

/// Options of plan_tube_layout().
struct TubeLayoutOptions {
  int max_racking = 4;        ///< the machine's racking limit (>= 2: one slot is two needles)
  int max_stack = 3;          ///< most loops on a needle after a merge, >= 2
  bool close_turns = true;    ///< closure tucks at short-row turns
  int max_closure_loops = 2;  ///< most loops a held needle may hold after a closure tuck
};

/// The needle layout of a tube.
struct TubeLayout {
  int rows = 0;
  int cols = 0;
  /// rows*cols: the wale's needle (on its bed) while row r is knitted,
  /// kNoNeedle when the wale is not alive at row r.
  std::vector<int> needle;
  std::vector<TubeTransition> transitions;  ///< size rows; transitions[r] precedes row r
  std::vector<int> closure_col;             ///< per row: the held wale tucked after the row's turn, -1 none
  std::vector<uint8_t> inside_turn;         ///< per row: the row is a short row that turns
  std::vector<LayoutProblem> problems;
  int open_turns = 0;
  int min_needle = 0, max_needle = 0;  ///< needle range over both beds and all steps
  int increases = 0, decreases = 0;
  int loop_moves = 0;                  ///< moves over all steps (each two transfers)

  int needle_at(int r, int c) const { return needle[static_cast<size_t>(r) * cols + c]; }
  bool alive(int r, int c) const { return needle_at(r, c) != kNoNeedle; }
};

/// Plans the tube layout (see the file comment).
/// \throw InvalidInput when the map is not tubular or not a valid map (as
///        map_to_stitch_mesh_topology()), or an option is out of range.
TubeLayout plan_tube_layout(const KnittingMap& map, const TubeLayoutOptions& options = {});

}  // namespace knitforge
