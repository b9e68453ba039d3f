// Parsing the command line and running the chosen command, with the exit
// codes and one-line messages every knitforge program shares.
#include <cstdio>
#include <exception>
#include <filesystem>
#include <string>
#include <vector>

#include <unistd.h>

#include <fmt/core.h>

#include "cli_common.h"
#include "knitforge/util/errors.h"

namespace knitforge::cli {

namespace {

std::vector<std::string>& arguments() {
  static std::vector<std::string> args;
  return args;
}

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

void set_command_line(int argc, char** argv) { arguments().assign(argv, argv + argc); }

[[noreturn]] void run_sibling_program(const std::string& name) {
  std::error_code ec;
  const std::filesystem::path self = std::filesystem::read_symlink("/proc/self/exe", ec);
  const std::filesystem::path program = (ec ? std::filesystem::path(".") : self.parent_path()) / name;
  if (!std::filesystem::exists(program))
    throw IOError(fmt::format("{} is missing (it should sit next to knitforge): build it with 'make build'",
                              program.string()));
  std::vector<std::string> args = arguments();
  if (args.empty()) args.push_back(name);
  args[0] = program.string();
  std::vector<char*> argv;
  for (std::string& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  std::fflush(stdout);
  std::fflush(stderr);
  execv(program.c_str(), argv.data());
  throw IOError(fmt::format("cannot run {}", program.string()));
}

int run_command_line(CLI::App& app, const Action& action, int argc, char** argv) {
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

}  // namespace knitforge::cli
