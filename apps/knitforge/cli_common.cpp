#include "cli_common.h"

#include <filesystem>

#include "knitforge/io/knittability_json.h"
#include "knitforge/machine/hand_instructions.h"
#include "knitforge/machine/knitout_writer.h"
#include "knitforge/machine/machine_knittability.h"
#include "knitforge/machine/machine_profile.h"
#include "knitforge/report/machine_report.h"
#include "knitforge/util/atomic_file.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <ostream>
#include <sstream>

#include <fmt/core.h>

#include "knitforge/evaluate/scalar_colours.h"
#include "knitforge/evaluate/stitch_distortion.h"
#include "knitforge/geometry/shapes.h"
#include "knitforge/io/io_detail.h"
#include "knitforge/io/knitting_map_csv.h"
#include "knitforge/io/knitting_map_image.h"
#include "knitforge/io/mesh_io.h"
#include "knitforge/io/ply_format.h"
#include "knitforge/io/stitch_mesh_ply.h"
#include "knitforge/util/atomic_file.h"
#include "knitforge/util/errors.h"

namespace knitforge::cli {

KnitParams parse_stitch_size(const std::string& text) {
  const auto x = text.find_first_of("xX");
  KnitParams p;
  bool ok = x != std::string::npos;
  if (ok) {
    try {
      size_t n1 = 0, n2 = 0;
      p.stitch_width = std::stod(text.substr(0, x), &n1);
      p.stitch_height = std::stod(text.substr(x + 1), &n2);
      ok = n1 == x && n2 == text.size() - x - 1;
    } catch (const std::exception&) {
      ok = false;
    }
  }
  if (!ok || !std::isfinite(p.stitch_width) || !std::isfinite(p.stitch_height) || p.stitch_width <= 0 ||
      p.stitch_height <= 0) {
    throw InvalidInput(fmt::format(
        "--stitch '{}': expected WIDTHxHEIGHT in millimetres with positive numbers, e.g. 3.5x2.8", text));
  }
  return p;
}

double unit_scale(const std::string& units) {
  if (units == "mm") return 1.0;
  if (units == "cm") return 10.0;
  if (units == "m") return 1000.0;
  throw InvalidInput(fmt::format("--units '{}': expected mm, cm or m", units));
}

std::string extension(const std::string& path) {
  const auto slash = path.find_last_of('/');
  const auto dot = path.find_last_of('.');
  if (dot == std::string::npos || (slash != std::string::npos && dot < slash)) return "";
  std::string e = path.substr(dot);
  std::transform(e.begin(), e.end(), e.begin(), [](unsigned char c) { return std::tolower(c); });
  return e;
}

StitchInput load_stitch_input(const std::string& path) {
  StitchInput in;
  const std::string ext = extension(path);
  if (ext == ".csv") {
    in.is_map = true;
    in.map = read_knitting_map_csv(path);
  } else if (ext == ".ply") {
    in.mesh = read_stitch_mesh_ply(path);
  } else {
    throw InvalidInput(fmt::format(
        "{}: expected a knitting map (.csv) or a stitch mesh (.ply with stitch properties)", path));
  }
  return in;
}

void write_map_by_extension(const std::string& path, const KnittingMap& map) {
  const std::string ext = extension(path);
  if (ext == ".csv") {
    write_knitting_map_csv(path, map);
  } else if (ext == ".png") {
    write_knitting_map_png(path, map);
  } else if (ext == ".svg") {
    write_knitting_map_svg(path, map);
  } else {
    throw InvalidInput(fmt::format("{}: a knitting map is written as .csv, .png or .svg", path));
  }
}

TriMesh load_surface(const std::string& path, const std::string& units) {
  const double s = unit_scale(units);
  TriMesh mesh = read_mesh(path);
  if (s != 1.0) {
    for (Vec3& v : mesh.vertices) v *= s;
  }
  return mesh;
}

TriMesh load_surface_or_shape(const std::string& input, const std::string& units, double edge,
                              std::string& description, bool* builtin) {
  if (builtin) *builtin = false;
  if (std::filesystem::is_regular_file(input)) {
    description = input;
    return load_surface(input, units);
  }
  std::string names;
  for (const auto& n : shape_names()) {
    if (n == input) {
      if (builtin) *builtin = true;
      description = "built-in " + n;
      return make_shape(n, edge);
    }
    names += (names.empty() ? "" : ", ") + n;
  }
  throw InvalidInput(fmt::format("{}: no such file, and not a built-in shape ({})", input, names));
}

CLI::Option* add_stitch_option(CLI::App& cmd, std::string& value) {
  return cmd.add_option("--stitch", value, "Stitch size WIDTHxHEIGHT in mm (default 3.5x2.8)");
}

bool is_stitch_mesh_ply(const std::string& path) {
  const std::string data = io_detail::load_file(path);
  const ply_detail::PlyHeader header = ply_detail::read_ply_header(path, data);
  const int face = header.find("face");
  return face >= 0 && header.elements[face].find("type") >= 0;
}

nlohmann::json scalar_stats_json(const ScalarStats& s) {
  return {{"count", s.count}, {"min", s.min}, {"mean", s.mean}, {"rms", s.rms},
          {"max", s.max},     {"p50", s.p50}, {"p90", s.p90},   {"p99", s.p99}};
}

void write_report_json(const std::string& path, const nlohmann::json& report, bool print) {
  const std::string text = report.dump(2) + "\n";
  write_file_atomically(path, [&](std::ostream& os) { os << text; });
  if (print) std::fputs(text.c_str(), stdout);
}

std::string read_text_file(const std::string& path, const std::string& what) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw IOError(fmt::format("{}: cannot open the {}", path, what));
  std::ostringstream ss;
  ss << in.rdbuf();
  if (in.bad()) throw IOError(fmt::format("{}: cannot read the {}", path, what));
  return ss.str();
}

