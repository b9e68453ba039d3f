#include "knitforge/report/program_report.h"

#include <cmath>
#include <filesystem>
#include <ostream>

#include <fmt/core.h>

#include "knitforge/convert/map_to_stitch_mesh.h"
#include "knitforge/convert/relax_stitch_mesh.h"
#include "knitforge/convert/stitch_mesh_to_yarn.h"
#include "knitforge/io/knitting_map_csv.h"
#include "knitforge/io/polyline_obj.h"
#include "knitforge/io/stitch_mesh_ply.h"
#include "knitforge/machine/machine_profile.h"
#include "knitforge/report/report_html.h"
#include "knitforge/report/simulation_json.h"
#include "knitforge/util/atomic_file.h"
#include "knitforge/util/errors.h"

namespace knitforge {

namespace {

using json = nlohmann::json;

std::string carriers_text(const std::vector<std::string>& names, uint32_t mask) {
  std::string s;
  for (size_t c = 0; c < names.size() && c < 32; ++c)
    if (mask & (1u << c)) s += (s.empty() ? "" : " ") + names[c];
  return s;
}

// The rounds of a plain tube as a ring of quads closed around, on a
// cylinder of the ring's circumference (normals outwards).
StitchMesh tube_mesh(int rounds, int ring, const KnitParams& p) {
  StitchMesh m;
  const double radius = ring * p.stitch_width / (2.0 * M_PI);
  for (int i = 0; i <= rounds; ++i) {
    for (int j = 0; j < ring; ++j) {
      const double a = -2.0 * M_PI * j / ring;
      m.vertices.emplace_back(radius * std::cos(a), i * p.stitch_height, radius * std::sin(a));
    }
  }
  auto V = [ring](int i, int j) { return i * ring + (j % ring); };
  for (int r = 0; r < rounds; ++r) {
    for (int j = 0; j < ring; ++j) {
      Stitch s;
      s.v = {V(r, j), V(r, j + 1), V(r + 1, j + 1), V(r + 1, j)};
      s.course = r;
      s.wale = j;
      m.stitches.push_back(s);
    }
  }
  return m;
}

}  // namespace

ProgramReport write_program_report(const std::string& program_name, const std::string& program_text,
                                   const KnitoutSimulation& sim, const std::string& outdir,
                                   const ProgramReportOptions& opt) {
  if (opt.relax_iterations < 0 || opt.max_stitches < 0)
    throw InvalidInput("program report: relax_iterations and max_stitches must be >= 0");
  KnitParams params = opt.params;
  const double pitch = 25.4 / (sim.stats.gauge > 0 ? sim.stats.gauge : 15.0);
  if (!(params.stitch_width > 0)) params.stitch_width = pitch;
  if (!(params.stitch_height > 0)) params.stitch_height = 0.75 * pitch;

  ProgramReport out;
  out.fabric = knit_graph_fabric(sim);
  const KnitGraphFabric& F = out.fabric;
  const KnitGraph& g = sim.graph;
  const std::filesystem::path dir(outdir);
  std::filesystem::create_directories(dir);
  auto file = [&](const char* n) { return (dir / n).string(); };
  json notes = json::array();

  // The fabric's stitch mesh, and per loop the stitch it belongs to.
  StitchMesh mesh;
  std::vector<int> stitch_of_loop(static_cast<size_t>(g.num_loops()), -1);
  const int stitches = static_cast<int>(F.stitch_loops.size());
  const bool draw = stitches <= opt.max_stitches;
  if (!draw)
    notes.push_back(fmt::format("{} stitches: more than the {} drawn; only report.json and knitout.k are written",
                                stitches, opt.max_stitches));
  RelaxOptions ro;
  ro.max_iterations = opt.relax_iterations;
  if (draw && F.map.rows > 0) {  // a sheet, or a tube read back as its tubular map
    mesh = map_to_stitch_mesh(F.map, params, ro);
    for (int s = 0; s < mesh.num_stitches(); ++s) {
      const Stitch& st = mesh.stitches[static_cast<size_t>(s)];
      const int l = F.loop_of_cell[static_cast<size_t>(st.course) * F.map.cols + st.wale];
      if (l >= 0) stitch_of_loop[static_cast<size_t>(l)] = s;
    }
    write_knitting_map_csv(file("knitting_map.csv"), F.map);
    try {
      write_yarn_obj(file("yarn.obj"), stitch_mesh_to_yarn(mesh, params));
    } catch (const Error& e) {
      notes.push_back(std::string("no yarn model: ") + e.what());
    }
  } else if (draw && F.ring > 0) {  // plain rounds without a map
    mesh = tube_mesh(F.rounds, F.ring, params);
    RelaxOptions tro = ro;
    tro.warm_up = 0.0;
    mesh = relax_stitch_mesh(mesh, params, tro).mesh;
    for (size_t i = 0; i < F.loop_of_round_stitch.size(); ++i)
      stitch_of_loop[static_cast<size_t>(F.loop_of_round_stitch[i])] = static_cast<int>(i);
    notes.push_back("a tube: drawn as its rounds closed around (no yarn model; the yarn model follows a sheet)");
  } else if (F.kind.empty()) {
    notes.push_back("the fabric is not drawn: " + F.reason);
  }
  if (mesh.num_stitches() > 0) write_stitch_mesh_ply(file("stitch_mesh.ply"), mesh);

  // The stitch a loop's finding is placed on: its own, else the nearest
  // stitch up its wale, else down.
  auto place = [&](int l) {
    for (int k = 0, x = l; x >= 0 && k < 64; ++k, x = g.loops[static_cast<size_t>(x)].child)
      if (stitch_of_loop[static_cast<size_t>(x)] >= 0) return stitch_of_loop[static_cast<size_t>(x)];
    for (int k = 0, x = l; x >= 0 && k < 64; ++k) {
      if (stitch_of_loop[static_cast<size_t>(x)] >= 0) return stitch_of_loop[static_cast<size_t>(x)];
      const auto ps = g.parents_of(x);
      x = ps.empty() ? -1 : ps.front();
    }
    return -1;
  };

  json& j = out.json;
  j["program"] = program_name;
  const SimulationStats& st = sim.stats;
  json machine = {{"profile", sim.machine},
                  {"machine", machine_profile(sim.machine).display_name},
                  {"verdict", sim.ok() ? "VALID" : "INVALID"},
                  {"errors", sim.errors},
                  {"warnings", sim.warnings},
                  {"gauge", st.gauge},
                  {"knit_time_s", st.time_s},
                  {"carriage_passes", st.carriage_passes},
                  {"racks", st.racks},
                  {"needles", {st.min_needle, st.max_needle}},
                  {"stitches", stitches}};
  json yarn = json::array();
  for (size_t c = 0; c < st.yarn_mm.size(); ++c)
    if (st.yarn_mm[c] > 0.0)
      yarn.push_back({{"carrier", g.carrier_names[c]}, {"role", "yarn"}, {"metres", st.yarn_mm[c] / 1000.0}});
  machine["yarn_m"] = std::move(yarn);
  machine["operations"] = {{"knits", st.knits},         {"tucks", st.tucks},   {"splits", st.splits},
                           {"misses", st.misses},       {"transfers", st.transfers}, {"drops", st.drops}};
  const json verdict = simulation_json(sim);
  machine["counts"] = verdict["counts"];
  machine["notes"] = json::array({"knitting time and yarn lengths are estimates from nominal machine data"});
  if (F.map.rows > 0) {
    machine["courses"] = F.map.rows;
    machine["wales"] = F.map.cols;
  }
  j["machine"] = std::move(machine);
  json fabric = {{"kind", F.kind.empty() ? "none" : F.kind},
                 {"stitches", stitches},
                 {"stitch_size_mm", {params.stitch_width, params.stitch_height}}};
  if (!F.reason.empty()) fabric["reason"] = F.reason;
  if (F.map.rows > 0) {
    fabric["courses"] = F.map.rows;
    fabric["wales"] = F.map.cols;
  }
  if (F.map.tubular()) {
    int rounds = 0;
    for (int r = 0; r < F.map.rows; ++r) rounds += F.map.closed(r);
    fabric["rounds"] = rounds;
    fabric["closed_end"] = F.map.closed_end;
  }
  if (F.ring > 0) {
    fabric["rounds"] = F.rounds;
    fabric["ring"] = F.ring;
  }
  j["fabric"] = std::move(fabric);
  json courses = json::array();
  for (size_t p = 0; p < sim.passes.size(); ++p) {
    const SimulatedPass& sp = sim.passes[p];
    courses.push_back({{"pass", p},
                       {"lines", {sp.first_line, sp.last_line}},
                       {"carriers", carriers_text(g.carrier_names, sp.carriers)},
                       {"direction", sp.direction > 0 ? "+" : "-"},
                       {"knits", sp.knits},
                       {"tucks", sp.tucks},
                       {"splits", sp.splits},
                       {"misses", sp.misses},
                       {"needles", {sp.min_slot, sp.max_slot}},
                       {"section", std::string(name(sp.section))},
                       {"time_s", sp.time_s}});
  }
  j["courses"] = std::move(courses);
  json diags = verdict["diagnostics"];
  int placed = 0;
  for (size_t k = 0; k < diags.size(); ++k) {
    const KnitoutDiagnostic& d = sim.diagnostics[k];
    const int s = d.loop >= 0 && mesh.num_stitches() > 0 ? place(d.loop) : -1;
    if (s >= 0) {
      const Vec3 c = stitch_centroid(mesh, s);
      diags[k]["stitch"] = s;
      diags[k]["position"] = {c.x(), c.y(), c.z()};
      ++placed;
    }
  }
  j["diagnostics"] = std::move(diags);
  j["diagnostics_placed"] = placed;
  if (sim.errors + sim.warnings > static_cast<int>(sim.diagnostics.size()))
    notes.push_back(fmt::format("{} more findings are counted but not listed", sim.errors + sim.warnings -
                                                                                   static_cast<int>(sim.diagnostics.size())));
  j["notes"] = std::move(notes);

  write_file_atomically(file("knitout.k"), [&](std::ostream& os) { os << program_text; }, true);
  write_file_atomically(file("report.json"), [&](std::ostream& os) { os << j.dump(2) << '\n'; }, true);
  if (opt.html) {
    ReportHtmlOptions ho;
    ho.title = std::filesystem::path(program_name).filename().string();
    write_report_html(outdir, ho);
  }
  return out;
}

}  // namespace knitforge
