// knitforge instructions: knitting map (.csv) or stitch mesh (.ply) ->
// row-by-row instructions for a manual machine, as text (.txt) or a
// printable HTML page (.html).
#include <fmt/core.h>

#include "cli_common.h"
#include "knitforge/convert/stitch_mesh_to_map.h"
#include "knitforge/machine/hand_instructions.h"
#include "knitforge/machine/machine_profile.h"
#include "knitforge/util/atomic_file.h"

namespace knitforge::cli {

void add_instructions_command(CLI::App& app, Action& action) {
  auto* cmd = app.add_subcommand(
      "instructions", "Knitting map (.csv) or stitch mesh (.ply) -> hand-machine instructions (.txt/.html)");
  struct Opts {
    std::string input, output, machine = "brother-kh868";
    bool no_wrap = false;
  };
  auto o = std::make_shared<Opts>();
  cmd->add_option("input", o->input, "Knitting map (.csv) or stitch mesh (.ply)")->required();
  cmd->add_option("-o,--output", o->output, "Output file: .txt (text) or .html (printable page)")->required();
  cmd->add_option("--machine", o->machine, "Machine profile (needle numbering)")->capture_default_str();
  cmd->add_flag("--no-wrap", o->no_wrap, "Do not wrap the held needle at short-row turns");
  cmd->callback([=, &action] {
    action = [=]() -> int {
      check_output_file("-o", o->output, {".txt", ".html", ".htm"}, {o->input});
      const std::string ext = extension(o->output);
      const MachineProfile& prof = machine_profile(o->machine);
      const StitchInput in = load_stitch_input(o->input);
      const KnittingMap map = in.is_map ? in.map : stitch_mesh_to_map(in.mesh);
      HandInstructionOptions ho;
      ho.wrap_turns = !o->no_wrap;
      const HandInstructions h = hand_instructions(map, prof, ho);
      const std::string text = ext == ".txt" ? hand_instructions_text(h) : hand_instructions_html(h);
      write_file_atomically(o->output, [&](std::ostream& os) { os << text; }, true);
      note(fmt::format("{}: {} rows for the {}, {} hand transfers, {} hold/return moves, {} wraps",
                       o->output, h.rows.size(), h.machine, h.hand_transfers, h.held_needle_changes,
                       h.wraps));
      return 0;
    };
  });
}

}  // namespace knitforge::cli
