#pragma once
/// \file machine_profile.h
/// Named knitting-machine profiles: the limits a knitting program must
/// respect and the timing data for knit-time estimates (seed §1.4, §1.4.3;
/// docs/machines.md).
///
/// Profiles (selected by name, e.g. `--machine shima-swg091n2`):
///
/// | name             | kind            | gauge | needles | carriers | hook | max rack | loops/needle | float |
/// |------------------|-----------------|-------|---------|----------|------|----------|--------------|-------|
/// | shima-swg091n2   | V-bed, 2 beds   | 15    | 540     | 1..10    | yes  | 4        | 4            | 20    |
/// | kniterate        | V-bed, 2 beds   | 7     | 252     | 1..6     | no   | 4        | 3            | 12    |
/// | generic          | V-bed, 2 beds   | 12    | 400     | 1..10    | no   | 4        | 4            | 20    |
/// | brother-kh868    | manual, 1 bed   | 5.64  | 200     | 1        | no   | 0        | 3            | 10    |
///
/// Conventions: needles are numbered 1..needle_count on each bed (knitout
/// needle numbers, `f1`..`fN`; the writer keeps every needle inside this
/// range). Racking R aligns back needle n with front needle n + R (knitout);
/// |R| <= max_racking. Gauge is needles per inch; the needle pitch is
/// 25.4 / gauge mm. A single-bed (manual) profile cannot run knitout
/// transfers: the knitout writer rejects it and the hand-instruction writer
/// uses it (needles labelled left/right of centre, e.g. L100..L1 R1..R100).
///
/// Timing model (used by knit-time estimates): a carriage pass that spans
/// `s` needles takes `pass_overhead_s + s * pitch_mm / speed_mm_s`, with the
/// speed of its kind (knit/tuck/miss passes, transfer passes); a transfer
/// pass additionally costs `transfer_pass_overhead_s`; every change of
/// racking costs `rack_s`; every carrier in/out (with or without the hook)
/// costs `carrier_in_out_s`. The numbers are nominal (documented per profile
/// in machine_profile.cpp), good for comparing programs, not for quoting
/// production times.

#include <string>
#include <string_view>
#include <vector>

namespace knitforge {

/// Timing data of a machine for the knit-time estimate (see the file comment).
struct MachineTiming {
  double knit_speed_mm_s = 600.0;         ///< carriage speed on knit/tuck/miss passes (mm/s)
  double transfer_speed_mm_s = 400.0;     ///< carriage speed on transfer passes (mm/s)
  double pass_overhead_s = 0.6;           ///< turn-around / acceleration per carriage pass (s)
  double transfer_pass_overhead_s = 0.4;  ///< extra fixed cost of a transfer pass (s)
  double rack_s = 0.3;                    ///< one racking movement of the back bed (s)
  double carrier_in_out_s = 2.0;          ///< bringing a carrier in or out (s)
};

/// The kind of a carriage pass, for pass_time_seconds().
enum class PassKind { Knit, Transfer };

/// A knitting machine: limits and conventions of the programs it runs.
struct MachineProfile {
  std::string name;             ///< selection name ("shima-swg091n2")
  std::string display_name;     ///< human-readable name ("Shima Seiki SWG091N2")
  std::string knitout_machine;  ///< value of the `;;Machine:` header ("SWG091N2")
  std::string description;      ///< one line for `--help` and docs
  double gauge = 15;            ///< needles per inch (5.64 for a 4.5 mm pitch)
  int needle_count = 540;       ///< needles per bed, numbered 1..needle_count
  int beds = 2;                 ///< 2 for a V-bed, 1 for a single-bed manual machine
  bool manual = false;          ///< a hand-operated machine (hand instructions, no knitout)
  std::vector<std::string> carriers;  ///< carrier names front to back (`;;Carriers:`)
  bool has_yarn_inserting_hook = true;  ///< inhook/releasehook/outhook; else in/out
  bool width_header = false;            ///< write `;;Width: needle_count` (Kniterate backend)
  int max_racking = 4;          ///< largest |racking| in needles (integer rackings)
  int max_loops_per_needle = 4; ///< most loops a needle may hold at any time
  /// Most loops a needle may hold after an interior transfer (a decrease
  /// stacks 2); stricter than max_loops_per_needle because of stretching and
  /// miss-transfer (seed §1.4.2). Must be <= max_loops_per_needle.
  int max_transfer_stack = 3;
  int max_float_needles = 20;   ///< longest float a carrier may make (needles)
  MachineTiming timing;         ///< data for the knit-time estimate

  /// Needle pitch in millimetres (25.4 / gauge).
  double needle_pitch_mm() const { return 25.4 / gauge; }
  /// True when `carrier` is one of the profile's carrier names.
  bool has_carrier(std::string_view carrier) const;
};

/// The profile called `name` (case-insensitive): "shima-swg091n2" (alias
/// "swg091n2", "shima"), "kniterate", "generic" (alias "generic-vbed"),
/// "brother-kh868" (alias "kh868").
/// \throw InvalidInput listing the known names when `name` is unknown.
const MachineProfile& machine_profile(std::string_view name);

/// The canonical names of all built-in profiles, in a fixed order.
std::vector<std::string> machine_profile_names();

/// Checks a (possibly user-modified) profile for consistency: positive gauge,
/// needle_count, beds in {1, 2}, at least one carrier, unique carrier names
/// without spaces, max_racking >= 0 (>= 1 for two beds), 1 <= max_transfer_stack
/// <= max_loops_per_needle, max_float_needles >= 1, positive speeds,
/// non-negative overheads.
/// \throw InvalidInput naming the profile and the offending field.
void validate_machine_profile(const MachineProfile& profile);

/// Time of one carriage pass of `kind` spanning `span_needles` needles
/// (see the timing model in the file comment), in seconds.
/// \pre span_needles >= 0
double pass_time_seconds(const MachineProfile& profile, PassKind kind, int span_needles);

}  // namespace knitforge
