#pragma once
/// \file knitout_simulate.h
/// A virtual two-bed knitting machine that executes a knitout program,
/// checks it against a machine profile and rebuilds its knit graph
/// (docs/machines.md, "The simulator"; knitout spec v0.6).
///
/// State: per needle (front, back, front and back sliders) the loops it
/// holds, in the order they arrived; per carrier whether it is in, whether
/// the yarn-inserting hook holds it, whether it has stitched and where it
/// last stitched; the hook; the racking (back needle n is aligned with front
/// needle n + R). Positions along the bed are "slots": front needle n is at
/// n, back needle n at n + R.
///
/// Rules (each finding is a KnitoutDiagnostic with the line; E = error,
/// W = warning):
///  - syntax and headers (from parse_knitout()) [E; x- extensions W];
///  - carriers: named in ;;Carriers: and among the machine's carriers [E];
///    used only while in, not brought in twice, taken out only while in and
///    after stitching, the first operation after `in`/`inhook` uses exactly
///    the carrier set brought in [E]; carriers still in at the end [E];
///  - hook (machines with a yarn-inserting hook; on others every hook
///    operation is an error): no `inhook` while the hook holds a carrier;
///    `releasehook` names exactly the carriers the hook holds and only after
///    they stitched; no transfer or split while the hook holds a carrier;
///    `out` of a carrier the hook still holds, and `outhook` while the hook
///    holds another carrier, are errors; the hook holding at the end [E]; the
///    first stitch of a hooked carrier going `+` [W] (carriers enter from the
///    right on Shima-like machines);
///  - racking: |R| <= max_racking and a fractional part the machine has
///    (quarter pitch 0.25 on hook machines, half pitch 0.5 on the Kniterate,
///    either on others) [E];
///  - transfers and splits: between a front-side and a back-side needle
///    aligned at the current racking, never slider to slider [E]; knit, tuck,
///    split and amiss not on sliders [E]; the back bed on a one-bed machine [E];
///  - loops per needle: more than max_loops_per_needle [E]; more than
///    max_transfer_stack after a transfer [W];
///  - floats: a carrier's consecutive stitches (knit/tuck/split) more than
///    max_float_needles slots apart [E];
///  - drops: dropping a knit or split loop formed in a fabric section (it
///    was pulled through loops no needle holds any more, so the wale runs)
///    [E]; tuck loops, loops knitted on empty needles and loops of cast-on,
///    bind-off (e.g. the tail of a chain bind-off) and waste sections drop
///    freely;
///  - knit on an empty needle outside a cast-on section [W];
///  - width: the program spans more needles than the bed has, or with
///    `;;Position: Keep` uses needles outside 1..needle_count [E];
///  - loops left on needles at the end [E] unless a comment states the
///    intention: a comment containing `leave-loops` (e.g.
///    `; leave-loops: live loops on waste yarn, remove by hand`).
///
/// Statistics: carriage passes (consecutive knit/tuck/split/miss operations
/// in one direction with one carrier set and racking, advancing along the
/// bed; drops/amisses form passes of their own; transfers at one racking
/// form transfer passes until a slot repeats or another operation comes),
/// racks (changes of racking), stitch counts, the knitting time from the
/// profile's timing model (machine_profile.h), and yarn per carrier: every
/// knit/tuck/split draws one loop of length 4.2 needle pitches (Munden's
/// dry-relaxed loop constant with the wale spacing taken as the needle
/// pitch), plus the float beyond one pitch between consecutive stitches.

#include <array>
#include <string>
#include <vector>

#include "knitforge/machine/knit_graph.h"
#include "knitforge/machine/knitout_parse.h"
#include "knitforge/machine/machine_profile.h"

namespace knitforge {

struct SimulateOptions {
  /// At most this many diagnostics are kept per rule (counts stay exact);
  /// <= 0 keeps all.
  int max_diagnostics_per_rule = 100;
  /// Loop length of one stitch in needle pitches, for the yarn estimate.
  double loop_length_pitches = 4.2;
};

struct SimulationStats {
  int carriage_passes = 0;   ///< all passes (knit, drop and transfer passes)
  int knit_passes = 0;       ///< passes with carriers (knit/tuck/split/miss)
  int transfer_passes = 0;
  int racks = 0;             ///< changes of racking
  int knits = 0, tucks = 0, splits = 0, misses = 0, transfers = 0, drops = 0;
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
  std::vector<KnitoutDiagnostic> diagnostics;  ///< parse and run findings, by line
  std::array<int, kNumKnitoutRules> error_counts{};
  std::array<int, kNumKnitoutRules> warning_counts{};
  int errors = 0, warnings = 0;
  bool leave_loops_stated = false;  ///< a `leave-loops` comment was found

  bool ok() const { return errors == 0; }
  /// Human-readable verdict, statistics and diagnostics (one per line).
  std::string text() const;
};

/// Runs `program` (already parsed; its diagnostics are included) on the
/// virtual machine of `profile`.
/// \throw InvalidInput when the profile is inconsistent (validate_machine_profile).
KnitoutSimulation simulate_knitout(const KnitoutFile& program, const MachineProfile& profile,
                                   const SimulateOptions& options = {});

}  // namespace knitforge
