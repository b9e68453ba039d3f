#pragma once
/// \file knitout_writer.h
/// Knitting map -> knitout program (knitout spec v0.6, `;!knitout-2`) for a
/// two-bed machine profile: sheet knitting on the front bed, short rows as
/// partial passes, short columns and edge shaping by transfers (seed §1.4,
/// Fig. 1.8; docs/machines.md).
///
/// Program layout (every block starts with a `;` comment naming it, so a
/// reader can tie the program back to the map):
///  1. Headers: `;!knitout-2`, `;;Machine:`, `;;Gauge:`, `;;Width:` (profiles
///     with width_header, i.e. Kniterate), `;;Carriers:`, `;;Position:`;
///     then comments and the optional `x-stitch-number`, `x-xfer-stitch-number`,
///     `x-speed-number` settings (only when the options ask for them).
///  2. `; cast-on ...`: the needles of course 0. Without a waste section: the
///     main carrier comes in (`inhook`, or `in` without a hook), tucks every
///     other needle leftwards, the remaining needles rightwards (alternating
///     tuck cast-on), knits one course leftwards, `releasehook`. With
///     `waste_rows` > 0: the waste carrier casts on the same way and knits
///     waste_rows courses, goes out; the draw-thread carrier knits one course
///     and goes out; the main carrier comes in and knits one course. One more
///     rightward main course is added when course 0 goes right to left.
///  3. `; course r ...` for every map row r, in map order: exactly the stitches
///     of the row, in the row's direction: `tuck` on the (empty) needle of a
///     wale's first stitch (Increase or outside increase: the stitch has no
///     loop below), `knit` for every other stitch (a needle holding a merged
///     Decrease loop knits both loops together).
///     Wales that end at a free top edge in a run (needle_layout.h) are
///     bound off: during the row (`; bind-off during course r`: the
///     stitch, one more `knit` on its needle, its loop moved onto the next
///     wale's needle, then `; course r (continued)`) or after it (`; bind-off
///     after course r`: the same steps back from the fabric edge). These
///     loops are not fabric loops (knit_graph_compare.h).
///  4. `; turn after course r ...` when the row ends inside the fabric: a
///     `tuck` on the first held needle beyond the turn closes the hole
///     (see needle_layout.h; omitted, with a comment, when the needle already
///     holds the closure limit).
///  5. `; transfers before course r ...` when the needle layout changes
///     (needle_layout.h): per step `xfer f n b n` at racking 0 for every moving
///     loop, then per displacement d `rack d` and `xfer b n f n+d`, then
///     `rack 0`. The comments list the increases and decreases and the counts.
///  6. `; bind-off ...`: BindOff::Chain: from the end where the carrier is,
///     each loop is moved onto the next needle (f->b, rack ±1, b->f, rack 0)
///     and knitted there; the last loop knits a tail of tail_rows courses, the
///     carrier goes out and the tail loop is dropped (thread the cut yarn end
///     through it by hand). BindOff::Waste: the main carrier goes out, the
///     waste carrier comes in and knits bind_off_waste_rows courses over the
///     live loops, goes out, and the waste loops are dropped.
///  Every carrier ends out; no loop is left on a needle.
///
/// The fabric is centred on the bed (needles 1..needle_count). Racking never
/// exceeds the profile's max_racking (larger displacements are split into
/// steps), merges never stack more than max_transfer_stack loops, closure
/// tucks keep held needles at <= 2 loops. Output is deterministic.
///
/// Yarn: every stitch is knitted with the main carrier; a map with several
/// yarn indices is knitted in one yarn and a warning says so.

#include <optional>
#include <string>
#include <vector>

#include "knitforge/core/knitting_map.h"
#include "knitforge/machine/machine_profile.h"

namespace knitforge {

/// How the last course is secured.
enum class BindOff {
  Chain,  ///< chain bind-off by transfers, then a knitted tail
  Waste,  ///< live loops held by waste-yarn courses, then dropped
};

/// Options of write_knitout().
struct KnitoutOptions {
  std::string carrier;        ///< main yarn carrier; "" = the profile's first carrier
  std::string waste_carrier;  ///< waste yarn; "" = the profile's second carrier
  std::string draw_carrier;   ///< draw thread; "" = the profile's third carrier
  int waste_rows = 0;         ///< > 0: a waste section of this many courses + draw thread
  BindOff bind_off = BindOff::Chain;
  int bind_off_waste_rows = 8;  ///< courses of waste yarn for BindOff::Waste, >= 1
  int tail_rows = 4;            ///< tail courses on the last needle of a chain bind-off, >= 1
  bool close_turns = true;      ///< tuck on the held needle at short-row turns
  double gauge = 0;             ///< `;;Gauge:` value; 0 = the profile's gauge
  std::string position = "Center";  ///< `;;Position:` Left, Center, Right or Keep
  std::optional<int> stitch_number;       ///< emit `x-stitch-number N` (knitting passes)
  std::optional<int> xfer_stitch_number;  ///< emit `x-xfer-stitch-number N`
  std::optional<int> speed_number;        ///< emit `x-speed-number N`
};

/// Counts of what the program does (all operations, including cast-on and
/// bind-off, unless named otherwise).
struct KnitoutStats {
  int courses = 0;             ///< map rows knitted
  int map_knits = 0;           ///< `knit` operations of map stitches
  int map_tucks = 0;           ///< `tuck` operations of map stitches (wale starts)
  int knits = 0;               ///< all `knit` operations
  int tucks = 0;               ///< all `tuck` operations
  int xfers = 0;               ///< all `xfer` operations
  int racks = 0;               ///< `rack` operations
  int transfer_passes = 0;     ///< groups of transfers at one racking
  int increases = 0;           ///< wale starts (interior and edge)
  int decreases = 0;           ///< wale ends merged onto a neighbour
  int bound_off = 0;           ///< wale ends bound off by a chain (needle_layout.h)
  int inside_turns = 0;        ///< short-row turns inside the fabric
  int closed_turns = 0;        ///< turns closed by a tuck
  int open_turns = 0;          ///< turns left open (loop limit)
  int first_needle = 0;        ///< leftmost needle used
  int last_needle = 0;         ///< rightmost needle used
};

/// A knitout program and what went into it.
struct KnitoutProgram {
  std::string text;                   ///< the program, LF line endings
  KnitoutStats stats;
  std::vector<std::string> warnings;  ///< e.g. several yarns knitted with one carrier
};

/// Writes the knitout program of `map` for `profile` (see the file comment).
/// \throw InvalidInput when the profile has one bed (use hand_instructions())
///        or is inconsistent, a carrier option names a carrier the profile
///        does not have or two roles share a carrier, an option is out of range
///        (waste_rows < 0, bind_off_waste_rows < 1, tail_rows < 1, position not
///        Left/Center/Right/Keep, gauge < 0), the fabric needs more needles than
///        the bed has, a bind-off float would exceed max_float_needles, or the
///        map is invalid (as plan_needle_layout()).
KnitoutProgram write_knitout(const KnittingMap& map, const MachineProfile& profile,
                             const KnitoutOptions& options = {});

}  // namespace knitforge
