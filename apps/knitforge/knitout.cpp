// knitforge knitout: knitting map (.csv) or stitch mesh (.ply) -> knitout
// program (.k) for a named machine profile.
#include <numeric>

#include <fmt/core.h>

#include "cli_common.h"
#include "knitforge/convert/stitch_mesh_to_map.h"
#include "knitforge/machine/knitout_writer.h"
#include "knitforge/machine/machine_profile.h"
#include "knitforge/util/atomic_file.h"

namespace knitforge::cli {

void add_knitout_command(CLI::App& app, Action& action) {
  auto* cmd = app.add_subcommand(
      "knitout", "Knitting map (.csv) or stitch mesh (.ply) -> knitout program (.k) for a machine");
  struct Opts {
    std::string input, output, machine = "shima-swg091n2", bind_off = "chain", carrier, waste_carrier,
                                draw_carrier, position = "Center";
    double gauge = 0;
    int waste_rows = -1, bind_off_waste_rows = 8, tail_rows = 4;
    bool open_turns = false;
    int stitch_number = -1, xfer_stitch_number = -1, speed_number = -1;
  };
  auto o = std::make_shared<Opts>();
  std::string names;
  for (const auto& n : machine_profile_names()) {
    if (machine_profile(n).beds == 2) names += (names.empty() ? "" : ", ") + n;
  }
  cmd->add_option("input", o->input, "Knitting map (.csv) or stitch mesh (.ply)")->required();
  cmd->add_option("-o,--output", o->output, "Output knitout file (.k)")->required();
  cmd->add_option("--machine", o->machine, "Machine profile: " + names)->capture_default_str();
  cmd->add_option("--gauge", o->gauge, "Value of the ;;Gauge: header (default: the profile's)")
      ->check(non_negative_number());
  cmd->add_option("--carrier", o->carrier, "Main yarn carrier (default: the profile's first)");
  cmd->add_option("--waste-carrier", o->waste_carrier, "Waste yarn carrier (default: second)");
  cmd->add_option("--draw-carrier", o->draw_carrier, "Draw-thread carrier (default: third)");
  cmd->add_option("--waste-rows", o->waste_rows,
                  "Courses of waste yarn before the fabric, followed by a draw thread (0: none; at most 1000; "
                  "default: the machine's, e.g. 70 on the Kniterate, 16 on the Shima, 0 on generic)")
      ->check(number_in(0, 1000));
  cmd->add_option("--bind-off", o->bind_off, "chain (transfers + knitted tail) or waste (live loops on waste yarn)")
      ->capture_default_str();
  cmd->add_option("--bind-off-waste-rows", o->bind_off_waste_rows, "Waste courses for --bind-off waste (at most 1000)")
      ->capture_default_str()
      ->check(number_in(0, 1000));
  cmd->add_option("--tail-rows", o->tail_rows, "Tail courses after a chain bind-off (at most 1000)")
      ->capture_default_str()
      ->check(number_in(0, 1000));
  cmd->add_flag("--open-turns", o->open_turns, "Do not tuck on the held needle at short-row turns");
  cmd->add_option("--position", o->position, "Value of ;;Position: (Left, Center, Right, Keep)")
      ->capture_default_str();
  cmd->add_option("--stitch-number", o->stitch_number,
                  "x-stitch-number of the fabric courses (a stitch-table entry; Kniterate 0..9)")
      ->check(non_negative_number());
  cmd->add_option("--xfer-stitch-number", o->xfer_stitch_number, "x-xfer-stitch-number of the fabric (Kniterate)")
      ->check(non_negative_number());
  cmd->add_option("--speed-number", o->speed_number, "x-speed-number of the fabric courses")
      ->check(non_negative_number());
  cmd->callback([=, &action] {
    action = [=]() -> int {
      check_output_file("-o", o->output, {".k"}, {o->input});
      const MachineProfile& prof = machine_profile(o->machine);
      KnitoutOptions ko;
      ko.carrier = o->carrier;
      ko.waste_carrier = o->waste_carrier;
      ko.draw_carrier = o->draw_carrier;
      ko.waste_rows = o->waste_rows;
      if (o->bind_off == "chain") ko.bind_off = BindOff::Chain;
      else if (o->bind_off == "waste") ko.bind_off = BindOff::Waste;
      else throw InvalidInput(fmt::format("--bind-off '{}': expected chain or waste", o->bind_off));
      ko.bind_off_waste_rows = o->bind_off_waste_rows;
      ko.tail_rows = o->tail_rows;
      ko.close_turns = !o->open_turns;
      ko.gauge = o->gauge;
      ko.position = o->position;
      if (o->stitch_number >= 0) ko.body.stitch_number = std::to_string(o->stitch_number);
      if (o->xfer_stitch_number >= 0) ko.body.xfer_stitch_number = std::to_string(o->xfer_stitch_number);
      if (o->speed_number >= 0) ko.body.speed_number = o->speed_number;
      const StitchInput in = load_stitch_input(o->input);
      const KnittingMap map = in.is_map ? in.map : stitch_mesh_to_map(in.mesh);
      const KnitoutProgram prog = write_knitout(map, prof, ko);
      write_file_atomically(o->output, [&](std::ostream& os) { os << prog.text; }, true);
      for (const auto& w : prog.warnings) note("warning: " + w);
      const KnitoutStats& s = prog.stats;
      note(fmt::format(
          "{}: {} courses, {} stitches, {} increases, {} decreases ({} bound off at the edge), {} shaping "
          "transfers ({} in all), {} racks, {} short-row turns ({} closed), {} waste courses, needles {} on {}",
          o->output, s.courses, s.map_knits + s.map_tucks, s.increases, s.decreases, s.edge_chained,
          s.shaping_xfers, s.xfers, s.racks, s.inside_turns, s.closed_turns, s.waste_rows,
          map.tubular() ? fmt::format("f{0}..f{1} and b{0}..b{1}, every other needle (a tube in the round)",
                                      s.first_needle, s.last_needle)
                        : fmt::format("f{}..f{}", s.first_needle, s.last_needle),
          prof.name));
      if (prog.simulation) {
        const SimulationStats& ss = prog.simulation->stats;
        note(fmt::format("virtual machine: VALID, knit graph MATCHES the map; estimated knitting time {:.1f} min, "
                         "yarn {:.2f} m (estimate)",
                         ss.time_s / 60.0, std::accumulate(ss.yarn_mm.begin(), ss.yarn_mm.end(), 0.0) / 1000.0));
      }
      return 0;
    };
  });
}

}  // namespace knitforge::cli
