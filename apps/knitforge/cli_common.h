#pragma once
// Helpers shared by the subcommands: option parsing of physical quantities,
// loading inputs by extension, writing outputs by extension, messages.
// No algorithms here: everything of substance is in the library.

#include <functional>
#include <string>
#include <utility>
#include <vector>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "knitforge/core/knit_params.h"
#include "knitforge/core/knitting_map.h"
#include "knitforge/core/stitch_mesh.h"
#include "knitforge/evaluate/evaluate_stitch_mesh.h"
#include "knitforge/evaluate/scalar_stats.h"
#include "knitforge/geometry/cut_to_disk.h"
#include "knitforge/geometry/geodesic_source.h"
#include "knitforge/geometry/tri_mesh.h"
#include "knitforge/sim/newton_solve.h"
#include "knitforge/util/errors.h"
#include "knitforge/util/work_limit.h"

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
void add_shortcolumn_command(CLI::App& app, Action& action);
void add_report_command(CLI::App& app, Action& action);
void add_support_command(CLI::App& app, Action& action);
void add_close_command(CLI::App& app, Action& action);
void add_thicken_command(CLI::App& app, Action& action);
void add_machines_command(CLI::App& app, Action& action);
void add_predict_command(CLI::App& app, Action& action);
void add_body_command(CLI::App& app, Action& action);
/// body render-depth / calibrate / fuse (body_depth.cpp), on the body command.
void add_body_depth_commands(CLI::App& body, Action& action);
/// body render-photo (body_photo.cpp), on the body command.
void add_body_photo_command(CLI::App& body, Action& action);
void add_cloth_command(CLI::App& app, Action& action);

/// Remembers the command line (main() calls it first): run_sibling_program()
/// hands it on.
void set_command_line(int argc, char** argv);

/// Parses the command line with `app` and runs the chosen `action`: exit 0
/// on success, 1 for an input error or failed check, 2 for a usage error,
/// each error one line "knitforge: ..." on stderr.
int run_command_line(CLI::App& app, const Action& action, int argc, char** argv);

/// Replaces this process by the program `name` in knitforge's own
/// directory, with the same command line (how `knitforge body ddr-train |
/// ddr-evaluate | reconstruct` run knitforge-ddr, the only program that
/// loads LibTorch). Returns only by throwing.
/// \throw IOError when the program is missing or cannot be run.
[[noreturn]] void run_sibling_program(const std::string& name);

/// A usage error found after parsing (a missing, empty or malformed
/// argument): the program exits 2, like CLI11's own parse errors.
class UsageError : public InvalidInput {
 public:
  using InvalidInput::InvalidInput;
};

/// Option validators that accept only finite numbers (no nan, inf) and say
/// what is wrong with the value as given ("--edge 0: must be a positive
/// number"; never the representable range).
CLI::Validator positive_number();
CLI::Validator non_negative_number();
CLI::Validator number_in(double lo, double hi);

/// Checks an output file before any work: a non-empty name (UsageError
/// otherwise) with one of `extensions` (".csv"; empty: any), not a
/// directory, in an existing writable directory, and not the same file as
/// any of `inputs`.
/// \throw UsageError / InvalidInput naming `option` and the path.
void check_output_file(const std::string& option, const std::string& path,
                       const std::vector<std::string>& extensions, const std::vector<std::string>& inputs = {});

/// Checks that an input file exists and is a file (not a directory).
/// \throw IOError naming the path.
void check_input_file(const std::string& path);

/// Checks an output directory before any work: a non-empty name, an
/// existing directory or one that can be created (its nearest existing
/// ancestor is a writable directory), and not one of `inputs`.
void check_output_dir(const std::string& option, const std::string& path,
                      const std::vector<std::string>& inputs = {});

/// Adds "--max-stitches N" (default kDefaultMaxStitches) to cmd.
CLI::Option* add_max_stitches_option(CLI::App& cmd, double& value);

/// Refuses, before any work, a surface whose stitch count area / (w x h)
/// exceeds max_stitches (check_work(); the message names the surface, its
/// area and size, and says how to override).
void check_surface_stitches(const TriMesh& surface, const std::string& description, const KnitParams& params,
                            double max_stitches, double bytes_per_stitch);

/// Where a simulator solve's time went, as report JSON:
/// {"evaluate_s", "factor_s", "max_step_s", "line_search_s"}.
nlohmann::json newton_timings_json(const NewtonTimings& t);

/// Where a simulator solve's iterations went, as report JSON: one array per
/// quantity, one entry per Newton iteration ({"energy_uj", "max_force_mn",
/// "factorizations", "shift", "step", "energy_trials"}; see NewtonIterate).
nlohmann::json newton_history_json(const std::vector<NewtonIterate>& history);

/// Parses "WxH" (millimetres, e.g. "3.5x2.8") into KnitParams.
/// \throw InvalidInput naming the option when malformed or not positive.
KnitParams parse_stitch_size(const std::string& text);

/// A JSON file (`what` names it in the error).
/// \throw IOError when it cannot be read; InvalidInput when it is not JSON.
nlohmann::json read_json_file(const std::string& path, const std::string& what);

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

/// The built-in shape names, comma-separated (for help texts).
std::string shape_name_list();

/// Reads a triangle mesh and scales it to millimetres.
TriMesh load_surface(const std::string& path, const std::string& units);

/// A design command's input surface: a mesh file (scaled to mm by `units`)
/// or, when no such file exists, a built-in shape meshed at `edge` mm.
/// `description` receives "built-in NAME" or the path; `builtin` whether it
/// was a shape. \throw InvalidInput naming the input and the shape names.
TriMesh load_surface_or_shape(const std::string& input, const std::string& units, double edge,
                              std::string& description, bool* builtin = nullptr);

