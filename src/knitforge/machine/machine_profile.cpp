#include "knitforge/machine/machine_profile.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <set>

#include <fmt/core.h>

#include "knitforge/util/errors.h"

namespace knitforge {

namespace {

std::vector<std::string> numbered_carriers(int n) {
  std::vector<std::string> c;
  for (int i = 1; i <= n; ++i) c.push_back(std::to_string(i));
  return c;
}

using C = KnitoutCheck;
using L = CheckLevel;

constexpr const char* kSpec = "knitout spec (textiles-lab/knitout, knitout.html)";
constexpr const char* kBoth =
    "both open translators (textiles-lab knitout-backend-kniterate knitout-to-kcode.js, knitout-backend-swg "
    "knitout-to-dat.js)";
constexpr const char* kKcode = "textiles-lab knitout-backend-kniterate, knitout-to-kcode.js";
constexpr const char* kDat = "textiles-lab knitout-backend-swg, knitout-to-dat.js";
constexpr const char* kVkm = "ACT Lab virtual_knitting_machine (SWG091N2 model)";

void set(MachineProfile& p, C c, L level, std::string source) {
  p.checks[static_cast<size_t>(c)] = {level, std::move(source)};
}

// The levels every profile starts from; each profile then sets what its
// machine's software does differently.
void default_checks(MachineProfile& p) {
  set(p, C::MagicLine, L::Error, fmt::format("{}: line 1 is ;!knitout-N; {} stop without it", kSpec, kBoth));
  set(p, C::Version, L::Warning,
      fmt::format("{}: readers accept any version and warn about later ones; {} warn and read on", kSpec, kBoth));
  set(p, C::LineEndings, L::Warning,
      fmt::format("{}: readers should accept other line endings with a warning; {} warn and strip the CR", kSpec,
                  kBoth));
  set(p, C::Malformed, L::Error, fmt::format("{}: syntax of each operation; {} stop on such a line", kSpec, kBoth));
  set(p, C::UnknownOperation, L::Error, fmt::format("{}: 'unsupported operation'", kBoth));
  set(p, C::CarriersHeader, L::Error, fmt::format("{}: \"'Carriers:' header is required\"", kBoth));
  set(p, C::CarrierNames, L::Off, "any carrier names (the spec lets the header name them)");
  set(p, C::HeaderValue, L::Error, fmt::format("{}: stop on a malformed Gauge, Width or Position", kBoth));
  set(p, C::HeaderUnknown, L::Warning, fmt::format("{}: 'Unknown comment header' (warning)", kBoth));
  set(p, C::ExtensionUnknown, L::Warning,
      fmt::format("{}: readers warn about unsupported extensions and ignore them", kSpec));
  set(p, C::ExtensionValue, L::Error, fmt::format("{}: stop on a bad value of an extension they read", kBoth));
  set(p, C::UndeclaredCarrier, L::Error,
      fmt::format("{}: carrier sets name carriers of the Carriers header; {}: \"isn't named in the Carriers comment "
                  "header\"",
                  kSpec, kBoth));
  set(p, C::CarrierNotOnMachine, L::Error, "the machine has no such carrier");
  set(p, C::CarrierNotIn, L::Error, fmt::format("{}: \"using a carrier that isn't active\"", kBoth));
  set(p, C::CarrierInTwice, L::Error, fmt::format("{}: \"Can't bring in carrier -- it is already active\"", kBoth));
  set(p, C::FirstUseSet, L::Error, fmt::format("{}: \"first use of carriers doesn't match in info\"", kBoth));
  set(p, C::OutNotIn, L::Error, fmt::format("{}: \"Can't bring out carrier -- it isn't yet active\"", kBoth));
  set(p, C::OutBeforeStitch, L::Error, fmt::format("{}: \"it hasn't yet stitched\"", kBoth));
  set(p, C::CarrierLeftIn, L::Error, fmt::format("{}: \"All carriers need to be taken out\"", kBoth));
  set(p, C::FirstPassDirection, L::Off, "carriers may start from either side");
  set(p, C::Plating, L::Off, "several carriers may make a stitch together (plating)");
  set(p, C::HookUnavailable, L::Error, "the machine has no yarn-inserting hook");
  set(p, C::HookBusy, L::Error,
      fmt::format("{}: \"can't bring in ... with hook; hook is holding\"; {}: Inserting_Hook_In_Use", kDat, kVkm));
  set(p, C::ReleasehookMismatch, L::Error, fmt::format("{}: \"Can't releasehook on ..., hook currently holds\"", kDat));
  set(p, C::ReleasehookEarly, L::Error,
      fmt::format("{}: releasehook follows an inhook of the same set and at least one knitting operation", kSpec));
  set(p, C::HookTransfer, L::Error,
      "the hook holds the yarn end at the bed until released; knitforge releases it before any transfer "
      "(docs/machines.md)");
  set(p, C::OutWhileHooked, L::Error,
      fmt::format("{}: \"Can't out carriers, hook release pending\", \"Can't outhook carriers, hook is already "
                  "holding\"; {}: Hooked_Carrier_Exception",
                  kDat, kVkm));
  set(p, C::HookLeft, L::Error, "as carrier-left-in: the hook ends empty");
  set(p, C::RackingRange, L::Error, "the machine's racking range");
  set(p, C::RackingFraction, L::Error, "the machine's fractional rackings");
  set(p, C::QuarterPitchAsHalf, L::Off, "quarter pitch is knitted as written");
  set(p, C::Misaligned, L::Error, fmt::format("{}: \"needles are not aligned at racking R\"", kBoth));
  set(p, C::SameBedMove, L::Error,
      fmt::format("{}: \"must xfer/split front <-> back\"; {}: \"cannot move from slider to slider\"", kBoth, kDat));
  set(p, C::SliderStitch, L::Error,
      fmt::format("{}: Slider_Loop_Exception (a slider cannot form a loop); {}: \"cannot split from slider\"", kVkm,
                  kDat));
  set(p, C::BackBedOnOneBed, L::Error, "the machine has one bed");
  set(p, C::NeedleRange, L::Error,
      fmt::format("{}: with Position Keep the needles must lie in [1, Width]; a program wider than the bed cannot be "
                  "placed",
                  kDat));
  set(p, C::LoopsPerNeedle, L::Error,
      fmt::format("a needle's hook holds only so many loops (the profile's loops-per-needle limit; {} warns at 4)",
                  kVkm));
  set(p, C::TransferStack, L::Warning,
      "seed §1.4.2: loops stacked by transfers stretch the yarn and risk miss-transfers");
  set(p, C::Float, L::Warning, fmt::format("{}: Long_Float_Warning beyond 20 needles; no translator refuses floats", kVkm));
  set(p, C::Run, L::Warning,
      "no translator checks drops: a dropped knit loop whose parents are gone unravels down its wale");
  set(p, C::EmptyNeedleKnit, L::Warning, fmt::format("{}: 'Knitting on empty needle' warning", kVkm));
  set(p, C::LoopsLeft, L::Warning,
      "no translator checks it: live loops unravel when the fabric comes off the machine");
}

std::vector<ExtensionRule> common_extensions() {
  return {{"x-vis-color", ExtensionValue::Anything, {}, "knitout-live-visualizer (display colour; ignored by machines)"}};
}

// Nominal numbers: carriage speeds are typical production settings of the
// machine class (about 1 m/s knitting and 0.6 m/s transferring on a Shima
// whole-garment machine, slower on the small Kniterate), overheads are the
// turn-around of a carriage and one racking step. They rank programs; they do
// not quote production times.
std::vector<MachineProfile> make_profiles() {
  std::vector<MachineProfile> v;
  {
    MachineProfile p;
    p.name = "shima-swg091n2";
    p.display_name = "Shima Seiki SWG091N2";
    p.knitout_machine = "SWG091N2";
    p.description = "Shima Seiki SWG091N2-like whole-garment V-bed, 15 gauge, 10 carriers, yarn-inserting hook";
    p.gauge = 15;
    p.needle_count = 540;  // 36 inch bed at 15 needles per inch
    p.beds = 2;
    p.carriers = numbered_carriers(10);
    p.has_yarn_inserting_hook = true;
    p.max_racking = 4;
    p.max_loops_per_needle = 4;
    p.max_transfer_stack = 3;
    p.max_float_needles = 20;
    p.timing = {1000.0, 600.0, 0.5, 0.3, 0.25, 3.0};
    p.carrier_park_side = BedSide::Right;
    p.racking_fractions = {0.25};
    p.required_carriers_header = "1 2 3 4 5 6 7 8 9 10";
    p.extensions = common_extensions();
    p.extensions.push_back({"x-stitch-number", ExtensionValue::NonNegativeInteger, {},
                            fmt::format("{} (an entry of the machine's stitch table)", kDat)});
    p.extensions.push_back(
        {"x-speed-number", ExtensionValue::NonNegativeInteger, {}, fmt::format("{}; knitout extensions.html", kDat)});
    p.extensions.push_back({"x-presser-mode", ExtensionValue::OnOffAuto, {}, kDat});
    default_checks(p);
    set(p, C::CarrierNames, L::Error, fmt::format("{}: \"'Carriers:' header must be '1 2 3 4 5 6 7 8 9 10'\"", kDat));
    set(p, C::CarrierNotOnMachine, L::Error, "the machine has carriers 1..10");
    set(p, C::FirstPassDirection, L::Warning,
        fmt::format("carriers wait right of the bed ({} takes 'out' to the right; {} refuses a rightward first "
                    "stitch of a hooked carrier); a first pass to the right drags the yarn across the bed",
                    kDat, kVkm));
    set(p, C::HookUnavailable, L::Off, "the machine has a yarn-inserting hook");
    set(p, C::RackingRange, L::Error, fmt::format("{}: maximum rack 4 ({} allows 8)", kVkm, kDat));
    set(p, C::RackingFraction, L::Error,
        fmt::format("{}: \"rackings must be an integer or an integer + 0.25\" (quarter pitch)", kDat));
    p.writer.waste_rows = 16;
    p.writer.waste_reason =
        "the take-down needs fabric to hold before the first course (seed ch. 2: waste yarn gives the pull-down "
        "force for outside widening); the draw thread lets the waste come off without cutting";
    p.writer.settings_source =
        "no stitch or speed numbers are written: the SWG stitch table is the machine's own (knitout-backend-swg "
        "README); set them with --stitch-number / --speed-number";
    v.push_back(p);
  }
  {
    MachineProfile p;
    p.name = "kniterate";
    p.display_name = "Kniterate";
    p.knitout_machine = "Kniterate";
    p.description = "Kniterate digital V-bed, 7 gauge, 252 needles, 6 carriers, no yarn-inserting hook (in/out)";
    p.gauge = 7;
    p.needle_count = 252;
    p.beds = 2;
    p.carriers = numbered_carriers(6);
    p.has_yarn_inserting_hook = false;
    p.width_header = true;
    p.max_racking = 4;
    p.max_loops_per_needle = 3;
    p.max_transfer_stack = 3;
    p.max_float_needles = 12;
    p.timing = {400.0, 250.0, 1.0, 0.5, 0.5, 5.0};
    p.carrier_park_side = BedSide::Left;
    p.racking_fractions = {0.5};
    p.quarter_pitch_as_half = true;
    p.required_carriers_header = "1 2 3 4 5 6";
    p.extensions = common_extensions();
    for (const char* n : {"x-stitch-number", "x-xfer-stitch-number"})
      p.extensions.push_back({n, ExtensionValue::DigitOrLetter, {}, fmt::format("{}: a number 0-9 or a letter A-Z", kKcode)});
    for (const char* n : {"x-speed-number", "x-roller-advance", "x-add-roller-advance", "x-carrier-spacing",
                          "x-carrier-stopping-distance"})
      p.extensions.push_back({n, ExtensionValue::Number, {}, kKcode});
    p.extensions.push_back({"x-xfer-style", ExtensionValue::Keyword, {"four-pass", "two-pass"}, kKcode});
    p.extensions.push_back({"x-end-pass", ExtensionValue::NoValue, {}, kKcode});
    default_checks(p);
    set(p, C::CarrierNames, L::Error, fmt::format("{}: \"'Carriers:' header must be '1 2 3 4 5 6'\"", kKcode));
    set(p, C::CarrierNotOnMachine, L::Error, "the machine has carriers 1..6");
    set(p, C::FirstPassDirection, L::Error,
        fmt::format("{}: carriers park left of needle 0 and 'out' takes them back there; a first pass to the left "
                    "fails its 'properly ordered carrier stops' assertion and the k-code is written with "
                    "misordered carrier stops",
                    kKcode));
    set(p, C::Plating, L::Error,
        fmt::format("{}: 'expecting zero or one carriers per pass' (assertion; the k-code is corrupt)", kKcode));
    set(p, C::HookUnavailable, L::Error, fmt::format("{}: \"cannot 'inhook' on this machine\"", kKcode));
    set(p, C::RackingRange, L::Error, fmt::format("{} (annotated-knitout-1.k): racking -4..4", kKcode));
    set(p, C::RackingFraction, L::Error,
        fmt::format("{}: \"rackings must be an integer or an integer + 0.5\"", kKcode));
    set(p, C::QuarterPitchAsHalf, L::Warning,
        fmt::format("{} adds 0.25 to a racking with fraction .25 (0.25 -> 0.5, -0.75 -> -0.5): it is knitted at "
                    "half pitch",
                    kKcode));
    set(p, C::Float, L::Warning,
        fmt::format("{}; the Kniterate tutorial (annotated-knitout-1.k) warns that floats over ~5 needles drop "
                    "stitches",
                    kVkm));
    p.writer.waste_rows = 70;
    p.writer.waste_reason =
        "the Kniterate has no sinkers: its rollers need about 70 courses of waste fabric to grab before the first "
        "course (knitout-backend-kniterate annotated-knitout-1.k, extras/waste-section.js)";
    p.writer.waste = {"6", "", 300, 400};
    p.writer.cast_on = {"6", "", 100, 100};
    p.writer.body = {"5", "3", 100, 100};
    p.writer.bind_off = {"6", "3", 100, 100};
    p.writer.settings_source =
        "waste: extras/waste-section.js of knitout-backend-kniterate (stitch 6, speed 300, roller 400); body: the "
        "translator's defaults (stitch 5, transfer stitch 3, speed 100, roller 100); cast-on and bind-off one "
        "stitch number looser";
    v.push_back(p);
  }
  {
    MachineProfile p;
    p.name = "generic";
    p.display_name = "Generic V-bed";
    p.knitout_machine = "generic";
    p.description = "Generic two-bed V-bed machine, 12 gauge, 400 needles, 10 carriers, plain in/out";
    p.gauge = 12;
    p.needle_count = 400;
    p.beds = 2;
    p.carriers = numbered_carriers(10);
    p.has_yarn_inserting_hook = false;
    p.max_racking = 4;
    p.max_loops_per_needle = 4;
    p.max_transfer_stack = 3;
    p.max_float_needles = 20;
    p.timing = {800.0, 500.0, 0.6, 0.4, 0.3, 2.0};
    p.racking_fractions = {0.25, 0.5, 0.75};
    p.extensions = common_extensions();
    for (const char* n : {"x-stitch-number", "x-xfer-stitch-number", "x-speed-number", "x-roller-advance",
                          "x-add-roller-advance", "x-presser-mode", "x-carrier-spacing", "x-carrier-stopping-distance",
                          "x-xfer-style", "x-end-pass"})
      p.extensions.push_back({n, ExtensionValue::Anything, {}, "read by one of the open translators"});
    default_checks(p);
    set(p, C::CarrierNotOnMachine, L::Warning, "a generic machine: any carrier names (numbered 1..10 when written)");
    set(p, C::CarrierLeftIn, L::Warning, "the spec does not require every carrier out at the end");
    set(p, C::HookUnavailable, L::Warning,
        "every spec operation is accepted: the hook operations are read as in / releasehook (nothing) / out");
    set(p, C::RackingRange, L::Error, "knitforge's generic profile: |racking| <= 4");
    set(p, C::RackingFraction, L::Error, "any quarter or half pitch");
    p.writer.waste_reason = "no machine-specific take-down is known; pass --waste-rows N for one";
    p.writer.settings_source = "no settings are written";
    v.push_back(p);
  }
  {
    MachineProfile p;
    p.name = "brother-kh868";
    p.display_name = "Brother KH868";
    p.knitout_machine = "KH868";
    p.description = "Brother KH868 single-bed manual machine, 4.5 mm pitch, needles L100..L1 R1..R100 (hand instructions)";
    p.gauge = 25.4 / 4.5;
    p.needle_count = 200;
    p.beds = 1;
    p.manual = true;
    p.carriers = {"1"};
    p.has_yarn_inserting_hook = false;
    p.max_racking = 0;
    p.max_loops_per_needle = 3;
    p.max_transfer_stack = 3;
    p.max_float_needles = 10;
    // A person pushing the carriage: ~0.4 m/s, a few seconds per row for
    // checking the work; a transfer "pass" is moving stitches by hand.
    p.timing = {400.0, 20.0, 3.0, 10.0, 0.0, 30.0};
    default_checks(p);
    set(p, C::RackingRange, L::Error, "a single bed does not rack");
    set(p, C::RackingFraction, L::Error, "a single bed does not rack");
    p.writer.settings_source = "hand instructions: no machine settings";
    v.push_back(p);
  }
  return v;
}

const std::vector<MachineProfile>& profiles() {
  static const std::vector<MachineProfile> v = make_profiles();
  return v;
}

std::string lower(std::string_view s) {
  std::string r(s);
  std::transform(r.begin(), r.end(), r.begin(), [](unsigned char c) { return std::tolower(c); });
  return r;
}

}  // namespace

bool MachineProfile::has_carrier(std::string_view carrier) const {
  return std::find(carriers.begin(), carriers.end(), carrier) != carriers.end();
}

const ExtensionRule* MachineProfile::extension(std::string_view ext) const {
  for (const auto& e : extensions) {
    if (e.name == ext) return &e;
  }
  return nullptr;
}

const MachineProfile& machine_profile(std::string_view name) {
  std::string n = lower(name);
  if (n == "swg091n2" || n == "shima") n = "shima-swg091n2";
  if (n == "generic-vbed") n = "generic";
  if (n == "kh868") n = "brother-kh868";
  for (const auto& p : profiles())
    if (p.name == n) return p;
  std::string known;
  for (const auto& p : profiles()) known += (known.empty() ? "" : ", ") + p.name;
  throw InvalidInput(
      fmt::format("unknown machine '{}': choose one of {}", std::string(name), known));
}

std::vector<std::string> machine_profile_names() {
  std::vector<std::string> names;
  for (const auto& p : profiles()) names.push_back(p.name);
  return names;
}

void validate_machine_profile(const MachineProfile& p) {
  auto bad = [&](const std::string& what) {
    throw InvalidInput(fmt::format("machine profile '{}': {}", p.name, what));
  };
  if (!(p.gauge > 0) || !std::isfinite(p.gauge)) bad("gauge must be positive");
  if (p.needle_count < 1) bad("needle_count must be at least 1");
  if (p.beds != 1 && p.beds != 2) bad("beds must be 1 or 2");
  if (p.carriers.empty()) bad("needs at least one carrier");
  std::set<std::string> seen;
  for (const auto& c : p.carriers) {
    if (c.empty() || c.find_first_of(" \t;") != std::string::npos)
      bad(fmt::format("carrier name '{}' must be non-empty without spaces or ';'", c));
    if (!seen.insert(c).second) bad(fmt::format("carrier '{}' is listed twice", c));
  }
  if (p.max_racking < 0) bad("max_racking must be >= 0");
  if (p.beds == 2 && p.max_racking < 1) bad("a two-bed machine needs max_racking >= 1");
  if (p.max_loops_per_needle < 1) bad("max_loops_per_needle must be >= 1");
  if (p.max_transfer_stack < 1 || p.max_transfer_stack > p.max_loops_per_needle)
    bad("max_transfer_stack must be between 1 and max_loops_per_needle");
  if (p.max_float_needles < 1) bad("max_float_needles must be >= 1");
  for (double f : p.racking_fractions) {
    if (!(f > 0.0 && f < 1.0)) bad(fmt::format("racking fraction {} must lie in (0, 1)", f));
  }
  if (p.writer.waste_rows < 0) bad("writer.waste_rows must be >= 0");
  const auto& t = p.timing;
  if (!(t.knit_speed_mm_s > 0) || !(t.transfer_speed_mm_s > 0)) bad("carriage speeds must be positive");
  if (!(t.pass_overhead_s >= 0) || !(t.transfer_pass_overhead_s >= 0) || !(t.rack_s >= 0) ||
      !(t.carrier_in_out_s >= 0))
    bad("timing overheads must be >= 0");
}

std::string machine_rules_markdown(const MachineProfile& p) {
  std::string s = "| check | category | level | what | source |\n|---|---|---|---|---|\n";
  for (int c = 0; c < kNumKnitoutChecks; ++c) {
    const KnitoutCheckInfo& info = knitout_check_info(static_cast<KnitoutCheck>(c));
    const CheckRule& r = p.checks[static_cast<size_t>(c)];
    s += fmt::format("| `{}` | {} | {} | {} | {} |\n", info.id, name(info.rule), name(r.level), info.summary,
                     r.source);
  }
  return s;
}

double pass_time_seconds(const MachineProfile& p, PassKind kind, int span_needles) {
  const double span_mm = std::max(0, span_needles) * p.needle_pitch_mm();
  if (kind == PassKind::Transfer)
    return p.timing.pass_overhead_s + p.timing.transfer_pass_overhead_s +
           span_mm / p.timing.transfer_speed_mm_s;
  return p.timing.pass_overhead_s + span_mm / p.timing.knit_speed_mm_s;
}

}  // namespace knitforge
