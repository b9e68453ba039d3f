#pragma once
/// \file hand_instructions.h
/// Row-by-row instructions for a single-bed manual knitting machine such as
/// the Brother KH868 (seed §1.4.3: "we can also execute the machine knitting
/// instructions by hand on a manual machine ... extra hand tools to perform
/// stitch transfers"). docs/machines.md shows an example.
///
/// The needle layout is the knitout writer's (needle_layout.h) without a
/// racking limit (the transfer tool moves a stitch any distance): the same
/// left/right rule, so increases open an empty needle by moving the stitches
/// on the outer side one needle outwards, decreases move a stitch onto its
/// neighbour towards the centre and close the gap.
///
/// Needles are named as printed on the machine: L<k> left of centre and
/// R<k> right of it (L1 and R1 meet at the centre mark), for a bed of
/// needle_count needles (L100..L1 R1..R100 on the KH868). The fabric is
/// centred on the bed. The map is read as the knitter sees the work: map
/// column 0 on the left (the purl side faces the knitter on a single bed).
///
/// For each map row r (row counter RC r -> r+1), in order:
///  - transfers to do with the transfer tool before the row (moves to the left
///    are listed left to right, moves to the right right to left, so every
///    stitch goes onto an empty needle or onto the stitch it is decreased
///    onto); needles to bring to working position (B) for increases (the new
///    stitch is made on the empty needle) and to put out of work (A) at the
///    edges;
///  - needles to push to holding position (E) and needles to return to upper
///    working position (D) for short rows (holding cam lever on H while any
///    needle is held);
///  - the carriage direction and the needles that knit;
///  - at a short-row turn, the held needle next to the turn to wrap before
///    the next row (closes the hole, like the tuck of the knitout writer).

#include <string>
#include <vector>

#include "knitforge/core/knitting_map.h"
#include "knitforge/machine/machine_profile.h"

namespace knitforge {

/// Options of hand_instructions().
struct HandInstructionOptions {
  bool wrap_turns = true;  ///< wrap the first held needle at short-row turns
};

/// The instructions of one map row.
struct HandRow {
  int row = 0;                       ///< map row (0-based); the row counter reads `row` before it
  int direction = 1;                 ///< +1 carriage left to right, -1 right to left
  std::vector<std::string> before;   ///< transfers, needle positions, holds (in order)
  std::string knit;                  ///< "Knit L10..R10 (20 stitches)"
  std::vector<std::string> after;    ///< wrap at a short-row turn
};

/// Instructions for a whole map.
struct HandInstructions {
  std::string machine;               ///< profile display name
  std::string title;                 ///< one-line summary of the piece
  std::vector<std::string> setup;    ///< cast-on and machine settings
  std::vector<HandRow> rows;
  std::vector<std::string> finish;   ///< bind-off
  int stitches = 0;                  ///< map stitches
  int hand_transfers = 0;            ///< stitches moved with the transfer tool
  int held_needle_changes = 0;       ///< needles pushed to hold or returned
  int wraps = 0;                     ///< short-row wraps
};

/// Needle label of bed index k (0 = leftmost of `needle_count`): "L<n>" left
/// of centre, "R<n>" right of it.
/// \pre 0 <= k < needle_count
std::string hand_needle_label(int k, int needle_count);

/// Builds the instructions (see the file comment).
/// \throw InvalidInput when the fabric needs more needles than the profile's
///        bed, or the map is invalid (as plan_needle_layout()).
HandInstructions hand_instructions(const KnittingMap& map, const MachineProfile& profile,
                                   const HandInstructionOptions& options = {});

/// Plain text, one instruction per line (LF).
std::string hand_instructions_text(const HandInstructions& h);

/// A printable, self-contained HTML page (inline CSS, no scripts or links).
std::string hand_instructions_html(const HandInstructions& h);

}  // namespace knitforge
