#include "knitforge/report/machine_report.h"

#include <algorithm>
#include <limits>

namespace knitforge {

nlohmann::json machine_report_json(const KnitoutProgram& program, const MachineProfile& profile,
                                   const KnittingMap& map, const std::string& knitout_file,
                                   const StitchMesh* designed) {
  nlohmann::json j;
  const KnitoutStats& s = program.stats;
  int inc = 0, dec = 0;
  for (CellType c : map.cells) {
    inc += c == CellType::Increase;
    dec += c == CellType::Decrease;
  }
  auto shaping = [&](int fabric_xfers, int other_xfers) -> nlohmann::json {
    return {{"transfer_stitches", inc + dec},
            {"short_column_increases", inc},
            {"short_column_decreases", dec},
            {"wales_started", s.increases},
            {"wales_ended", s.decreases},
            {"edge_bound_off", s.edge_chained},
            {"transfers", fabric_xfers},
            {"other_transfers", other_xfers}};
  };
  j["profile"] = profile.name;
  j["machine"] = profile.display_name;
  j["gauge"] = profile.gauge;
  j["knitout"] = knitout_file;
  j["stitches"] = map.num_stitches();
  j["courses"] = map.rows;
  j["wales"] = map.cols;
  if (designed && designed->num_vertices() > 0) {
    Vec3 lo = Vec3::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
    for (const Vec3& v : designed->vertices) {
      lo = lo.cwiseMin(v);
      hi = hi.cwiseMax(v);
    }
    const Vec3 size = hi - lo;
    j["finished_size_mm"] = {size.x(), size.y(), size.z()};
  }
  if (program.simulation) {
    const KnitoutSimulation& sim = *program.simulation;
    j["verdict"] = sim.ok() ? "VALID" : "INVALID";
    j["matches_map"] = program.comparison && program.comparison->ok();
    j["errors"] = sim.errors;
    j["warnings"] = sim.warnings;
    j["knit_time_s"] = sim.stats.time_s;
    auto& yarn = j["yarn_m"] = nlohmann::json::array();
    for (size_t c = 0; c < sim.stats.yarn_mm.size(); ++c) {
      if (sim.stats.yarn_mm[c] <= 0.0) continue;
      const std::string& name = sim.graph.carrier_names[c];
      const char* role = name == program.main_carrier    ? "main"
                         : name == program.waste_carrier ? "waste"
                         : name == program.draw_carrier  ? "draw thread"
                                                          : "other";
      yarn.push_back({{"carrier", name}, {"role", role}, {"metres", sim.stats.yarn_mm[c] / 1000.0}});
    }
    j["carriage_passes"] = sim.stats.carriage_passes;
    j["racks"] = sim.stats.racks;
    j["shaping"] = shaping(sim.stats.transfers_by_section[0], sim.stats.transfers - sim.stats.transfers_by_section[0]);
  } else {
    j["verdict"] = "NOT VERIFIED";
    j["shaping"] = shaping(s.shaping_xfers, s.xfers - s.shaping_xfers);
  }
  j["short_row_turns"] = {{"inside", s.inside_turns}, {"closed", s.closed_turns}, {"open", s.open_turns}};
  j["waste_courses"] = s.waste_rows;
  j["needles"] = {s.first_needle, s.last_needle};
  j["notes"] = program.warnings;
  if (s.waste_rows > 0) j["notes"].push_back("waste section: " + profile.writer.waste_reason);
  j["notes"].push_back("knitting time and yarn lengths are estimates from nominal machine data");
  return j;
}

nlohmann::json machine_report_skipped(const MachineProfile& profile, const std::string& reason) {
  return {{"profile", profile.name}, {"machine", profile.display_name}, {"verdict", "NOT WRITTEN"}, {"reason", reason}};
}

}  // namespace knitforge