/// The input of a design command: load_surface_or_shape(), then
/// prepare_surface() (unused vertices dropped, split vertices welded; a
/// note says what changed). `vertex_map` (optional) receives, for every
/// vertex of the file, its index in the returned mesh or -1.
TriMesh load_design_surface(const std::string& input, const std::string& units, double edge,
                            std::string& description, bool* builtin = nullptr,
                            std::vector<int>* vertex_map = nullptr);

/// The plane x = centre of the bounding box as a source (the default source
/// of `shortrow`, and where `flatten` prefers its seams: garments are
/// usually modelled symmetric about x = 0).
GeodesicSource symmetry_plane_source(const TriMesh& mesh);

/// The polylines of a --cut file (OBJ `l` elements), scaled to mm.
/// \throw InvalidInput when the file has no polyline.
std::vector<std::vector<Vec3>> read_cuts(const std::string& path, double scale);

/// Adds the standard "--cut FILE.obj" option of the design commands.
CLI::Option* add_cut_option(CLI::App& cmd, std::string& value);

/// Adds the standard "--stitch WxH" option.
CLI::Option* add_stitch_option(CLI::App& cmd, std::string& value);

/// Writes a design command's report (indented JSON) to `path` atomically
/// and, when `print` (--json), also to stdout.
void write_report_json(const std::string& path, const nlohmann::json& report, bool print);

/// The seams of a design for report.json: count, total length (mm) and one
/// entry per seam (kind, on_source, length_mm, end points).
nlohmann::json seams_json(const std::vector<Seam>& seams);

/// The note a design command gives when it cut the surface into a disk
/// (nothing when there are no seams); `extra` ends the line.
void note_seams(const std::vector<Seam>& seams, int boundary_loops, int genus, const std::string& extra = "");

/// Writes OUTDIR/seams.obj (one polyline per seam) when there are seams.
void write_seams_obj(const std::string& outdir, const std::vector<Seam>& seams);

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

/// Per-vertex values as colours on the surface (viridis over [lo, hi]).
void write_vertex_coloured(const std::string& path, const TriMesh& surface, const std::vector<double>& value, double lo,
                           double hi, bool ascii);

/// |div| per vertex of a divergence metric and its 99th percentile (the
/// colour scale of divergence.ply: a few spikes at cone points do not wash
/// out the rest).
std::pair<std::vector<double>, double> divergence_magnitude(const std::vector<double>& divergence);

/// The stitch mesh as triangles with one colour per stitch (viridis of
/// `value` over [0, hi]), for viewing (distortion.ply, shape_error.ply).
void write_coloured_stitches(const std::string& path, const StitchMesh& mesh, const std::vector<double>& value,
                             double hi);

/// The evaluation outputs of a design command in `dir`: relaxed.ply,
/// shape_error.ply, distortion.ply; and the "evaluation" section of
/// report.json.
void write_evaluation_files(const std::string& dir, const StitchMesh& designed, const StitchMeshEvaluation& ev,
                            bool ascii);
nlohmann::json evaluation_json(const StitchMeshEvaluation& ev);

/// The end of a design command whose map passed its own checks: notes
/// whether it is knittable on `machine` too (design_machine_end()'s
/// machine_ok) and returns the exit code, 0 or 1.
int machine_exit_code(bool machine_ok, const std::string& machine);

/// The design routes' converged predicted shape (docs/evaluate.md): after
/// the design, the free static equilibrium of the stitch mesh by the fabric
/// simulator (as `knitforge predict DESIGN_DIR`, same solver options and the
/// same shape-error measure: rigid fit to the design, then ICP onto the
/// target). Runs by default when the design has at most
/// kDesignPredictMaxStitches stitches (a converged free prediction costs
/// ~15 ms CPU per stitch at 3.7k stitches, docs/benchmarks.md); --predict
/// forces it, --no-predict skips it.
constexpr int kDesignPredictMaxStitches = 1500;
struct DesignPredictOptions {
  bool force = false, skip = false;
  int max_iterations = 500;
};
/// Adds --predict, --no-predict and --predict-max-iterations to cmd.
void add_design_predict_options(CLI::App& cmd, DesignPredictOptions& options);
/// The "prediction" section of report.json (null when it did not run, with
/// a note saying why); writes OUTDIR/predicted.ply (aligned to the target)
/// when it converged, and removes one of an earlier run otherwise (the report
/// page draws predicted.ply). An unconverged prediction reports converged =
/// false and no shape error. `summary` receives the CLI line.
nlohmann::json design_prediction(const DesignPredictOptions& options, const std::string& outdir,
                                 const StitchMesh& designed, const KnitParams& params, const TriMesh& target,
                                 bool ascii, std::string& summary);
/// A design route's shape results in report.json, the same for every route:
/// "evaluation" (evaluation_json() of the route's Shape-Up evaluation, when
/// it ran, with "predictor" saying it is a preview, not a converged shape) and
/// "prediction" (design_prediction() of `designed` against `target`, the
/// surface the route designed for; --no-evaluate skips it unless --predict).
/// Returns the lines to note at the end of the run: the preview's shape
/// error, then the prediction's (either may be absent).
std::vector<std::string> report_design_shape(nlohmann::json& report, const DesignPredictOptions& options,
                                             bool no_evaluate, const std::string& outdir,
                                             const StitchMesh& designed, const KnitParams& params,
                                             const TriMesh& target, const StitchMeshEvaluation* evaluation,
                                             bool ascii);

/// One line on stderr: "knitforge: <message>" (progress and notes).
void note(const std::string& message);

}  // namespace knitforge::cli