void add_design_machine_options(CLI::App& cmd, DesignMachineOptions& o) {
  cmd.add_option("--machine", o.machine,
                 "Machine to write the program for: shima-swg091n2 (knitout.k), kniterate, generic, brother-kh868 "
                 "(hand instructions)")
      ->capture_default_str();
  cmd.add_flag("--no-knitout", o.no_knitout, "Do not write the machine program");
  cmd.add_option("--waste-rows", o.waste_rows,
                 "Courses of waste yarn before the fabric (default: the machine's, e.g. 70 on the Kniterate)");
}

nlohmann::json design_machine_end(const DesignMachineOptions& o, const std::string& outdir, const KnittingMap& map,
                                  bool map_knittable, const StitchMesh* designed, bool& machine_ok,
                                  nlohmann::json& machine_check) {
  const MachineProfile& prof = machine_profile(o.machine);
  machine_ok = true;
  if (o.no_knitout) return machine_report_skipped(prof, "--no-knitout");
  if (!map_knittable) return machine_report_skipped(prof, "the design is not knittable");
  const std::filesystem::path dir(outdir);
  KnitoutOptions ko;
  ko.waste_rows = o.waste_rows;
  try {
    if (prof.manual) {
      const HandInstructions h = hand_instructions(map, prof);
      const std::string file = (dir / "instructions.html").string();
      write_file_atomically(file, [&](std::ostream& os) { os << hand_instructions_html(h); }, true);
      note("hand instructions -> " + file);
      return {{"profile", prof.name},        {"machine", prof.display_name}, {"verdict", "HAND INSTRUCTIONS"},
              {"instructions", "instructions.html"}, {"stitches", map.num_stitches()},  {"courses", map.rows},
              {"wales", map.cols},           {"hand_transfers", h.hand_transfers}};
    }
    const KnitoutProgram p = write_knitout(map, prof, ko);
    const std::string file = (dir / "knitout.k").string();
    write_file_atomically(file, [&](std::ostream& os) { os << p.text; }, true);
    for (const auto& w : p.warnings) note("warning: " + w);
    nlohmann::json j = machine_report_json(p, prof, map, "knitout.k", designed);
    note(fmt::format("machine program -> {} ({}: {}, knit graph {} the map; {:.1f} min, {} transfer stitches)", file,
                     prof.name, j["verdict"].get<std::string>(),
                     j.value("matches_map", false) ? "MATCHES" : "DIFFERS from",
                     j.value("knit_time_s", 0.0) / 60.0, j["shaping"]["transfer_stitches"].get<int>()));
    return j;
  } catch (const InvalidInput& e) {
    // The machine cannot knit this (seed-knittable) map: say where.
    machine_ok = false;
    KnitoutOptions check_opt = ko;
    machine_check = to_json(check_machine_knittability(map, prof, check_opt));
    note(fmt::format("machine '{}' cannot knit the design: {}", prof.name, e.what()));
    nlohmann::json j = machine_report_skipped(prof, e.what());
    j["verdict"] = "CANNOT KNIT";
    return j;
  }
}

