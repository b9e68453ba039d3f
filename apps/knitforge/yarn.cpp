// knitforge yarn: stitch mesh (or map) -> yarn model polylines (seed §1.3.3).
#include <fmt/core.h>

#include "cli_common.h"
#include "knitforge/convert/map_to_stitch_mesh.h"
#include "knitforge/convert/stitch_mesh_to_yarn.h"
#include "knitforge/io/polyline_obj.h"

namespace knitforge::cli {

void add_yarn_command(CLI::App& app, Action& action) {
  auto* cmd = app.add_subcommand(
      "yarn", "Stitch mesh (.ply) or knitting map (.csv, relaxed first) -> yarn polylines (.obj)");
  struct Opts {
    std::string input, output, stitch = "3.5x2.8";
    YarnOptions yarn;
  };
  auto o = std::make_shared<Opts>();
  cmd->add_option("input", o->input, "Stitch mesh (.ply) or knitting map (.csv)")->required();
  cmd->add_option("-o,--output", o->output, "Yarn polylines (.obj)")->required();
  add_stitch_option(*cmd, o->stitch);
  cmd->add_option("--radius", o->yarn.yarn_radius, "Yarn radius in mm (0 = 0.12 x stitch width)")
      ->check(non_negative_number());
  cmd->callback([=, &action] {
    action = [=]() -> int {
      const KnitParams params = parse_stitch_size(o->stitch);
      check_output_file("-o", o->output, {".obj"}, {o->input});
      const StitchInput in = load_stitch_input(o->input);
      const StitchMesh mesh = in.is_map ? map_to_stitch_mesh(in.map, params) : in.mesh;
      const YarnModel yarn = stitch_mesh_to_yarn(mesh, params, o->yarn);
      write_yarn_obj(o->output, yarn);
      size_t points = 0;
      for (const auto& y : yarn.yarns) points += y.points.size();
      note(fmt::format("{} yarn(s), {} polyline vertices for {} stitches -> {}", yarn.yarns.size(), points,
                       mesh.num_stitches(), o->output));
      return 0;
    };
  });
}

}  // namespace knitforge::cli
