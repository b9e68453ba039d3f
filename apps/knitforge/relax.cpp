// knitforge relax: knitting map -> relaxed 3D stitch mesh (seed §1.3.2).
#include <fmt/core.h>

#include "cli_common.h"
#include "knitforge/convert/map_to_stitch_mesh.h"
#include "knitforge/io/stitch_mesh_ply.h"
#include "knitforge/util/timer.h"

namespace knitforge::cli {

void add_relax_command(CLI::App& app, Action& action) {
  auto* cmd = app.add_subcommand(
      "relax", "Knitting map -> stitch mesh with its relaxed 3D shape (Shape-Up, seed 1.3.2)");
  struct Opts {
    std::string input, output, stitch = "3.5x2.8";
    RelaxOptions relax;
    double max_stitches = kDefaultMaxStitches;
    bool ascii = false;
  };
  auto o = std::make_shared<Opts>();
  cmd->add_option("map", o->input, "Knitting map (.csv)")->required();
  cmd->add_option("-o,--output", o->output, "Stitch mesh (.ply)")->required();
  add_stitch_option(*cmd, o->stitch);
  cmd->add_option("--iterations", o->relax.max_iterations, "Maximum Shape-Up iterations (at most 100000)")
      ->check(number_in(0, 100000));
  add_max_stitches_option(*cmd, o->max_stitches);
  cmd->add_option("--warm-up", o->relax.warm_up,
                  "z warm-up amplitude, fraction of the map's diagonal (0 = off)")
      ->check(non_negative_number());
  cmd->add_flag("--ascii", o->ascii, "Write an ASCII PLY instead of binary");
  cmd->callback([=, &action] {
    action = [=]() -> int {
      const KnitParams params = parse_stitch_size(o->stitch);
      check_output_file("-o", o->output, {".ply"}, {o->input});
      const StitchInput in = load_stitch_input(o->input);
      if (!in.is_map) throw InvalidInput(o->input + ": relax takes a knitting map (.csv)");
      check_work({fmt::format("relaxing {}", o->input), static_cast<double>(in.map.num_stitches()), "stitches",
                  o->max_stitches, 0.0, "raise the limit with --max-stitches"});
      Timer t;
      const StitchMesh topo = map_to_stitch_mesh_topology(in.map, params);
      const RelaxResult r = relax_stitch_mesh(topo, params, o->relax);
      StitchMeshPlyOptions w;
      w.ascii = o->ascii;
      write_stitch_mesh_ply(o->output, r.mesh, w);
      note(fmt::format("{} stitches, {} vertices; Shape-Up {} iterations ({}), energy {:.4g} mm^4, {:.2f} s -> {}",
                       r.mesh.num_stitches(), r.mesh.num_vertices(), r.iterations,
                       r.converged ? "converged" : "iteration limit", r.energy.empty() ? 0.0 : r.energy.back(),
                       t.seconds(), o->output));
      return 0;
    };
  });
}

}  // namespace knitforge::cli
