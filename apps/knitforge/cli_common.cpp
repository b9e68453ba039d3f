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
#include "knitforge/geometry/mesh_measures.h"
#include "knitforge/geometry/prepare_surface.h"
#include "knitforge/geometry/shapes.h"
#include "knitforge/io/io_detail.h"
#include "knitforge/io/knitting_map_csv.h"
#include "knitforge/io/knitting_map_image.h"
#include "knitforge/io/mesh_io.h"
#include "knitforge/io/polyline_obj.h"
#include "knitforge/io/ply_format.h"
#include "knitforge/io/stitch_mesh_ply.h"
#include "knitforge/util/atomic_file.h"
#include "knitforge/util/errors.h"
#include "knitforge/util/work_limit.h"
#include "knitforge/geometry/mesh_measures.h"

#include <unistd.h>

#include <limits>

namespace knitforge::cli {

namespace {

// The value as the user typed it, printable, at most 63 characters: a longer
// one keeps its first 20 and its last 40 (a path's file name is at its end).
std::string shown(const std::string& text) {
  constexpr size_t kHead = 20, kTail = 40;
  std::string out;
  for (unsigned char c : text) out += (c >= 0x20 && c < 0x7f) ? static_cast<char>(c) : '?';
  if (out.size() <= kHead + kTail + 3) return out;
  return out.substr(0, kHead) + "..." + out.substr(out.size() - kTail);
}

CLI::Validator number_validator(const std::string& name, std::function<std::string(double)> check) {
  return CLI::Validator(
      [check](std::string& text) -> std::string {
        size_t used = 0;
        double v = 0.0;
        try {
          v = std::stod(text, &used);
        } catch (const std::exception&) {
          used = 0;
        }
        if (used == 0 || used != text.size()) return "'" + shown(text) + "' is not a number";
        if (!std::isfinite(v)) return "'" + shown(text) + "' is not a finite number";
        return check(v);
      },
      name);
}

}  // namespace

CLI::Validator positive_number() {
  return number_validator("POSITIVE", [](double v) {
    return v > 0.0 ? std::string() : fmt::format("{} must be a positive number", v);
  });
}

CLI::Validator non_negative_number() {
  return number_validator("NONNEGATIVE", [](double v) {
    return v >= 0.0 ? std::string() : fmt::format("{} must be zero or a positive number", v);
  });
}

CLI::Validator number_in(double lo, double hi) {
  return number_validator(fmt::format("[{}, {}]", lo, hi), [lo, hi](double v) {
    return v >= lo && v <= hi ? std::string() : fmt::format("{} must be within [{}, {}]", v, lo, hi);
  });
}

void check_output_file(const std::string& option, const std::string& path,
                       const std::vector<std::string>& extensions, const std::vector<std::string>& inputs) {
  namespace fs = std::filesystem;
  if (path.empty()) throw UsageError(fmt::format("{}: the output file name is empty", option));
  if (!extensions.empty()) {
    const std::string ext = extension(path);
    if (std::find(extensions.begin(), extensions.end(), ext) == extensions.end()) {
      std::string list;
      for (const auto& e : extensions) list += (list.empty() ? "" : ", ") + e;
      throw InvalidInput(fmt::format("{} {}: unknown output format '{}'; use {}", option, shown(path),
                                     shown(ext), list));
    }
  }
  std::error_code ec;
  if (fs::is_directory(path, ec)) {
    throw InvalidInput(fmt::format("{} {}: is a directory; give a file name{}", option, shown(path),
                                   extensions.empty() ? "" : ", e.g. " + shown((fs::path(path) / ("out" + extensions.front())).string())));
  }
  const fs::path parent = fs::path(path).parent_path().empty() ? fs::path(".") : fs::path(path).parent_path();
  if (!fs::is_directory(parent, ec)) {
    throw InvalidInput(fmt::format("{} {}: the directory {} does not exist; create it first", option, shown(path),
                                   shown(parent.string())));
  }
  if (::access(parent.c_str(), W_OK) != 0) {
    throw InvalidInput(fmt::format("{} {}: the directory {} is not writable", option, shown(path), shown(parent.string())));
  }
  for (const auto& in : inputs) {
    if (!in.empty() && fs::exists(path, ec) && fs::exists(in, ec) && fs::equivalent(path, in, ec)) {
      throw InvalidInput(fmt::format("{} {}: is the input file; writing it would replace the input, give "
                                     "another output name",
                                     option, shown(path)));
    }
  }
}

void check_input_file(const std::string& path) {
  namespace fs = std::filesystem;
  std::error_code ec;
  if (fs::is_directory(path, ec)) throw IOError(fmt::format("{}: is a directory, not a file", shown(path)));
  if (!fs::exists(path, ec)) throw IOError(fmt::format("{}: no such file; check the path", shown(path)));
}

void check_output_dir(const std::string& option, const std::string& path, const std::vector<std::string>& inputs) {
  namespace fs = std::filesystem;
  if (path.empty()) throw UsageError(fmt::format("{}: the output directory name is empty", option));
  std::error_code ec;
  for (const auto& in : inputs) {
    if (!in.empty() && fs::exists(path, ec) && fs::exists(in, ec) && fs::equivalent(path, in, ec)) {
      throw InvalidInput(fmt::format("{} {}: is the input; give a directory for the outputs", option, shown(path)));
    }
  }
  fs::path p(path);
  if (fs::exists(p, ec) && !fs::is_directory(p, ec)) {
    throw InvalidInput(fmt::format(
        "{} {}: exists and is not a directory; the outputs are written into a directory, give a new or "
        "existing directory",
        option, shown(path)));
  }
  // The nearest existing ancestor must be a writable directory (create_directories makes the rest).
  fs::path q = fs::absolute(p, ec);
  while (!q.empty() && !fs::exists(q, ec)) {
    if (q == q.parent_path()) break;
    q = q.parent_path();
  }
  if (!fs::is_directory(q, ec)) {
    throw InvalidInput(fmt::format("{} {}: {} is not a directory, so the output directory cannot be created",
                                   option, shown(path), shown(q.string())));
  }
  if (::access(q.c_str(), W_OK) != 0) {
    throw InvalidInput(fmt::format("{} {}: {} is not writable", option, shown(path), shown(q.string())));
  }
}

CLI::Option* add_max_stitches_option(CLI::App& cmd, double& value) {
  value = kDefaultMaxStitches;
  return cmd
      .add_option("--max-stitches", value,
                  fmt::format("Refuse designs estimated above this many stitches (default {:.0f}; see the user "
                              "guide, Limits)",
                              kDefaultMaxStitches))
      ->check(positive_number());
}

void check_surface_stitches(const TriMesh& surface, const std::string& description, const KnitParams& params,
                            double max_stitches, double bytes_per_stitch) {
  const double area = total_area(surface);
  // The extent of the vertices the faces use (an unused stray vertex does not count).
  Vec3 lo = Vec3::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
  for (const auto& t : surface.faces) {
    for (int v : t) lo = lo.cwiseMin(surface.vertices[v]), hi = hi.cwiseMax(surface.vertices[v]);
  }
  const Vec3 size = surface.faces.empty() ? Vec3::Zero() : Vec3(hi - lo);
  const std::string what =
      fmt::format("{} ({:.4g} mm^2, {:.4g} x {:.4g} x {:.4g} mm) at stitch size {} x {} mm", shown(description), area,
                  size.x(), size.y(), size.z(), params.stitch_width, params.stitch_height);
  check_work({what, area / (params.stitch_width * params.stitch_height), "stitches", max_stitches,
              bytes_per_stitch,
              "check the units (--units) and the stitch size (--stitch), or raise the limit with --max-stitches"});
  // The knitting map spans the surface: its courses and wales are bounded
  // by the extent over the stitch height and width. A few faces reaching far
  // out (a stray vertex 70 m away) make a huge, nearly empty map although
  // the area is small (measured: 5.2 GB and 77 s for the mannequin panel
  // with one such face); refused here at 20 cells per allowed stitch.
  const double extent = size.norm();
  check_work({fmt::format("{} spans {:.4g} mm (diagonal of the faces' bounding box): its knitting map", shown(description),
                          extent),
              (extent / params.stitch_height) * (extent / params.stitch_width), "cells", 20.0 * max_stitches, 8.0,
              "look for stray vertices or faces far from the rest of the surface, check the units (--units), or "
              "raise the limit with --max-stitches (20 cells per stitch)"});
}

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
    throw UsageError(fmt::format(
        "--stitch '{}': expected WIDTHxHEIGHT in millimetres with positive numbers, e.g. 3.5x2.8", shown(text)));
  }
  return p;
}

