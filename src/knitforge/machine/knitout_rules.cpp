#include "knitforge/machine/knitout_rules.h"

#include <string>

#include <fmt/core.h>

#include "knitforge/util/errors.h"

namespace knitforge {

namespace {

constexpr std::array<std::string_view, kNumKnitoutRules> kRuleNames = {
    "syntax",   "header",     "extension",       "undeclared-carrier", "inactive-carrier", "carrier-left-in",
    "racking",  "misaligned", "slider",          "loops-per-needle",   "float",            "hook",
    "drop",     "empty-needle-knit", "loops-left", "width",            "carrier-direction",
};

using R = KnitoutRule;
// In the order of KnitoutCheck.
constexpr std::array<KnitoutCheckInfo, kNumKnitoutChecks> kChecks = {{
    {"magic-line", R::Syntax, "line 1 is the magic line ;!knitout-N"},
    {"version", R::Syntax, "the knitout version is 2 (others are read as version 2)"},
    {"line-endings", R::Syntax, "lines end with LF, not CR LF or CR"},
    {"malformed", R::Syntax, "every line parses: operands, numbers, needles, carrier sets"},
    {"unknown-operation", R::Syntax, "every operation is one of the spec's"},
    {"carriers-header", R::Header, "a ;;Carriers: header names the carriers before the first operation"},
    {"carrier-names", R::Header, ";;Carriers: lists exactly the carriers the machine's translator requires"},
    {"header-value", R::Header, ";;Position:, ;;Gauge: and ;;Width: have valid values"},
    {"header-unknown", R::Header, "headers are known, given once, and come before the first operation"},
    {"extension-unknown", R::Extension, "x- extensions are known to the machine's software (others are ignored)"},
    {"extension-value", R::Extension, "known x- extensions have values the machine's software accepts"},
    {"undeclared-carrier", R::UndeclaredCarrier, "carrier sets name only carriers of ;;Carriers:"},
    {"carrier-not-on-machine", R::UndeclaredCarrier, ";;Carriers: names only carriers the machine has"},
    {"carrier-not-in", R::InactiveCarrier, "a carrier is used only while it is in"},
    {"carrier-in-twice", R::InactiveCarrier, "a carrier is not brought in while it is in"},
    {"first-use-set", R::InactiveCarrier, "the first operation after in uses exactly the carrier set brought in"},
    {"out-not-in", R::InactiveCarrier, "a carrier is taken out only while it is in"},
    {"out-before-stitch", R::InactiveCarrier, "a carrier is taken out only after it made a stitch"},
    {"carrier-left-in", R::CarrierLeftIn, "every carrier is out at the end"},
    {"first-pass-direction", R::CarrierDirection,
     "a carrier's first pass after in runs away from the side where the carriers wait"},
    {"plating", R::InactiveCarrier, "a stitch is made with one carrier (no plating)"},
    {"hook-unavailable", R::Hook, "inhook, releasehook and outhook only on a machine with a yarn-inserting hook"},
    {"hook-busy", R::Hook, "inhook only while the hook holds no carrier"},
    {"releasehook-mismatch", R::Hook, "releasehook names exactly the carriers the hook holds"},
    {"releasehook-early", R::Hook, "releasehook only after the hooked carriers made a stitch"},
    {"hook-transfer", R::Hook, "no transfer or split while the hook holds a carrier"},
    {"out-while-hooked", R::Hook, "no out of a hooked carrier, no outhook while the hook holds another"},
    {"hook-left", R::Hook, "the hook holds no carrier at the end"},
    {"racking-range", R::Racking, "|racking| is within the machine's range"},
    {"racking-fraction", R::Racking, "a fractional racking is one the machine can rack to"},
    {"quarter-pitch-as-half", R::Racking, "quarter-pitch racking is knitted as written (not at half pitch)"},
    {"misaligned", R::Misaligned, "transfers and splits go between needles aligned at the current racking"},
    {"same-bed-move", R::Slider, "transfers and splits go between the beds, never slider to slider"},
    {"slider-stitch", R::Slider, "knit, tuck, split and amiss are not made on sliders"},
    {"back-bed-on-one-bed", R::Slider, "a one-bed machine uses no back-bed needle"},
    {"needle-range", R::Width, "needles stay on the machine's bed"},
    {"loops-per-needle", R::LoopsPerNeedle, "no needle holds more loops than the machine holds"},
    {"transfer-stack", R::LoopsPerNeedle, "a transfer stacks at most the transfer-stack limit on a needle"},
    {"float", R::Float, "consecutive stitches of a carrier are at most the float limit apart"},
    {"run", R::Drop, "a drop does not release a knit loop whose wale then runs"},
    {"empty-needle-knit", R::EmptyNeedleKnit, "knit and split only on needles holding loops (outside a cast-on)"},
    {"loops-left", R::LoopsLeft, "no loops are left on the needles at the end (unless a comment says leave-loops)"},
}};

}  // namespace

std::string_view name(KnitoutRule rule) { return kRuleNames[static_cast<size_t>(rule)]; }

std::optional<KnitoutRule> knitout_rule_from_name(std::string_view n) {
  for (size_t i = 0; i < kRuleNames.size(); ++i) {
    if (kRuleNames[i] == n) return static_cast<KnitoutRule>(i);
  }
  return std::nullopt;
}

const KnitoutCheckInfo& knitout_check_info(KnitoutCheck check) { return kChecks[static_cast<size_t>(check)]; }

std::optional<KnitoutCheck> knitout_check_from_id(std::string_view id) {
  for (size_t i = 0; i < kChecks.size(); ++i) {
    if (kChecks[i].id == id) return static_cast<KnitoutCheck>(i);
  }
  return std::nullopt;
}

std::string_view name(CheckLevel level) {
  switch (level) {
    case CheckLevel::Off: return "off";
    case CheckLevel::Warning: return "warning";
    case CheckLevel::Error: return "error";
  }
  return "off";
}

StrictRules all_rules_strict() {
  StrictRules s{};
  s.fill(true);
  return s;
}

StrictRules parse_strict_rules(std::string_view text) {
  StrictRules s{};
  if (text == "all") return all_rules_strict();
  if (text == "none" || text.empty()) return s;
  size_t start = 0;
  while (start <= text.size()) {
    const size_t comma = text.find(',', start);
    const std::string_view item =
        text.substr(start, comma == std::string_view::npos ? std::string_view::npos : comma - start);
    const auto rule = knitout_rule_from_name(item);
    if (!rule) {
      std::string names;
      for (auto n : kRuleNames) names += (names.empty() ? "" : ", ") + std::string(n);
      throw InvalidInput(fmt::format("--strict: unknown category '{}'; use all, none or a comma-separated list of: {}",
                                     std::string(item.substr(0, 80)), names));
    }
    s[static_cast<size_t>(*rule)] = true;
    if (comma == std::string_view::npos) break;
    start = comma + 1;
  }
  return s;
}

}  // namespace knitforge
