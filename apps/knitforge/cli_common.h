#pragma once
// Helpers shared by the subcommands: option parsing of physical quantities,
// loading inputs by extension, writing outputs by extension, messages.
// No algorithms here: everything of substance is in the library.

#include <functional>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "knitforge/core/knit_params.h"
#include "knitforge/core/knitting_map.h"
#include "knitforge/core/stitch_mesh.h"
#include "knitforge/evaluate/scalar_stats.h"
#include "knitforge/geometry/tri_mesh.h"
#include "knitforge/util/errors.h"

namespace knitforge::cli {

/// What a subcommand runs after parsing; returns the process exit code.
using Action = std::function<int()>;

/// Registers each subcommand on `app`; `action` receives the runner of the
/// subcommand the user chose.
void add_shape_command(CLI::App& app, Action& action);
void add_sample_map_command(CLI::App& app, Action& action);
void add_check_command(CLI::App& app, Action& action);
void add_relax_command(CLI::App& app, Action& action);
void add_map_command(CLI::App& app, Action& action);
void add_yarn_command(CLI::App& app, Action& action);
void add_simulate_command(CLI::App& app, Action& action);
void add_knitout_command(CLI::App& app, Action& action);
void add_instructions_command(CLI::App& app, Action& action);
void add_flatten_command(CLI::App& app, Action& action);
void add_render_command(CLI::App& app, Action& action);
void add_shortrow_command(CLI::App& app, Action& action);
void add_report_command(CLI::App& app, Action& action);
void add_support_command(CLI::App& app, Action& action);
void add_close_command(CLI::App& app, Action& action);
void add_thicken_command(CLI::App& app, Action& action);
void add_machines_command(CLI::App& app, Action& action);
void add_body_command(CLI::App& app, Action& action);

/// Parses "WxH" (millimetres, e.g. "3.5x2.8") into KnitParams.
/// \throw InvalidInput naming the option when malformed or not positive.
KnitParams parse_stitch_size(const std::string& text);

/// Scale factor from a unit name ("mm", "cm", "m") to millimetres.
double unit_scale(const std::string& units);

/// Lower-case extension of a path including the dot (".csv"), "" if none.
std::string extension(const std::string& path);

/// A knitting map or a stitch mesh, loaded from a .csv (map) or a .ply
/// (stitch mesh) file.
struct StitchInput {
  bool is_map = false;
  KnittingMap map;
  StitchMesh mesh;
};
StitchInput load_stitch_input(const std::string& path);

/// Writes a knitting map in the format given by the extension of `path`
/// (.csv, .png, .svg).
void write_map_by_extension(const std::string& path, const KnittingMap& map);

/// True when `path` is a PLY file whose faces carry the stitch properties
/// (a stitch mesh) rather than a plain triangle mesh.
bool is_stitch_mesh_ply(const std::string& path);

/// The whole content of a text file (`what` names it in the error).
/// \throw IOError when it cannot be read.
std::string read_text_file(const std::string& path, const std::string& what = "file");

/// Reads a triangle mesh and scales it to millimetres.
TriMesh load_surface(const std::string& path, const std::string& units);

/// A design command's input surface: a mesh file (scaled to mm by `units`)
/// or, when no such file exists, a built-in shape meshed at `edge` mm.
/// `description` receives "built-in NAME" or the path; `builtin` whether it
/// was a shape. \throw InvalidInput naming the input and the shape names.
TriMesh load_surface_or_shape(const std::string& input, const std::string& units, double edge,
                              std::string& description, bool* builtin = nullptr);

/// Adds the standard "--stitch WxH" option.
CLI::Option* add_stitch_option(CLI::App& cmd, std::string& value);

/// Writes a design command's report (indented JSON) to `path` atomically
/// and, when `print` (--json), also to stdout.
void write_report_json(const std::string& path, const nlohmann::json& report, bool print);

/// Statistics for a report: count, min, mean, rms, max, p50, p90, p99.
nlohmann::json scalar_stats_json(const ScalarStats& s);

/// The machine options of a design command (--machine, --no-knitout,
/// --waste-rows).
struct DesignMachineOptions {
  std::string machine = "shima-swg091n2";
  bool no_knitout = false;
  int waste_rows = -1;
};
void add_design_machine_options(CLI::App& cmd, DesignMachineOptions& options);

/// The machine end of a design command: for a knittable map, writes the
/// machine program (OUTDIR/knitout.k for a two-bed machine, verified by the
/// virtual machine; OUTDIR/instructions.html for a manual one) and returns
/// the "machine" section of report.json; `machine_ok` is false when the
/// machine cannot knit the map, and `machine_check` then holds the machine's
/// knittability report (the cells and the reason).
nlohmann::json design_machine_end(const DesignMachineOptions& options, const std::string& outdir,
                                  const KnittingMap& map, bool map_knittable, const StitchMesh* designed,
                                  bool& machine_ok, nlohmann::json& machine_check);

/// One line on stderr: "knitforge: <message>" (progress and notes).
void note(const std::string& message);

}  // namespace knitforge::cli