nlohmann::json newton_timings_json(const NewtonTimings& t) {
  return {{"evaluate_s", t.evaluate}, {"factor_s", t.factor}, {"max_step_s", t.max_step},
          {"line_search_s", t.line_search}};
}

nlohmann::json newton_history_json(const std::vector<NewtonIterate>& history) {
  nlohmann::json j = {{"energy_uj", nlohmann::json::array()},      {"max_force_mn", nlohmann::json::array()},
                      {"factorizations", nlohmann::json::array()}, {"shift", nlohmann::json::array()},
                      {"step", nlohmann::json::array()},           {"energy_trials", nlohmann::json::array()},
                      {"projected", nlohmann::json::array()}};
  for (const NewtonIterate& h : history) {
    j["energy_uj"].push_back(h.energy);
    j["max_force_mn"].push_back(h.max_force_mn);
    j["factorizations"].push_back(h.factorizations);
    j["shift"].push_back(h.shift);
    j["step"].push_back(h.step);
    j["energy_trials"].push_back(h.energy_trials);
    j["projected"].push_back(h.projected);
  }
  return j;
}

double unit_scale(const std::string& units) {
  if (units == "mm") return 1.0;
  if (units == "cm") return 10.0;
  if (units == "m") return 1000.0;
  throw UsageError(fmt::format("--units '{}': expected mm, cm or m", shown(units)));
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
  if (input.empty()) throw UsageError("the input name is empty; give a mesh file or a built-in shape");
  std::error_code ec;
  const std::vector<std::string> shapes = shape_names();
  // A directory is never a mesh: a built-in's name still means the built-in
  // when a directory of that name is in the way (e.g. an earlier `-o sock`).
  if (std::filesystem::is_directory(input, ec) && std::find(shapes.begin(), shapes.end(), input) == shapes.end()) {
    throw InvalidInput(fmt::format("{}: is a directory, not a mesh file", shown(input)));
  }
  if (std::filesystem::is_regular_file(input, ec)) {
    description = input;
    return load_surface(input, units);
  }
  std::string names;
  for (const auto& n : shapes) {
    if (n == input) {
      if (builtin) *builtin = true;
      description = "built-in " + n;
      return make_shape(n, edge);
    }
    names += (names.empty() ? "" : ", ") + n;
  }
  throw InvalidInput(fmt::format("{}: no such file, and not a built-in shape ({})", shown(input), names));
}

