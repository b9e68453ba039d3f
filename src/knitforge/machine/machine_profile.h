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

#include <array>
#include <string>
#include <string_view>
#include <vector>

#include "knitforge/machine/knitout_rules.h"

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

/// A side of the needle bed (where carriers wait before `in` and after `out`).
enum class BedSide : uint8_t { None, Left, Right };

/// How the machine's software treats one check (knitout_rules.h), and the
/// public source the level was taken from (a translator's message, the spec,
/// a simulator, the seed).
struct CheckRule {
  CheckLevel level = CheckLevel::Error;
  std::string source;
};

/// The values an x- extension takes on a machine's software.
enum class ExtensionValue : uint8_t {
  DigitOrLetter,       ///< one character 0-9 or A-Z (Kniterate stitch numbers)
  NonNegativeInteger,  ///< 0, 1, 2, ...
  Number,              ///< any number
  OnOffAuto,           ///< on, off or auto
  Keyword,             ///< one of `keywords`
  Anything,            ///< not checked (e.g. x-vis-color)
  NoValue,             ///< no argument
};

/// An x- extension the machine's software reads.
struct ExtensionRule {
  std::string name;  ///< "x-stitch-number"
  ExtensionValue value = ExtensionValue::Anything;
  std::vector<std::string> keywords;  ///< for ExtensionValue::Keyword
  std::string source;                 ///< where it is documented
};

/// Machine settings written (as x- extensions) at the start of a section of
/// a program; "" / -1 = not written (the machine's default applies).
struct SectionSettings {
  std::string stitch_number;       ///< x-stitch-number (a stitch-table entry)
  std::string xfer_stitch_number;  ///< x-xfer-stitch-number
  int speed_number = -1;           ///< x-speed-number
  int roller_advance = -1;         ///< x-roller-advance (Kniterate take-down)
  bool empty() const {
    return stitch_number.empty() && xfer_stitch_number.empty() && speed_number < 0 && roller_advance < 0;
  }
};

/// Operator-ready defaults of the knitout writer for a machine: what a
/// machine operator expects a program to start and end with.
struct WriterDefaults {
  int waste_rows = 0;          ///< courses of waste yarn (+ a draw thread) before the fabric; 0 = none
  std::string waste_reason;    ///< why the machine needs it (docs, --help)
  SectionSettings waste;       ///< settings of the waste section
  SectionSettings cast_on;     ///< settings of the cast-on
  SectionSettings body;        ///< settings of the fabric courses
  SectionSettings bind_off;    ///< settings of the bind-off
  std::string settings_source;  ///< where the setting values come from
};

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
  /// Where carriers wait before `in` and return after `out`: a carrier's
  /// first pass runs away from this side (check first-pass-direction).
  BedSide carrier_park_side = BedSide::None;
  /// Fractional rackings (in (0, 1), of R - floor(R)) the machine racks to.
  std::vector<double> racking_fractions;
  /// The translator knits quarter-pitch rackings (fraction 0.25) at half
  /// pitch (+0.25), as the Kniterate's does.
  bool quarter_pitch_as_half = false;
  /// The exact `;;Carriers:` value the machine's translator requires ("" = any).
  std::string required_carriers_header;
  /// The x- extensions the machine's software reads (others: extension-unknown).
  std::vector<ExtensionRule> extensions;
  /// Level and source of every check, indexed by KnitoutCheck.
  std::array<CheckRule, kNumKnitoutChecks> checks;
  /// Defaults of the knitout writer.
  WriterDefaults writer;

  /// The level of `check` on this machine.
  CheckLevel level(KnitoutCheck check) const { return checks[static_cast<size_t>(check)].level; }
  /// The extension rule called `name`, or nullptr.
  const ExtensionRule* extension(std::string_view name) const;

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
/// non-negative overheads, racking fractions in (0, 1), waste_rows >= 0.
/// \throw InvalidInput naming the profile and the offending field.
void validate_machine_profile(const MachineProfile& profile);

/// The rules of `profile` as a Markdown table: one row per check with its
/// category, level and source (docs/machines.md is made from this).
std::string machine_rules_markdown(const MachineProfile& profile);

/// Time of one carriage pass of `kind` spanning `span_needles` needles
/// (see the timing model in the file comment), in seconds.
/// \pre span_needles >= 0
double pass_time_seconds(const MachineProfile& profile, PassKind kind, int span_needles);

}  // namespace knitforge
