// knitforge-ddr: the single-image body reconstruction (seed §5.4), the only
// program that loads LibTorch. `knitforge body ddr-train | ddr-evaluate |
// reconstruct` hand their command line to it; it takes the same one.
#include <CLI/CLI.hpp>

#include "body_ddr_options.h"
#include "ddr_commands.h"

int main(int argc, char** argv) {
  using namespace knitforge;
  CLI::App app{"knitforge-ddr: the LibTorch commands of knitforge (run as 'knitforge body ddr-train | ddr-evaluate "
               "| reconstruct')"};
  app.require_subcommand(1);
  cli::set_command_line(argc, argv);
  cli::Action action;
  auto* body = app.add_subcommand("body", "Bodies for individuals (seed ch. 5): single-image reconstruction");
  body->require_subcommand(1);
  cli::add_body_ddr_commands(*body, action, {cli::run_ddr_train, cli::run_ddr_evaluate, cli::run_reconstruct});
  return cli::run_command_line(app, action, argc, argv);
}
