#pragma once
/// \file knitout_rules.h
/// The rules a knitout program is judged by: every check the parser
/// (knitout_parse.h) and the virtual machine (knitout_simulate.h) make, the
/// category each belongs to, and how the software of each machine profile
/// treats it (docs/machines.md, "Rules per machine").
///
/// A *check* is one condition ("the first pass after `in` runs away from the
/// side where the carriers park"). Its *category* (KnitoutRule) groups checks
/// for counts, JSON and `--strict` ("carrier-direction"). Its *level* on a
/// machine profile says what that machine's software does with it:
///  - Error: the machine cannot or must not execute it — its translator
///    refuses the program or writes a corrupt machine file, or the machine
///    itself cannot do it (racking beyond its range, too many loops);
///  - Warning: the machine runs it but the fabric will suffer (loops dropped
///    at the end unravel, a long float snags) or it is against a convention;
///  - Off: the machine has no such rule (not checked).
/// Levels come from the profile (machine_profile.h, MachineProfile::checks),
/// each with the source it was taken from; a simulation may promote chosen
/// warning categories to errors (SimulateOptions::strict).

#include <array>
#include <cstdint>
#include <optional>
#include <string_view>

#include "knitforge/util/severity.h"

namespace knitforge {

/// Categories of findings (stable names, used in counts, JSON and --strict).
enum class KnitoutRule : uint8_t {
  Syntax,              ///< "syntax": malformed line, unknown operation, magic line, version, line endings
  Header,              ///< "header": missing or malformed header
  Extension,           ///< "extension": x- extension unknown, unsupported or with a bad value
  UndeclaredCarrier,   ///< "undeclared-carrier": carrier not named in ;;Carriers: or not on the machine
  InactiveCarrier,     ///< "inactive-carrier": carrier used while not in, brought in twice, ...
  CarrierLeftIn,       ///< "carrier-left-in": carrier still in at the end
  Racking,             ///< "racking": racking beyond the machine, unsupported fraction
  Misaligned,          ///< "misaligned": transfer/split between needles not aligned at the racking
  Slider,              ///< "slider": knit/tuck on a slider, slider-to-slider or same-bed move
  LoopsPerNeedle,      ///< "loops-per-needle": more loops on a needle than the machine holds
  Float,               ///< "float": a carrier floats over many needles
  Hook,                ///< "hook": yarn-inserting hook misuse
  Drop,                ///< "drop": live fabric dropped (the wale runs)
  EmptyNeedleKnit,     ///< "empty-needle-knit": knit on an empty needle outside a cast-on
  LoopsLeft,           ///< "loops-left": loops left on the needles at the end
  Width,               ///< "width": needles beyond the machine's bed
  CarrierDirection,    ///< "carrier-direction": a carrier's first pass runs from the wrong side
};
inline constexpr int kNumKnitoutRules = 17;

/// Stable name of a category ("syntax", "hook", ...).
std::string_view name(KnitoutRule rule);
/// The category called `name`, or nullopt.
std::optional<KnitoutRule> knitout_rule_from_name(std::string_view name);

/// Every check (stable ids, see knitout_check_id()).
enum class KnitoutCheck : uint8_t {
  // parsing
  MagicLine,            ///< line 1 is not `;!knitout-N`
  Version,              ///< a knitout version other than 2 (read as version 2)
  LineEndings,          ///< CR LF or CR line endings
  Malformed,            ///< a line that does not parse (operands, numbers, needles)
  UnknownOperation,     ///< an operation the spec does not have
  CarriersHeader,       ///< the required `;;Carriers:` header is missing or empty
  CarrierNames,         ///< `;;Carriers:` is not the list the machine's translator requires
  HeaderValue,          ///< a malformed `;;Position:`, `;;Gauge:` or `;;Width:`
  HeaderUnknown,        ///< an unknown header, a header given twice, a header after the first operation
  ExtensionUnknown,     ///< an x- extension the machine's software does not know (ignored)
  ExtensionValue,       ///< a known x- extension with a value the machine's software refuses
  UndeclaredCarrier,    ///< a carrier set names a carrier missing from `;;Carriers:`
  // carriers
  CarrierNotOnMachine,  ///< `;;Carriers:` names a carrier the machine does not have
  CarrierNotIn,         ///< a carrier used while it is not in
  CarrierInTwice,       ///< `in` of a carrier that is in
  FirstUseSet,          ///< the first operation after `in` uses another carrier set
  OutNotIn,             ///< `out` of a carrier that is not in
  OutBeforeStitch,      ///< `out` of a carrier that made no stitch
  CarrierLeftIn,        ///< a carrier is still in at the end
  FirstPassDirection,   ///< a carrier's first pass after `in` starts from the side opposite its parking side
  Plating,              ///< a stitch made with several carriers at once
  // yarn-inserting hook
  HookUnavailable,      ///< inhook/releasehook/outhook on a machine without a hook
  HookBusy,             ///< inhook while the hook holds a carrier
  ReleasehookMismatch,  ///< releasehook of carriers the hook does not hold, or of an empty hook
  ReleasehookEarly,     ///< releasehook before the hooked carriers made a stitch
  HookTransfer,         ///< a transfer or split while the hook holds a carrier
  OutWhileHooked,       ///< `out` of a carrier the hook still holds, outhook while the hook holds another
  HookLeft,             ///< the hook still holds a carrier at the end
  // racking and needles
  RackingRange,         ///< |racking| beyond the machine
  RackingFraction,      ///< a fractional racking the machine cannot rack to
  QuarterPitchAsHalf,   ///< a quarter-pitch racking the machine's translator knits at half pitch
  Misaligned,           ///< transfer or split between needles that do not face each other
  SameBedMove,          ///< transfer or split within one bed, or slider to slider
  SliderStitch,         ///< knit/tuck/split/amiss on a slider
  BackBedOnOneBed,      ///< the back bed on a one-bed machine
  NeedleRange,          ///< needles beyond the bed (program too wide, or outside 1..N with Position Keep)
  // loops and fabric
  LoopsPerNeedle,       ///< more loops on a needle than the machine holds
  TransferStack,        ///< more loops than the transfer stack limit after a transfer
  Float,                ///< consecutive stitches of a carrier further apart than the float limit
  Run,                  ///< a drop releases a knit loop whose wale then runs (unravels)
  EmptyNeedleKnit,      ///< knit/split on an empty needle outside a cast-on or waste section
  LoopsLeft,            ///< loops left on the needles at the end (no `leave-loops` comment)
};
inline constexpr int kNumKnitoutChecks = 42;

/// What the software of a machine does with a check (see the file comment).
enum class CheckLevel : uint8_t { Off = 0, Warning = 1, Error = 2 };

/// Static description of a check.
struct KnitoutCheckInfo {
  std::string_view id;       ///< stable id ("first-pass-direction")
  KnitoutRule rule;          ///< its category
  std::string_view summary;  ///< one line: what is checked
};

/// The description of `check`.
const KnitoutCheckInfo& knitout_check_info(KnitoutCheck check);
/// Shorthands.
inline std::string_view knitout_check_id(KnitoutCheck c) { return knitout_check_info(c).id; }
inline KnitoutRule knitout_check_rule(KnitoutCheck c) { return knitout_check_info(c).rule; }
/// The check with this id, or nullopt.
std::optional<KnitoutCheck> knitout_check_from_id(std::string_view id);

/// "off", "warning", "error".
std::string_view name(CheckLevel level);

/// Which warning categories a simulation turns into errors.
using StrictRules = std::array<bool, kNumKnitoutRules>;
/// Every category strict (what knitforge demands of its own programs).
StrictRules all_rules_strict();
/// Parses "all", "none" or a comma-separated list of category names
/// ("drop,loops-left") into a StrictRules.
/// \throw InvalidInput naming the unknown category and listing the names.
StrictRules parse_strict_rules(std::string_view text);

}  // namespace knitforge
