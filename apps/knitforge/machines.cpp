// knitforge machines: the built-in machine profiles, their limits and the
// rules a knitout program is judged by on each (docs/machines.md).
#include <cstdio>

#include <fmt/core.h>

#include "cli_common.h"
#include "knitforge/machine/machine_profile.h"

namespace knitforge::cli {

void add_machines_command(CLI::App& app, Action& action) {
  auto* cmd = app.add_subcommand("machines",
                                 "List the machine profiles; --markdown: their limits, writer defaults and the level "
                                 "and source of every rule");
  struct Opts {
    bool markdown = false;
  };
  auto o = std::make_shared<Opts>();
  cmd->add_flag("--markdown", o->markdown, "Print the full reference as Markdown (as in docs/machines.md)");
  cmd->callback([=, &action] {
    action = [=]() -> int {
      if (o->markdown) {
        std::printf("%s", machines_reference_markdown().c_str());
        return 0;
      }
      for (const auto& n : machine_profile_names()) {
        const MachineProfile& p = machine_profile(n);
        std::printf("%-16s %s\n", p.name.c_str(), p.description.c_str());
      }
      std::printf("(knitforge simulate --rules --machine NAME prints the rules of one machine)\n");
      return 0;
    };
  });
}

}  // namespace knitforge::cli