TriMesh load_design_surface(const std::string& input, const std::string& units, double edge,
                            std::string& description, bool* builtin, std::vector<int>* vertex_map) {
  const TriMesh raw = load_surface_or_shape(input, units, edge, description, builtin);
  PreparedSurface p = prepare_surface(raw);
  if (p.unused_vertices > 0 || p.welded_vertices > 0) {
    std::string what;
    if (p.unused_vertices > 0) what = fmt::format("dropped {} vertices used by no face", p.unused_vertices);
    if (p.welded_vertices > 0) {
      what += fmt::format("{}welded {} vertices that repeat another's position (a split seam)",
                          what.empty() ? "" : "; ", p.welded_vertices);
    }
    note(fmt::format("{}: {}", description, what));
  }
  if (vertex_map) *vertex_map = std::move(p.vertex_map);
  return std::move(p.mesh);
}

GeodesicSource symmetry_plane_source(const TriMesh& mesh) {
  const BoundingBox box = bounding_box(mesh);
  return source_from_plane(mesh, Vec3(1, 0, 0), 0.5 * (box.min.x() + box.max.x()));
}

std::vector<std::vector<Vec3>> read_cuts(const std::string& path, double scale) {
  const auto lines = read_polylines_obj(path);
  if (lines.empty()) throw InvalidInput(path + ": no polyline (l element) to cut along");
  std::vector<std::vector<Vec3>> out;
  for (const auto& line : lines) {
    out.push_back(line.points);
    for (Vec3& p : out.back()) p *= scale;
  }
  return out;
}

