#pragma once
/// \file knitout_tube_writer.h
/// Tubular knitting map -> knitout program: knitting in the round on both
/// beds (docs/tubes.md, docs/machines.md "Tubes"). Called by write_knitout()
/// for a map with KnittingMap::seam (after its option, carrier and
/// knittability checks); write_knitout() verifies the program as for sheets.
///
/// Program layout (each block starts with a `;` comment naming it):
///  1. Headers and comments, as for sheets.
///  2. Cast-on round the tube (tube_layout.h: the front half on even
///     relative front needles, the back half on the odd back needles
///     between): every carrier comes in at the left fold (line 0) when the
///     profile parks its carriers at the left, else at the right fold
///     (line cols/2), so that its first pass runs away from the parking side.
///     Without waste: the main carrier tucks every other wale round the tube,
///     then the others, and knits one round (the hook, where the profile has
///     one, is released after it, before any transfer). With waste_rows > 0:
///     the waste carrier does so and knits waste_rows rounds, the draw thread
///     one round, then the main carrier one round. Cast-on stitches continue
///     round to the seam of course 0.
///  3. `; course r ...` for every map row in order: its stitches from the
///     seam (closed rows) or along the short row (open rows), each on its
///     wale's bed: front stitches in the row's direction, back stitches in
///     the opposite machine direction (a round going left to right on the
///     front comes back right to left on the back). A wale's first stitch
///     is a tuck on its empty needle. A short row that turns tucks on the
///     held needle beyond its end (tube_layout.h).
///  4. `; transfers before course r ...`: per step, the moving front loops
///     go to the back bed and the moving back loops to the front at racking
///     0, then per racking they return displaced (tube_layout.h).
///  5. `; bind-off ...`: BindOff::Chain: from the seam of the last round
///     each loop is moved onto the next wale's needle round the tube (within
///     a bed by a transfer to the other bed and back racked by two needles,
///     across a fold by one transfer at the racking that aligns the two
///     needles; a loop further away than the machine racks walks over the
///     empty needles of the other parity, one bed change per transfer) and
///     knitted there; the last loop knits a tail of tail_rows
///     stitches, the carrier goes out and the tail loop is dropped.
///     BindOff::Waste: the waste carrier knits bind_off_waste_rows rounds
///     over the live loops, goes out, and every loop is dropped.
///     A closed tube (KnittingMap::closed_end) ends with its closing seam
///     whatever the bind-off option: `; bind-off: closing seam`, every
///     back loop of the last round onto the front needle of its pair
///     (closing_pairs(); one transfer pass per racking, a walk for a pair
///     further apart than the machine racks), a joining pass
///     knitting each front needle through its two loops (the carrier first
///     misses to the nearer end of the front bed when the round ended
///     inside a bed), then the chain as above along the front bed, a tail.

#include <string>

#include "knitforge/machine/knitout_writer.h"

namespace knitforge {

/// What write_knitout() has settled before it hands a tube over.
struct TubeWriterSetup {
  std::string main_carrier, waste_carrier, draw_carrier;  ///< "" when unused
  int waste_rows = 0;      ///< resolved (>= 0)
  SectionSettings body;    ///< fabric settings (profile's, with the options')
};

/// The program of a tube (see the file comment), not yet verified.
/// \throw InvalidInput when the tube layout has a problem (the message names
///        the cell), the tube needs more needles than the bed has, the
///        machine cannot rack at all where the bind-off must move a loop,
///        or a closed tube's last round has unequal halves.
KnitoutProgram write_tube_knitout(const KnittingMap& map, const MachineProfile& profile,
                                  const KnitoutOptions& options, const TubeWriterSetup& setup);

}  // namespace knitforge
