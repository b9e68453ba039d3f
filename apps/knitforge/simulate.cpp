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
#include "knitforge/report/program_report.h"
#include "knitforge/report/simulation_json.h"

namespace knitforge::cli {

void add_simulate_command(CLI::App& app, Action& action) {
  auto* cmd = app.add_subcommand(
      "simulate",
      "Run a knitout program (.k) on a virtual two-bed machine and judge it as that machine's software does: "
      "errors (what it cannot or must not execute) and warnings (what the fabric will suffer), with line "
      "numbers and statistics; with --against, check it knits the given map. Exit 0 when there is no error "
      "(warnings allowed), 1 when there is");
  struct Opts {
    std::string input, machine = "shima-swg091n2", against, strict, report;
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
  cmd->add_option("--report", o->report,
                  "Write a fabric view to this directory: the knit graph as a relaxed stitch mesh, the yarn, "
                  "per-course statistics and the findings placed on the fabric, in report.html");
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
      if (!o->report.empty()) check_output_dir("--report", o->report, {o->input});
      const std::string text = read_text_file(o->input, "knitout program");
      const KnitoutFile file = parse_knitout(text);
      const KnitoutSimulation sim = simulate_knitout(file, profile, so);
      bool ok = sim.ok();
      nlohmann::json j;
      if (o->json) {
        j = simulation_json(sim);
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
          j["against"] = graph_comparison_json(cmp);
          j["against"]["map"] = o->against;
        } else {
          std::printf("%s: %s", o->against.c_str(), cmp.text().c_str());
        }
      }
      if (!o->report.empty()) {
        const ProgramReport rep = write_program_report(o->input, text, sim, o->report);
        const KnitGraphFabric& f = rep.fabric;
        note(fmt::format("fabric view -> {}/report.html ({}{}; {} of {} findings placed on the fabric)", o->report,
                         f.kind.empty() ? "not drawn: " + f.reason : f.kind,
                         f.kind == "sheet" ? fmt::format(", {} courses x {} wales", f.map.rows, f.map.cols)
                         : f.ring > 0      ? fmt::format(", {} round{} of {} stitches", f.rounds, f.rounds == 1 ? "" : "s", f.ring)
                         : f.kind == "tube"
                             ? fmt::format(", {} courses ({} rounds) x {} columns{}", f.map.rows,
                                           rep.json["fabric"]["rounds"].get<int>(), f.map.cols,
                                           f.map.closed_end ? ", closed at the end" : "")
                             : std::string(),
                         rep.json["diagnostics_placed"].get<int>(), rep.json["diagnostics"].size()));
      }
      if (o->json) std::printf("%s\n", j.dump(2).c_str());
      return ok ? 0 : 1;
    };
  });
}

}  // namespace knitforge::cli
