// knitforge check: knittability of a map or stitch mesh (seed §1.2.2), or the
// validity of an input surface. Exit 0 when it passes, 1 when it does not.
#include <cstdio>
#include <fstream>

#include <fmt/core.h>
#include <nlohmann/json.hpp>

#include "cli_common.h"
#include "knitforge/convert/map_knittability.h"
#include "knitforge/core/knittability.h"
#include "knitforge/geometry/surface_checks.h"
#include "knitforge/convert/stitch_mesh_to_map.h"
#include "knitforge/io/knittability_json.h"
#include "knitforge/machine/machine_knittability.h"
#include "knitforge/machine/machine_profile.h"

namespace knitforge::cli {

namespace {

int check_surface(const std::string& path, const std::string& units, bool json) {
  const TriMesh mesh = load_surface(path, units);
  const SurfaceReport r = validate_surface(mesh);
  if (json) {
    nlohmann::json j;
    j["valid"] = r.ok();
    j["is_disk"] = r.is_disk;
    j["vertices"] = r.num_vertices;
    j["faces"] = r.num_faces;
    j["components"] = r.num_components;
    j["boundary_loops"] = r.num_boundary_loops;
    j["genus"] = r.genus;
    j["errors"] = r.num_errors;
    j["warnings"] = r.num_warnings;
    auto& issues = j["issues"] = nlohmann::json::array();
    for (const auto& i : r.issues) {
      issues.push_back({{"kind", std::string(to_string(i.kind))}, {"error", i.is_error},
                        {"element", i.element}, {"message", i.message}});
    }
    std::printf("%s\n", j.dump(2).c_str());
  } else {
    std::printf("%s: %s\n", path.c_str(), r.summary().c_str());
    for (const auto& i : r.issues) {
      std::printf("  %s: %s\n", i.is_error ? "error" : "warning", i.message.c_str());
    }
  }
  return r.ok() ? 0 : 1;
}

}  // namespace

void add_check_command(CLI::App& app, Action& action) {
  auto* cmd = app.add_subcommand(
      "check",
      "Check the knittability of a knitting map (.csv) or stitch mesh (.ply), or the validity of "
      "a surface mesh (.obj/.ply/.off/.stl); exit 0 when it passes, 1 when not");
  struct Opts {
    std::string input, units = "mm", machine = "shima-swg091n2";
    bool json = false;
  };
  auto o = std::make_shared<Opts>();
  cmd->add_option("input", o->input, "Map, stitch mesh or surface mesh")->required();
  cmd->add_flag("--json", o->json, "Print the report as JSON");
  cmd->add_option("--units", o->units, "Units of a surface mesh: mm, cm or m");
  cmd->add_option("--machine", o->machine,
                  "Also check what this machine's program writer needs (loops per needle, bed width, ...): "
                  "shima-swg091n2, kniterate, generic, brother-kh868; 'none' for the seed's rules only")
      ->capture_default_str();
  cmd->callback([=, &action] {
    action = [=]() -> int {
      const std::string ext = extension(o->input);
      const bool stitch_input = ext == ".csv" || (ext == ".ply" && is_stitch_mesh_ply(o->input));
      if (!stitch_input) return check_surface(o->input, o->units, o->json);
      const StitchInput in = load_stitch_input(o->input);
      const bool machine = o->machine != "none";
      const MachineProfile* prof = machine ? &machine_profile(o->machine) : nullptr;
      KnittabilityReport r = in.is_map ? check_knittability(in.map) : check_knittability(in.mesh);
      if (prof && r.ok()) {
        // The mesh's map (seed Alg. 1.1), judged with the machine's limits.
        r = check_machine_knittability(in.is_map ? in.map : stitch_mesh_to_map(in.mesh), *prof);
      }
      if (o->json) {
        nlohmann::json j = to_json(r);
        j["machine"] = prof ? prof->name : "none";
        std::printf("%s\n", j.dump(2).c_str());
      } else {
        std::printf("%s: %s", o->input.c_str(), r.text().c_str());
        if (prof) std::printf("  (checked for machine '%s'; --machine none checks the seed's rules only)\n", prof->name.c_str());
      }
      return r.ok() ? 0 : 1;
    };
  });
}

}  // namespace knitforge::cli
