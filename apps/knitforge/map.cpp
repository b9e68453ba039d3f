// knitforge map: stitch mesh -> knitting map (seed Alg. 1.1), or a map redrawn.
#include <fmt/core.h>

#include "cli_common.h"
#include "knitforge/convert/stitch_mesh_to_map.h"

namespace knitforge::cli {

void add_map_command(CLI::App& app, Action& action) {
  auto* cmd = app.add_subcommand(
      "map", "Stitch mesh (.ply) -> knitting map (.csv/.png/.svg); a .csv map is redrawn");
  struct Opts {
    std::string input;
    std::vector<std::string> outputs;
  };
  auto o = std::make_shared<Opts>();
  cmd->add_option("input", o->input, "Stitch mesh (.ply) or knitting map (.csv)")->required();
  cmd->add_option("-o,--output", o->outputs, "Output file(s): .csv, .png, .svg (repeatable)")->required();
  cmd->callback([=, &action] {
    action = [=]() -> int {
      for (const auto& out : o->outputs) check_output_file("-o", out, {".csv", ".png", ".svg"}, {o->input});
      const StitchInput in = load_stitch_input(o->input);
      const KnittingMap map = in.is_map ? in.map : stitch_mesh_to_map(in.mesh);
      for (const auto& out : o->outputs) write_map_by_extension(out, map);
      note(fmt::format("{} x {} map, {} stitches", map.rows, map.cols, map.num_stitches()));
      return 0;
    };
  });
}

}  // namespace knitforge::cli
