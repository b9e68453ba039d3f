#pragma once
/// \file needle_layout.h
/// Where every wale of a knitting map sits on the needle bed, course by
/// course, and which loop transfers move it there (seed §1.4.1-1.4.2,
/// Fig. 1.8). Shared by the knitout writer and the hand-machine instructions.
///
/// Model. A map column is a wale. Wale c is *alive* at row r when cell (r, c)
/// is a stitch or a Collapsed cell between two stitches of its column (the
/// wale passes a short row that does not reach it: its loop is held on its
/// needle). While row r is knitted, the loops of the alive wales sit on
/// consecutive front-bed needles in column order; the row's stitches are a
/// consecutive run of them (a valid map cannot hold a held wale inside a row).
///
/// Between row r and row r+1 the layout changes:
///  - a wale alive at r+1 but not at r *starts* (an Increase, or a new wale at
///    the fabric edge: outside increase) and needs an empty needle between its
///    neighbours; its first stitch is made on that empty needle;
///  - a wale alive at r but not at r+1 *ends* (a Decrease, or a wale whose
///    column stops at the fabric edge: outside decrease); its loops are moved
///    onto the needle of a continuing neighbour, so the next stitch of that
///    neighbour is knitted through both (knit two together);
///  - everything else keeps its order and closes up to consecutive needles.
///
/// Where an ending wale goes. The map's stitch mesh says which later
/// stitches take the loop of a wale's last stitch: those whose bottom edge
/// touches its top (a Decrease's apex, or the top corner of an edge wale next
/// to the wale that continues). When such a stitch exists, the loops merge
/// onto its wale. A wale whose top touches no later stitch (the fabric edge
/// narrows there: an outside decrease) may merge onto either neighbour; the
/// left/right rule (seed §1.4.2, "choose according to the location of
/// stitches") then decides: the *pivot* is the continuing wale whose needle is
/// nearest to needle 0 (the centre of course 0; ties: the lower needle); it
/// does not move. Wales left of the pivot move left to open needles
/// (increase left) or right to close gaps (decrease left); wales right of it
/// mirror this. A free ending wale left of the pivot merges onto its nearest
/// continuing neighbour to the right (towards the pivot), one right of the
/// pivot onto its left neighbour; when that needle would then hold more than
/// `max_stack` loops the other neighbour is used instead.
///
/// Bind-off chains. A wale whose top touches no later stitch (a free top:
/// the fabric edge narrows by several wales in one course, or a hole opens)
/// cannot merge onto a neighbour without knitting a fabric the map does not
/// describe. Runs of such wales are bound off by a chain along their row,
/// as a knitter casts off stitches at the edge (LayoutChain): right after a
/// chained stitch of row r is knitted its loop is moved onto the needle of
/// the next stitch of the row, which is then knitted through both (knit,
/// pass over); the chain ends on that next stitch (`onto_col`), so no
/// needle holds more than two loops. In a knittable map such a run never
/// ends its row (the row's last stitch continues into the next course), so
/// there always is a next stitch.
///
/// Closure tucks are given up where they would overflow a merge: a tuck of
/// an earlier turn on the ending wale or its target is taken back (that turn
/// is left open, counted in open_turns).
///
/// Problems. A transition that still cannot be made (ending wales whose
/// targets are all full, a chain that cannot be placed) is recorded in
/// `problems` with the map cell and the reason; writers refuse such a layout.
///
/// Transfers. Every loop (or stack of loops) whose needle changes is moved by
/// front -> back at racking 0, then back -> front at racking = displacement.
/// A displacement larger than `max_shift` is split into steps: in step k
/// every loop is at old + clamp(d, k * max_shift); these intermediate layouts
/// keep the wales in order on distinct needles (ending wales only meet their
/// target, at its final needle), so each step is a valid set of transfers.
///
/// Short-row turns. When row r ends inside the fabric (an alive wale lies
/// beyond its last stitch in the row direction), the first held wale beyond
/// it is the turn's *closure* needle: the knitout writer tucks on it before
/// turning (the hand instructions wrap it) so the turn leaves no hole. The
/// tuck adds a loop to a held needle; it is made only while that needle then
/// holds at most `max_closure_loops` loops (otherwise the turn stays open and
/// is counted in open_turns).
///
/// Needle numbers are relative (course 0 is centred on needle 0); writers add
/// an offset to place the fabric on the bed.

#include <climits>
#include <cstdint>
#include <string>
#include <vector>

#include "knitforge/core/knitting_map.h"
#include "knitforge/core/stitch_mesh.h"

