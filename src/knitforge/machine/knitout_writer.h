#pragma once
/// \file knitout_writer.h
/// Knitting map -> knitout program (knitout spec v0.6, `;!knitout-2`) for a
/// two-bed machine profile: sheet knitting on the front bed, short rows as
/// partial passes, short columns and edge shaping by transfers (seed §1.4,
/// Fig. 1.8; docs/machines.md).
///
/// The map must pass check_knittability() (the writer refuses a map the
/// check rejects, naming the first violation), and the needle layout
/// (needle_layout.h) must be possible within the machine's limits. Every
/// program is then run on the virtual machine of the profile with every
/// category strict and compared with the map (knitout_simulate.h,
/// knit_graph_compare.h): the writer returns only programs the simulator
/// calls VALID without warnings and whose knit graph MATCHES the map; the
/// verdict and statistics come with the program.
///
/// Program layout (every block starts with a `;` comment naming it, so a
/// reader can tie the program back to the map):
///  1. Headers: `;!knitout-2`, `;;Machine:`, `;;Gauge:`, `;;Width:` (profiles
///     with width_header, i.e. Kniterate), `;;Carriers:`, `;;Position:`;
///     then comments.
///  2. `; waste ...` (when waste_rows > 0; the profile's default,
///     WriterDefaults::waste_rows, when the option is -1): the waste carrier
///     comes in, casts on the needles of course 0 with alternating tucks and
///     knits waste_rows courses, goes out; the draw-thread carrier knits one
///     course and goes out. Then `; cast-on ...`: without a waste section the
///     main carrier casts on with alternating tucks (every other needle, then
///     the others) and knits one course; after a waste section it knits one
///     course over the draw thread. The hook (inhook) is released after the
///     first course, before any transfer. Every carrier's first pass runs
///     away from the profile's carrier_park_side (Kniterate: carriers park at
///     the left, so it runs `+`; Shima-like: `-`). One more main course is
///     added when the carrier is not on the side where course 0 starts.
///  3. `; course r ...` for every map row r, in map order: exactly the stitches
///     of the row, in the row's direction: `tuck` on the (empty) needle of a
///     wale's first stitch (Increase or outside increase: the stitch has no
///     loop below), `knit` for every other stitch (a needle holding a merged
///     Decrease loop knits both loops together). A bind-off chain of the row
///     (LayoutChain: wales ending with a free top, e.g. several at once at
///     the fabric edge) moves each chained loop onto the next stitch's needle
///     right after it is knitted (`; bound off along course r ...`).
///  4. `; turn after course r ...` when the row ends inside the fabric: a
///     `tuck` on the first held needle beyond the turn closes the hole
///     (see needle_layout.h; omitted, with a comment, when the needle already
///     holds the closure limit).
///  5. `; transfers before course r ...` when the needle layout changes (needle_layout.h): per step
///     `xfer f n b n` at racking 0 for every moving loop, then per
///     displacement d `rack d` and `xfer b n f n+d`, then `rack 0`. The
///     comments list the increases and decreases and the counts.
///  6. `; bind-off ...`: BindOff::Chain: from one end of the last course each
///     loop is moved onto the next needle (f->b, rack ±1, b->f, rack 0) and
///     knitted there; the chain ends on the profile's carrier_park_side when
///     the carrier can get to the other end without a float beyond the
///     machine's limit; the last loop knits a tail of tail_rows courses, the
///     carrier moves two needles beyond the fabric edge (out of the way of
///     the take-down), goes out, and the tail loop is dropped (thread the cut
///     yarn end through it by hand). BindOff::Waste: the main carrier goes
///     out, the waste carrier comes in and knits bind_off_waste_rows courses
///     over the live loops, goes out, and the waste loops are dropped.
///  Every carrier ends out; no loop is left on a needle.
/// Machine settings (x-stitch-number, x-xfer-stitch-number, x-speed-number,
/// x-roller-advance) are written at the start of the waste, cast-on, fabric
/// and bind-off sections from the profile's WriterDefaults, where the
/// machine's translator reads them (the Kniterate); KnitoutOptions::body
/// overrides the fabric settings.
///
/// The fabric is centred on the bed (needles 1..needle_count). Racking never
/// exceeds the profile's max_racking (larger displacements are split into
/// steps), merges never stack more than max_transfer_stack loops, closure
/// tucks keep held needles at <= 2 loops. Output is deterministic.
///
/// Tubes: a tubular map (KnittingMap::seam) is knitted in the round on both
/// beds by write_tube_knitout() (knitout_tube_writer.h, docs/tubes.md) after
/// the same option, carrier and knittability checks, and verified the same way.
///
/// Yarn: every stitch is knitted with the main carrier; a map with several
/// yarn indices is knitted in one yarn and a warning says so.

