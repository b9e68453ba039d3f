// knitforge command-line program: parses options, calls the library, writes files.
#include <cstdio>
#include <exception>

#include <CLI/CLI.hpp>

#include "knitforge/util/errors.h"

int main(int argc, char** argv) {
  CLI::App app{"knitforge: computational design of 3D and 4D knitwear"};
  app.set_version_flag("--version", "knitforge 0.1.0");
  app.require_subcommand(1);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e) == 0 ? 0 : 2;
  }
  return 0;
}
