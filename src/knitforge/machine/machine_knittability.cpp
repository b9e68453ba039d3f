#include "knitforge/machine/machine_knittability.h"

#include <algorithm>

#include <fmt/core.h>

#include "knitforge/convert/map_knittability.h"
#include "knitforge/machine/hand_instructions.h"
#include "knitforge/machine/needle_layout.h"
#include "knitforge/machine/tube_layout.h"
#include "knitforge/util/errors.h"

namespace knitforge {

KnittabilityReport check_machine_knittability(const KnittingMap& map, const MachineProfile& profile,
                                              const KnitoutOptions& options,
                                              const KnittabilityOptions& report_options) {
  KnittabilityReport seed = check_knittability(map, KnitParams{}, report_options);
  if (!seed.ok()) return seed;
  std::vector<KnittabilityViolation> found = seed.violations;  // warnings only
  KnitParams unit;
  auto add = [&](int row, int col, std::string message) {
    KnittabilityViolation v;
    v.rule = KnitRule::MachineLimit;
    if (row >= 0) {
      v.cells.push_back({row, col});
      v.position = Vec3((col + 0.5) * unit.stitch_width, (row + 0.5) * unit.stitch_height, 0.0);
    }
    v.message = std::move(message);
    found.push_back(std::move(v));
  };
  std::vector<LayoutProblem> problems;
  if (map.tubular() && profile.beds != 2) {
    add(-1, -1,
        fmt::format("machine '{}' has one needle bed: a tube is knitted in the round on two beds (docs/tubes.md)",
                    profile.name));
    return make_knittability_report(std::move(found), report_options);
  }
  if (map.tubular()) {
    TubeLayoutOptions lo;
    lo.max_racking = profile.max_racking;
    lo.max_stack = std::max(2, profile.max_transfer_stack);
    lo.close_turns = options.close_turns;
    problems = plan_tube_layout(map, lo).problems;
  } else {
    NeedleLayoutOptions lo;
    lo.max_shift = profile.beds == 2 ? std::max(1, profile.max_racking) : std::max(1, profile.needle_count);
    lo.max_stack = std::max(2, profile.max_transfer_stack);
    lo.close_turns = options.close_turns;
    problems = plan_needle_layout(map, lo).problems;
  }
  for (const auto& p : problems) add(p.row, p.col, p.message);
  if (problems.empty()) {
    try {
      if (profile.beds == 2) {
        (void)write_knitout(map, profile, options);
      } else {
        (void)hand_instructions(map, profile);
      }
    } catch (const Error& e) {
      add(-1, -1, std::string(e.what()));
    }
  }
  return make_knittability_report(std::move(found), report_options);
}

}  // namespace knitforge