void note(const std::string& message) { std::fprintf(stderr, "knitforge: %s\n", message.c_str()); }

void write_coloured_stitches(const std::string& path, const StitchMesh& mesh, const std::vector<double>& value,
                             double hi) {
  TriMesh tri;
  tri.vertices = mesh.vertices;
  MeshWriteOptions w;
  const std::vector<Rgb8> colour = scalar_colours(value, 0.0, hi > 0 ? hi : 1.0);
  for (int s = 0; s < mesh.num_stitches(); ++s) {
    const Stitch& st = mesh.stitches[s];
    for (int k = 1; k + 1 < st.corners(); ++k) {
      tri.faces.push_back({st.v[0], st.v[k], st.v[k + 1]});
      w.face_colours.push_back({colour[s][0], colour[s][1], colour[s][2]});
    }
  }
  write_mesh(path, tri, w);
}

void write_evaluation_files(const std::string& dir, const StitchMesh& designed, const StitchMeshEvaluation& ev,
                            bool ascii) {
  const std::filesystem::path d(dir);
  StitchMeshPlyOptions relaxed;
  relaxed.ascii = ascii;
  relaxed.scalars.push_back({"shape_error", ev.stitch_error});
  relaxed.scalars.push_back({"distortion", distortion_values(ev.relaxed_distortion)});
  write_stitch_mesh_ply((d / "relaxed.ply").string(), ev.relaxed, relaxed);
  write_coloured_stitches((d / "shape_error.ply").string(), ev.relaxed, ev.stitch_error, ev.stitch_error_stats.max);
  write_coloured_stitches((d / "distortion.ply").string(), designed, distortion_values(ev.designed_distortion),
                          ev.designed_distortion_stats.max);
}

nlohmann::json evaluation_json(const StitchMeshEvaluation& ev) {
  return {{"shape_error_mm", {{"rms", ev.rms_error}, {"max", ev.max_error}}},
          {"shape_error_relative", {{"rms", ev.relative_rms_error}, {"max", ev.relative_max_error}}},
          {"part_size_mm", ev.target_size},
          {"designed_error_mm", {{"rms", ev.designed_rms_error}, {"max", ev.designed_max_error}}},
          {"relaxation",
           {{"iterations", ev.relax_iterations},
            {"converged", ev.relax_converged},
            {"energy_start", ev.relax_energy_start},
            {"energy_end", ev.relax_energy_end}}},
          {"correspondence_rms_mm", ev.correspondence_rms},
          {"stitch_error_mm", scalar_stats_json(ev.stitch_error_stats)},
          {"distortion_designed", scalar_stats_json(ev.designed_distortion_stats)},
          {"distortion_relaxed", scalar_stats_json(ev.relaxed_distortion_stats)}};
}

}  // namespace knitforge::cli
