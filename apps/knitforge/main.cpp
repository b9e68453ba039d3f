// knitforge command-line program: parses options, calls the library, writes
// files. Exit codes: 0 success, 1 input error or failed check, 2 usage error.
#include <CLI/CLI.hpp>
#include "cli_common.h"

int main(int argc, char** argv) {
  using namespace knitforge;
  CLI::App app{
      "knitforge: computational design of 3D and 4D knitwear.\n"
      "All lengths are millimetres. Run 'knitforge <command> --help' for a command's options."};
  app.set_version_flag("--version", "knitforge 0.1.0");
  app.require_subcommand(1);
  app.fallthrough(false);

  cli::set_command_line(argc, argv);
  cli::Action action;
  cli::add_shape_command(app, action);
  cli::add_sample_map_command(app, action);
  cli::add_check_command(app, action);
  cli::add_relax_command(app, action);
  cli::add_map_command(app, action);
  cli::add_yarn_command(app, action);
  cli::add_simulate_command(app, action);
  cli::add_knitout_command(app, action);
  cli::add_instructions_command(app, action);
  cli::add_flatten_command(app, action);
  cli::add_render_command(app, action);
  cli::add_shortrow_command(app, action);
  cli::add_shortcolumn_command(app, action);
  cli::add_report_command(app, action);
  cli::add_support_command(app, action);
  cli::add_close_command(app, action);
  cli::add_thicken_command(app, action);
  cli::add_machines_command(app, action);
  cli::add_predict_command(app, action);
  cli::add_body_command(app, action);
  cli::add_cloth_command(app, action);

  return cli::run_command_line(app, action, argc, argv);
}
