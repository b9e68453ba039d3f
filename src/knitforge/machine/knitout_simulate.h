#pragma once
/// \file knitout_simulate.h
/// A virtual two-bed knitting machine that executes a knitout program,
/// judges it as the software of a machine profile does and rebuilds its
/// knit graph (docs/machines.md, "The simulator"; knitout spec v0.6).
///
/// State: per needle (front, back, front and back sliders) the loops it
/// holds, in the order they arrived; per carrier whether it is in, whether
/// the yarn-inserting hook holds it, whether it has stitched and where it
/// last stitched; the hook; the racking (back needle n is aligned with front
/// needle n + R). Positions along the bed are "slots": front needle n is at
/// n, back needle n at n + R.
///
/// Findings. Every check of knitout_rules.h that fails gives a
/// KnitoutDiagnostic with the line, at the level the profile gives the check
/// (MachineProfile::checks: Error, Warning, or Off = not reported). An
/// *error* is what the machine cannot or must not execute; a *warning* says
/// what the fabric will suffer or which convention is broken. ok() is true
/// when there is no error, warnings allowed. SimulateOptions::strict turns the
/// warnings of chosen categories into errors; knitforge's own programs are
/// judged with every category strict (write_knitout's self-check, the design
/// commands, `simulate --against`).
///
/// What the machine does, as the profile's software reads it:
///  - carriers: used only while in; `in`/`inhook` marks a carrier for its
///    next use; the first operation after it must use exactly that set; the
///    first pass runs away from the profile's carrier_park_side;
///  - the hook (profiles with one): held from `inhook` until `releasehook`;
///    on a profile without hook the hook operations are read as `in` /
///    nothing / `out` (at the level of hook-unavailable);
///  - racking: |R| <= max_racking; fractions from racking_fractions; on a
///    profile with quarter_pitch_as_half a fraction .25 is racked at .5, as
///    the Kniterate translator does (warning quarter-pitch-as-half);
///  - transfers and splits: between a front-side and a back-side needle
///    aligned at the current racking, never slider to slider; knit, tuck,
///    split and amiss not on sliders;
///  - loops per needle: more than max_loops_per_needle, more than
///    max_transfer_stack after a transfer;
///  - floats: consecutive stitches of a carrier (knit/tuck/split) more than
///    max_float_needles slots apart;
///  - drops: a drop that releases a knit or split loop formed in a fabric
///    section whose parents no needle holds any more makes the wale run (a
///    warning: most published test programs end by dropping their last
///    course); tuck loops and loops of cast-on, bind-off and waste sections
///    drop freely;
///  - knit on an empty needle outside a cast-on or waste section;
///  - width: the program spans more needles than the bed has, or with
///    `;;Position: Keep` uses needles outside 1..needle_count;
///  - loops left on needles at the end, unless a comment states the
///    intention (a comment containing `leave-loops`);
///  - x- extensions: known to the profile (MachineProfile::extensions) with a
///    valid value, or unknown (ignored).
///
/// Statistics: carriage passes (consecutive knit/tuck/split/miss operations
/// in one direction with one carrier set and racking, advancing along the
/// bed; drops/amisses form passes of their own; transfers at one racking
/// form transfer passes until a slot repeats or another operation comes),
/// racks (changes of racking), stitch counts, transfers per section, the
/// knitting time from the profile's timing model (machine_profile.h), and
/// yarn per carrier: every knit/tuck/split draws one loop of length 4.2
/// needle pitches (Munden's dry-relaxed loop constant with the wale spacing
/// taken as the needle pitch), plus the float beyond one pitch between
/// consecutive stitches. Every knit pass is recorded (SimulatedPass) with its
/// carriers, direction, needles and line range: the per-course statistics.

#include <array>
#include <string>
#include <vector>

#include "knitforge/machine/knit_graph.h"
#include "knitforge/machine/knitout_parse.h"
#include "knitforge/machine/knitout_rules.h"
#include "knitforge/machine/machine_profile.h"

namespace knitforge {

struct SimulateOptions {
  /// At most this many diagnostics are kept per category (counts stay
  /// exact); <= 0 keeps all.
  int max_diagnostics_per_rule = 100;
  /// Loop length of one stitch in needle pitches, for the yarn estimate.
  double loop_length_pitches = 4.2;
  /// Warning categories reported as errors (knitout_rules.h).
  StrictRules strict{};
};

/// One carriage pass that made stitches (knit/tuck/split/miss).
struct SimulatedPass {
  int first_line = 0, last_line = 0;  ///< knitout lines of its first and last operation
  uint32_t carriers = 0;              ///< carrier set (bit c = carrier index c)
  int8_t direction = 0;               ///< +1 / -1
  double rack = 0.0;                  ///< racking during the pass
  int knits = 0, tucks = 0, splits = 0, misses = 0;
  double min_slot = 0.0, max_slot = 0.0;  ///< bed positions it spans
  LoopSection section = LoopSection::Fabric;
  double time_s = 0.0;                ///< its share of the knitting time
};

struct SimulationStats {
  int carriage_passes = 0;   ///< all passes (knit, drop and transfer passes)
  int knit_passes = 0;       ///< passes with carriers (knit/tuck/split/miss)
  int transfer_passes = 0;
  int racks = 0;             ///< changes of racking
  int knits = 0, tucks = 0, splits = 0, misses = 0, transfers = 0, drops = 0;
  /// Transfers (xfer operations) per section (index: LoopSection): shaping
  /// transfers are those of fabric sections, the rest serve cast-on,
  /// bind-off and waste.
  std::array<int, 4> transfers_by_section{};
  int carriers_in = 0, carriers_out = 0;
  int min_needle = 0, max_needle = 0;  ///< range of slots used (0, 0 when none)
  double time_s = 0.0;                 ///< estimated knitting time
  std::vector<double> yarn_mm;         ///< per carrier (index as in carrier_names)
  double gauge = 0.0;                  ///< gauge used for the yarn estimate
};

struct KnitoutSimulation {
  std::string machine;                       ///< profile name
  KnitGraph graph;
  SimulationStats stats;
  std::vector<SimulatedPass> passes;         ///< knit passes in program order (KnitLoop::pass indexes them)
  std::vector<KnitoutDiagnostic> diagnostics;  ///< parse and run findings, by line
  std::array<int, kNumKnitoutRules> error_counts{};
  std::array<int, kNumKnitoutRules> warning_counts{};
  int errors = 0, warnings = 0;
  bool leave_loops_stated = false;  ///< a `leave-loops` comment was found

  bool ok() const { return errors == 0; }
  /// Human-readable verdict, statistics and diagnostics (one per line).
  std::string text() const;
};

/// Runs `program` (already parsed; its diagnostics are re-levelled by the
/// profile and included) on the virtual machine of `profile`.
/// \throw InvalidInput when the profile is inconsistent (validate_machine_profile).
KnitoutSimulation simulate_knitout(const KnitoutFile& program, const MachineProfile& profile,
                                   const SimulateOptions& options = {});

}  // namespace knitforge
