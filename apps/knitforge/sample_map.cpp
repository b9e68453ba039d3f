// knitforge sample-map: writes one of the built-in knitting maps.
#include <fmt/core.h>

#include "cli_common.h"
#include "knitforge/convert/random_knitting_map.h"
#include "knitforge/convert/sample_knitting_map.h"

namespace knitforge::cli {

void add_sample_map_command(CLI::App& app, Action& action) {
  auto* cmd = app.add_subcommand("sample-map", "Write a built-in knitting map (.csv, .png, .svg)");
  struct Opts {
    std::string name;
    std::vector<std::string> outputs;
    RandomMapOptions random;
    CupMapOptions cup;
    TubeMapOptions tube;
    bool list = false;
  };
  auto o = std::make_shared<Opts>();
  std::string names;
  for (const auto& n : sample_map_names()) names += (names.empty() ? "" : ", ") + n;
  cmd->add_option("name", o->name, "Map name: " + names);
  cmd->add_option("-o,--output", o->outputs, "Output file(s): .csv, .png, .svg (repeatable)");
  cmd->add_flag("--list", o->list, "List the map names and exit");
  auto* rows = cmd->add_option("--rows", o->random.rows, "random, tube, tapered-tube: number of map rows");
  auto* cols = cmd->add_option("--cols", o->random.cols, "random: number of map columns");
  auto* ends = cmd->add_option("--short-row-ends", o->random.short_row_ends,
                               "random: number of short-row end stitches (even)");
  auto* scols = cmd->add_option("--short-columns", o->random.short_columns, "random: number of short columns");
  auto* seed = cmd->add_option("--seed", o->random.seed, "random: random seed");
  auto* bshape = cmd->add_flag("--boundary-shaping", o->random.boundary_shaping,
                               "random: widen at the bottom and narrow at the top");
  auto* wales = cmd->add_option("--wales", o->cup.wales, "cup: width in stitches");
  auto* turns = cmd->add_option("--turns", o->cup.turns, "cup: short-row turns per side in each wedge");
  auto* round = cmd->add_option("--round", o->tube.round, "tube, tapered-tube: stitches round the tube (even)");
  auto* drounds = cmd->add_option("--decrease-rounds", o->tube.decrease_rounds,
                                  "tube, tapered-tube: rounds with 4 decreases each (one per quarter)");
  auto* every = cmd->add_option("--every", o->tube.every, "tube, tapered-tube: rounds between decrease rounds");
  cmd->callback([=, &action] {
    action = [=]() -> int {
      if (o->list) {
        for (const auto& n : sample_map_names()) std::printf("%s\n", n.c_str());
        return 0;
      }
      if (o->name.empty() || o->outputs.empty()) {
        throw UsageError("sample-map: give a map name and at least one -o FILE (see --list)");
      }
      for (const auto& out : o->outputs) check_output_file("-o", out, {".csv", ".png", ".svg"});
      const bool is_tube = o->name == "tube" || o->name == "tapered-tube";
      const bool random_opts = (*rows && !is_tube) || *cols || *ends || *scols || *seed || *bshape;
      const bool cup_opts = *wales || *turns;
      const bool tube_opts = (*rows && is_tube) || *round || *drounds || *every;
      if (random_opts && o->name != "random") {
        throw InvalidInput("--cols/--short-row-ends/--short-columns/--seed apply to 'random' only, --rows to "
                           "'random' and the tubes");
      }
      if ((*round || *drounds || *every) && !is_tube)
        throw InvalidInput("--round/--decrease-rounds/--every apply to 'tube' and 'tapered-tube' only");
      if (cup_opts && o->name != "cup") throw InvalidInput("--wales/--turns apply to 'cup' only");
      KnittingMap map;
      if (o->name == "random" && random_opts) {
        check_work({"sample-map random", static_cast<double>(o->random.rows) * o->random.cols, "cells", kDefaultMaxStitches,
                    0.0, "use fewer --rows / --cols"});
        map = random_knitting_map(o->random);
      } else if (o->name == "cup" && cup_opts) {
        map = cup_knitting_map(o->cup);
      } else if (is_tube && tube_opts) {
        TubeMapOptions t;
        if (o->name == "tapered-tube") t = {32, 24, 4, 4};
        if (*rows) t.rows = o->random.rows;
        if (*round) t.round = o->tube.round;
        if (*drounds) t.decrease_rounds = o->tube.decrease_rounds;
        if (*every) t.every = o->tube.every;
        check_work({"sample-map tube", static_cast<double>(t.rows) * t.round, "cells", kDefaultMaxStitches, 0.0,
                    "use fewer --rows / a smaller --round"});
        map = tube_knitting_map(t);
      } else {
        map = sample_knitting_map(o->name);
      }
      for (const auto& out : o->outputs) write_map_by_extension(out, map);
      note(fmt::format("{}: {} x {} {}map, {} stitches", o->name, map.rows, map.cols, map.tubular() ? "tubular " : "",
                       map.num_stitches()));
      return 0;
    };
  });
}

}  // namespace knitforge::cli
