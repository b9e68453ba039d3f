#include "knitforge/report/simulation_json.h"

#include <string>

namespace knitforge {

nlohmann::json simulation_json(const KnitoutSimulation& sim, size_t max_diagnostics) {
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
    if (diags.size() >= max_diagnostics) break;
    diags.push_back({{"line", d.line},
                     {"severity", d.severity == Severity::Error ? "error" : "warning"},
                     {"rule", std::string(name(d.rule))},
                     {"check", std::string(knitout_check_id(d.check))},
                     {"message", d.message}});
  }
  return j;
}

nlohmann::json graph_comparison_json(const GraphComparison& c) {
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

}  // namespace knitforge