namespace knitforge {

inline constexpr int kNoNeedle = INT_MIN;

/// One loop stack moving between front needles in a transfer step.
struct LayoutMove {
  int col = -1;   ///< the wale (map column) whose loops move
  int from = 0;   ///< front needle before the step
  int to = 0;     ///< front needle after the step
};

/// One transfer step: all moves happen together (front -> back at racking 0,
/// then back -> front grouped by displacement); |to - from| <= max_shift.
struct LayoutStep {
  std::vector<LayoutMove> moves;  ///< sorted by `from`
};

/// An ending wale and the continuing wale it merges onto.
struct LayoutMerge {
  int col = -1;
  int onto_col = -1;
};

/// A run of ending wales with free tops bound off by a chain along row
/// `row` (see the file comment).
struct LayoutChain {
  int row = -1;
  std::vector<int> cols;  ///< the chained wales, in the row's knitting order
  int onto_col = -1;      ///< the next stitch of the row, which takes the chain's last loop
};

/// A transition the machine cannot make.
struct LayoutProblem {
  int row = -1, col = -1;  ///< map cell (the ending wale's last row and column)
  std::string message;     ///< names the cell and what to change
};

/// The layout change between row r-1 and row r (transitions[0] is empty).
struct LayoutTransition {
  std::vector<int> starts;           ///< wales starting at row r (need an empty needle)
  std::vector<LayoutMerge> merges;   ///< wales ending after row r-1
  std::vector<LayoutStep> steps;     ///< transfer steps, in order
  int pivot_col = -1;                ///< the wale that does not move (-1 for r = 0)
  int pivot_needle = 0;              ///< its needle
};

/// Options of plan_needle_layout().
struct NeedleLayoutOptions {
  int max_shift = 4;          ///< largest needle displacement in one step (machine racking), >= 1
  int max_stack = 3;          ///< most loops on a needle after a merge, >= 2
  bool close_turns = true;    ///< choose closure needles at short-row turns
  int max_closure_loops = 2;  ///< most loops a held needle may hold after a closure tuck
};

/// The needle layout of a whole map.
struct NeedleLayout {
  int rows = 0;
  int cols = 0;
  /// rows*cols: the wale's needle while row r is knitted, kNoNeedle when the
  /// wale is not alive at row r.
  std::vector<int> needle;
  std::vector<LayoutTransition> transitions;  ///< size rows; transitions[r] precedes row r
  std::vector<int> first_col;  ///< per row: leftmost stitch column
  std::vector<int> last_col;   ///< per row: rightmost stitch column
  /// Per row: the held wale closing the turn after the row (-1: none, i.e.
  /// the row ends at the fabric edge, is the last row, or closure is off).
  std::vector<int> closure_col;
  /// Per row: true when the row ends inside the fabric (a short-row turn).
  std::vector<uint8_t> inside_turn;
  /// Bind-off chains, by row.
  std::vector<LayoutChain> chains;
  /// Transitions the machine cannot make (empty when the layout is complete).
  std::vector<LayoutProblem> problems;
  int open_turns = 0;          ///< inside turns left without closure (loop limit)
  int min_needle = 0;          ///< smallest needle used at any time
  int max_needle = 0;          ///< largest needle used at any time
  int increases = 0;           ///< starting wales (interior and edge)
  int decreases = 0;           ///< ending wales merged onto a neighbour or chained
  int chained = 0;             ///< ending wales bound off by chains
  int loop_moves = 0;          ///< moves over all steps (each is 2 transfers)

  int needle_at(int r, int c) const { return needle[static_cast<size_t>(r) * cols + c]; }
  bool alive(int r, int c) const { return needle_at(r, c) != kNoNeedle; }
};

/// Per map cell (row-major): 1 when wale c is alive at row r (a stitch, or a
/// Collapsed cell between two stitches of its column: a held loop).
/// \pre check_map_arrays(map) passes.
std::vector<uint8_t> alive_wales(const KnittingMap& map);

/// For every stitch that ends its wale: the wales of the later stitches whose
/// bottom edge touches its top, i.e. the wales that must take its loop
/// (docs/representations.md). Built from map_to_stitch_mesh_topology().
class WaleTakers {
 public:
  /// \throw InvalidInput as map_to_stitch_mesh_topology().
  explicit WaleTakers(const KnittingMap& map);
  /// Wales (sorted) of stitches in rows > after_row touching the top of the
  /// stitch at (row, col); empty when none (or no stitch there).
  std::vector<int> takers(int row, int col, int after_row) const;

 private:
  int cols_;
  StitchMesh mesh_;
  std::vector<int> cell_stitch_;
  std::vector<std::vector<int>> bottom_users_;
};

/// Plans the layout (see the file comment). Transitions the machine cannot
/// make are recorded in NeedleLayout::problems, not thrown.
/// \throw InvalidInput when the map is not a valid knitting map (as
///        map_to_stitch_mesh_topology()), when consecutive rows share no wale,
///        or when an option is out of range.
NeedleLayout plan_needle_layout(const KnittingMap& map, const NeedleLayoutOptions& options = {});

}  // namespace knitforge
