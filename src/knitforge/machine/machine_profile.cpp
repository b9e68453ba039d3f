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
    v.push_back(p);
  }
  {
    MachineProfile p;
    p.name = "kniterate";
    p.display_name = "Kniterate";
    p.knitout_machine = "kniterate";
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
  const auto& t = p.timing;
  if (!(t.knit_speed_mm_s > 0) || !(t.transfer_speed_mm_s > 0)) bad("carriage speeds must be positive");
  if (!(t.pass_overhead_s >= 0) || !(t.transfer_pass_overhead_s >= 0) || !(t.rack_s >= 0) ||
      !(t.carrier_in_out_s >= 0))
    bad("timing overheads must be >= 0");
}

double pass_time_seconds(const MachineProfile& p, PassKind kind, int span_needles) {
  const double span_mm = std::max(0, span_needles) * p.needle_pitch_mm();
  if (kind == PassKind::Transfer)
    return p.timing.pass_overhead_s + p.timing.transfer_pass_overhead_s +
           span_mm / p.timing.transfer_speed_mm_s;
  return p.timing.pass_overhead_s + span_mm / p.timing.knit_speed_mm_s;
}

}  // namespace knitforge