#include <optional>
#include <string>
#include <vector>

#include "knitforge/core/knitting_map.h"
#include "knitforge/machine/knit_graph_compare.h"
#include "knitforge/machine/knitout_simulate.h"
#include "knitforge/machine/machine_profile.h"

namespace knitforge {

/// How the last course is secured.
enum class BindOff {
  Chain,  ///< chain bind-off by transfers, then a knitted tail
  Waste,  ///< live loops held by waste-yarn courses, then dropped
};

/// Largest waste section accepted (courses); a program is a file a machine
/// loads, not a way to fill a disk.
inline constexpr int kMaxWasteRows = 1000;

/// Options of write_knitout().
struct KnitoutOptions {
  std::string carrier;        ///< main yarn carrier; "" = the profile's first carrier
  std::string waste_carrier;  ///< waste yarn; "" = the profile's second carrier
  std::string draw_carrier;   ///< draw thread; "" = the profile's third carrier
  /// Courses of waste yarn (plus a draw thread) before the fabric: 0 = none,
  /// -1 = the profile's default (WriterDefaults::waste_rows), at most kMaxWasteRows.
  int waste_rows = -1;
  BindOff bind_off = BindOff::Chain;
  int bind_off_waste_rows = 8;  ///< courses of waste yarn for BindOff::Waste, 1..kMaxWasteRows
  int tail_rows = 4;            ///< tail courses on the last needle of a chain bind-off, 1..100
  bool close_turns = true;      ///< tuck on the held needle at short-row turns
  double gauge = 0;             ///< `;;Gauge:` value; 0 = the profile's gauge
  std::string position = "Center";  ///< `;;Position:` Left, Center, Right or Keep
  /// Settings of the fabric courses; a field set here replaces the profile's
  /// WriterDefaults::body field ("" / -1 = keep the profile's).
  SectionSettings body;
  /// Run the program on the virtual machine and compare it with the map
  /// (see the file comment); false skips it (benchmarks of the writer alone).
  bool verify = true;
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
  int shaping_xfers = 0;       ///< `xfer`s of the fabric: increases, decreases, edge chains, layout shifts
  int racks = 0;               ///< `rack` operations
  int transfer_passes = 0;     ///< groups of transfers at one racking
  int increases = 0;           ///< wale starts (interior and edge)
  int decreases = 0;           ///< wale ends merged onto a neighbour or chained at the edge
  int edge_chained = 0;        ///< of the decreases: wales bound off by edge chains
  int inside_turns = 0;        ///< short-row turns inside the fabric
  int closed_turns = 0;        ///< turns closed by a tuck
  int open_turns = 0;          ///< turns left open (loop limit)
  int waste_rows = 0;          ///< courses of the waste section (0: none)
  int first_needle = 0;        ///< leftmost needle used
  int last_needle = 0;         ///< rightmost needle used
};

/// A knitout program and what went into it.
struct KnitoutProgram {
  std::string text;                   ///< the program, LF line endings
  KnitoutStats stats;
  std::vector<std::string> warnings;  ///< e.g. several yarns knitted with one carrier
  std::string main_carrier;           ///< the carriers of each role ("" when unused)
  std::string waste_carrier;
  std::string draw_carrier;
  /// The virtual machine's verdict (strict) and the comparison with the map
  /// (empty when KnitoutOptions::verify is false).
  std::optional<KnitoutSimulation> simulation;
  std::optional<GraphComparison> comparison;
};

/// Writes the knitout program of `map` for `profile` (see the file comment).
/// \throw InvalidInput when the profile has one bed (use hand_instructions())
///        or is inconsistent, a carrier option names a carrier the profile
///        does not have or two roles share a carrier, an option is out of range
///        (waste_rows < -1 or > kMaxWasteRows, bind_off_waste_rows or
///        tail_rows out of range, position not Left/Center/Right/Keep,
///        gauge < 0 or not finite, a body setting the machine's software
///        does not accept), the map is not knittable (check_knittability();
///        the message names the first violation), the needle layout has a
///        problem (needle_layout.h; the message names the cell), the fabric
///        needs more needles than the bed has, or a bind-off float would
///        exceed max_float_needles.
/// \throw Error when the verification fails (a knitforge bug: the message
///        says what the simulator found).
KnitoutProgram write_knitout(const KnittingMap& map, const MachineProfile& profile,
                             const KnitoutOptions& options = {});

}  // namespace knitforge
