// knitforge command-line program: parses options, calls the library, writes
// files. Exit codes: 0 success, 1 input error or failed check, 2 usage error.
#include <cstdio>
#include <exception>
#include <string>

#include <CLI/CLI.hpp>
#include <fmt/core.h>

#include "cli_common.h"
#include "knitforge/util/errors.h"

namespace {

// Every message is one line of printable text: line breaks become "; ",
// other control or non-ASCII bytes "?", and a message longer than 600
// characters is cut (the library quotes at most 80 characters of input;
// this is the last guard against echoing raw input).
std::string one_line(const std::string& message) {
  std::string out;
  for (size_t i = 0; i < message.size(); ++i) {
    const unsigned char c = static_cast<unsigned char>(message[i]);
    if (c == '\n') {
      if (i + 1 < message.size()) out += "; ";
    } else if (c == '\t') {
      out += ' ';
    } else {
      out += (c >= 0x20 && c < 0x7f) ? static_cast<char>(c) : '?';
    }
    if (out.size() >= 600) {
      out += fmt::format("... ({} more characters)", message.size() - i - 1);
      break;
    }
  }
  return out;
}

}  // namespace

int main(int argc, char** argv) {
  using namespace knitforge;
  CLI::App app{
      "knitforge: computational design of 3D and 4D knitwear.\n"
      "All lengths are millimetres. Run 'knitforge <command> --help' for a command's options."};
  app.set_version_flag("--version", "knitforge 0.1.0");
  app.require_subcommand(1);
  app.fallthrough(false);

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

  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    std::fprintf(stderr, "knitforge: usage error: %s\n", one_line(e.what()).c_str());
    std::fprintf(stderr, "Run 'knitforge --help' for the commands and their options.\n");
    return 2;
  }

  try {
    return action ? action() : 0;
  } catch (const cli::UsageError& e) {
    std::fprintf(stderr, "knitforge: usage error: %s\n", one_line(e.what()).c_str());
    std::fprintf(stderr, "Run 'knitforge --help' for the commands and their options.\n");
    return 2;
  } catch (const Error& e) {
    std::fprintf(stderr, "knitforge: error: %s\n", one_line(e.what()).c_str());
    return 1;
  } catch (const std::bad_alloc&) {
    std::fprintf(stderr, "knitforge: error: out of memory\n");
    return 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "knitforge: internal error: %s\n", one_line(e.what()).c_str());
    return 1;
  }
}