CLI::Option* add_cut_option(CLI::App& cmd, std::string& value) {
  return cmd.add_option("--cut", value,
                        "Cut the surface open along the polylines of FILE.obj first (your own seams); without it, "
                        "a surface that is not a disk is cut into one automatically");
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

nlohmann::json seams_json(const std::vector<Seam>& seams) {
  nlohmann::json list = nlohmann::json::array();
  for (const Seam& s : seams) {
    const Vec3& a = s.path.front();
    const Vec3& b = s.path.back();
    list.push_back({{"kind", to_string(s.kind)},
                    {"on_source", s.on_source},
                    {"length_mm", s.length},
                    {"from_mm", {a.x(), a.y(), a.z()}},
                    {"to_mm", {b.x(), b.y(), b.z()}}});
  }
  return {{"count", static_cast<int>(seams.size())}, {"length_mm", seam_length(seams)}, {"seams", list}};
}

void note_seams(const std::vector<Seam>& seams, int boundary_loops, int genus, const std::string& extra) {
  if (seams.empty()) return;
  note(fmt::format("cut the surface ({} boundary loop(s), genus {}) into a disk along {} seam(s), {:.1f} mm "
                   "(seams.obj){}",
                   boundary_loops, genus, seams.size(), seam_length(seams), extra));
}

void write_seams_obj(const std::string& outdir, const std::vector<Seam>& seams) {
  if (seams.empty()) return;
  std::vector<std::vector<Vec3>> lines;
  for (const Seam& seam : seams) lines.push_back(seam.path);
  write_polylines_obj((std::filesystem::path(outdir) / "seams.obj").string(), lines);
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

nlohmann::json read_json_file(const std::string& path, const std::string& what) {
  const std::string text = read_text_file(path, what);
  try {
    return nlohmann::json::parse(text);
  } catch (const nlohmann::json::parse_error& e) {
    throw InvalidInput(fmt::format("{}: not valid JSON ({})", path, e.what()));
  }
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
                 "Courses of waste yarn before the fabric (at most 1000; default: the machine's, e.g. 70 on the "
                 "Kniterate)")
      ->check(number_in(0, 1000));
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

int machine_exit_code(bool machine_ok, const std::string& machine) {
  if (!machine_ok) {
    note(fmt::format("the design is NOT knittable on machine '{}' (details in report.json, machine_knittability)",
                     machine));
    return 1;
  }
  note("knittable: the map passes every check");
  return 0;
}

std::string shape_name_list() {
  std::string names;
  for (const auto& n : shape_names()) names += (names.empty() ? "" : ", ") + n;
  return names;
}

void note(const std::string& message) { std::fprintf(stderr, "knitforge: %s\n", message.c_str()); }

void write_vertex_coloured(const std::string& path, const TriMesh& surface, const std::vector<double>& value, double lo,
                           double hi, bool ascii) {
  MeshWriteOptions w;
  w.ascii = ascii;
  for (const Rgb8& c : scalar_colours(value, lo, hi > lo ? hi : lo + 1)) w.vertex_colours.push_back({c[0], c[1], c[2]});
  write_mesh(path, surface, w);
}

std::pair<std::vector<double>, double> divergence_magnitude(const std::vector<double>& divergence) {
  std::vector<double> mag(divergence.size());
  for (size_t i = 0; i < mag.size(); ++i) mag[i] = std::abs(divergence[i]);
  std::vector<double> sorted = mag;
  std::sort(sorted.begin(), sorted.end());
  const double p99 = sorted.empty() ? 1.0 : sorted[static_cast<size_t>(0.99 * static_cast<double>(sorted.size() - 1))];
  return {std::move(mag), p99};
}

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
