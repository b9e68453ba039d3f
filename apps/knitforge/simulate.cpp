// knitforge simulate: run a knitout program on a virtual machine, report its
// errors and statistics, and optionally check it knits a given map.
// Exit 0 when the program is valid (and matches the map), 1 when not.
#include <cstdio>

#include <fmt/core.h>
#include <nlohmann/json.hpp>

#include "cli_common.h"
#include "knitforge/convert/stitch_mesh_to_map.h"
#include "knitforge/machine/knit_graph_compare.h"
#include "knitforge/machine/knitout_parse.h"
#include "knitforge/machine/knitout_rules.h"
#include "knitforge/machine/knitout_simulate.h"
#include "knitforge/machine/machine_profile.h"

namespace knitforge::cli {

namespace {

nlohmann::json to_json(const KnitoutSimulation& sim) {
  nlohmann::json j;
  j["valid"] = sim.ok();
  j["machine"] = sim.machine;
  j["errors"] = sim.errors;
  j["warnings"] = sim.warnings;
  const SimulationStats& st = sim.stats;
  j["stats"] = {{"carriage_passes", st.carriage_passes},
                {"knit_passes", st.knit_passes},
                {"transfer_passes", st.transfer_passes},
                {"racks", st.racks},
                {"knits", st.knits},
                {"tucks", st.tucks},
                {"splits", st.splits},
                {"misses", st.misses},
                {"transfers", st.transfers},
                {"fabric_transfers", st.transfers_by_section[0]},
                {"other_transfers", st.transfers - st.transfers_by_section[0]},
                {"drops", st.drops},
                {"loops", sim.graph.num_loops()},
                {"min_needle", st.min_needle},
                {"max_needle", st.max_needle},
                {"time_s", st.time_s},
                {"gauge", st.gauge}};
  auto& yarn = j["stats"]["yarn_mm"] = nlohmann::json::object();
  for (size_t c = 0; c < st.yarn_mm.size(); ++c) {
    if (st.yarn_mm[c] > 0.0) yarn[sim.graph.carrier_names[c]] = st.yarn_mm[c];
  }
  auto& counts = j["counts"] = nlohmann::json::object();
  for (int r = 0; r < kNumKnitoutRules; ++r) {
    if (sim.error_counts[r] + sim.warning_counts[r] > 0) {
      counts[std::string(name(static_cast<KnitoutRule>(r)))] = {{"errors", sim.error_counts[r]},
                                                                {"warnings", sim.warning_counts[r]}};
    }
  }
  auto& diags = j["diagnostics"] = nlohmann::json::array();
  for (const auto& d : sim.diagnostics) {
    diags.push_back({{"line", d.line},
                     {"severity", d.severity == Severity::Error ? "error" : "warning"},
                     {"rule", std::string(name(d.rule))},
                     {"check", std::string(knitout_check_id(d.check))},
                     {"message", d.message}});
  }
  return j;
}

nlohmann::json to_json(const GraphComparison& c) {
  nlohmann::json j;
  j["matches"] = c.ok();
  j["map_stitches"] = c.map_stitches;
  j["fabric_loops"] = c.fabric_loops;
  j["mismatches"] = c.mismatches;
  auto& issues = j["issues"] = nlohmann::json::array();
  for (const auto& m : c.issues) {
    issues.push_back({{"kind", m.kind},
                      {"stitch", m.stitch},
                      {"row", m.row},
                      {"col", m.col},
                      {"line", m.line},
                      {"message", m.message}});
  }
  return j;
}

}  // namespace

void add_simulate_command(CLI::App& app, Action& action) {
  auto* cmd = app.add_subcommand(
      "simulate",
      "Run a knitout program (.k) on a virtual two-bed machine and judge it as that machine's software does: "
      "errors (what it cannot or must not execute) and warnings (what the fabric will suffer), with line "
      "numbers and statistics; with --against, check it knits the given map. Exit 0 when there is no error "
      "(warnings allowed), 1 when there is");
  struct Opts {
    std::string input, machine = "shima-swg091n2", against, strict;
    bool json = false, rules = false;
  };
  auto o = std::make_shared<Opts>();
  cmd->add_option("input", o->input, "Knitout program (.k)");
  cmd->add_option("--machine", o->machine, "Machine profile (shima-swg091n2, kniterate, generic)")
      ->capture_default_str();
  cmd->add_option("--against", o->against,
                  "Knitting map (.csv) or stitch mesh (.ply) the program should knit (implies --strict all)");
  cmd->add_option("--strict", o->strict,
                  "Warning categories to treat as errors: all, none, or a comma-separated list (e.g. "
                  "drop,loops-left,float)");
  cmd->add_flag("--rules", o->rules, "Print the machine's rules (check, category, level, source) as Markdown");
  cmd->add_flag("--json", o->json, "Print the report as JSON");
  cmd->callback([=, &action] {
    action = [=]() -> int {
      const MachineProfile& profile = machine_profile(o->machine);
      if (o->rules) {
        std::printf("%s", machine_rules_markdown(profile).c_str());
        return 0;
      }
      if (o->input.empty()) {
        std::fprintf(stderr, "knitforge: usage error: simulate: the knitout program (.k) is required (or --rules)\n");
        return 2;
      }
      SimulateOptions so;
      so.strict = parse_strict_rules(o->strict);
      if (!o->against.empty()) so.strict = all_rules_strict();
      check_input_file(o->input);
      if (!o->against.empty()) check_input_file(o->against);
      const KnitoutFile file = read_knitout(o->input);
      const KnitoutSimulation sim = simulate_knitout(file, profile, so);
      bool ok = sim.ok();
      nlohmann::json j;
      if (o->json) {
        j = to_json(sim);
        j["file"] = o->input;
      } else {
        std::printf("%s: %s", o->input.c_str(), sim.text().c_str());
      }
      if (!o->against.empty()) {
        const StitchInput in = load_stitch_input(o->against);
        const KnittingMap map = in.is_map ? in.map : stitch_mesh_to_map(in.mesh);
        const GraphComparison cmp = compare_knit_graph(sim.graph, map);
        ok = ok && cmp.ok();
        if (o->json) {
          j["against"] = to_json(cmp);
          j["against"]["map"] = o->against;
        } else {
          std::printf("%s: %s", o->against.c_str(), cmp.text().c_str());
        }
      }
      if (o->json) std::printf("%s\n", j.dump(2).c_str());
      return ok ? 0 : 1;
    };
  });
}

}  // namespace knitforge::cli
