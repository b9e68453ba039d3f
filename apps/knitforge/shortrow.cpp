// knitforge shortrow: 3D surface -> short-row stitch mesh and knitting map
// (seed §3.2), with evaluation and a report.
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <future>
#include <sstream>

#include <fmt/core.h>
#include <nlohmann/json.hpp>

#include "cli_common.h"
#include "shortrow_tube.h"
#include "knitforge/convert/stitch_mesh_to_yarn.h"
#include "knitforge/core/stitch.h"
#include "knitforge/core/stitch_adjacency.h"
#include "knitforge/design/shortrow/design_short_rows.h"
#include "knitforge/evaluate/scalar_colours.h"
#include "knitforge/evaluate/scalar_stats.h"
#include "knitforge/evaluate/stitch_distortion.h"
#include "knitforge/geometry/mesh_measures.h"
#include "knitforge/geometry/shapes.h"
#include "knitforge/io/knittability_json.h"
#include "knitforge/io/knitting_map_csv.h"
#include "knitforge/io/knitting_map_image.h"
#include "knitforge/io/mesh_io.h"
#include "knitforge/io/polyline_obj.h"
#include "knitforge/report/report_html.h"
#include "knitforge/io/stitch_mesh_ply.h"
#include "knitforge/util/number_list.h"
#include "knitforge/util/timer.h"

namespace knitforge::cli {

namespace {

std::vector<double> parse_numbers(const std::string& text, const std::string& what) {
  return parse_number_list(text, "--source " + what);
}

/// An index given as a number of --source: a whole number in [0, 2^31).
int source_index(double x, const std::string& what) {
  if (!(x >= 0.0) || x != std::floor(x) || x > 2147483647.0) {
    throw UsageError(fmt::format("--source {}: {:.17g} is not an index (a whole number from 0 to 2147483647)",
                                 what, x));
  }
  return static_cast<int>(x);
}

/// A vertex id of the input file as a vertex of the prepared mesh.
int mapped_vertex(const std::vector<int>& vertex_map, double x, const std::string& what) {
  const int id = source_index(x, what);
  if (static_cast<size_t>(id) >= vertex_map.size()) {
    throw InvalidInput(fmt::format("--source {}: vertex id {} is not a vertex of the input (ids 0 to {})", what, id,
                                   vertex_map.size() - 1));
  }
  const int v = vertex_map[static_cast<size_t>(id)];
  if (v < 0) throw InvalidInput(fmt::format("--source {}: vertex {} is used by no face", what, id));
  return v;
}

/// --source TEXT (coordinates in the input's units, scaled by `scale`;
/// vertex ids of the input file, mapped by `vertex_map`).
GeodesicSource parse_source(const TriMesh& mesh, const std::string& text, double scale,
                            const std::vector<int>& vertex_map) {
  if (text.empty()) return symmetry_plane_source(mesh);
  const size_t colon = text.find(':');
  const std::string kind = text.substr(0, colon);
  const std::string args = colon == std::string::npos ? "" : text.substr(colon + 1);
  if (kind == "plane") {
    const auto v = parse_numbers(args, "plane");
    if (v.size() != 4) throw InvalidInput("--source plane:NX,NY,NZ,D takes four numbers (normal and offset)");
    return source_from_plane(mesh, Vec3(v[0], v[1], v[2]), v[3] * scale);
  }
  if (kind == "boundary") {
    const auto v = parse_numbers(args, "boundary");
    if (v.size() != 2 && v.size() != 3) {
      throw InvalidInput(
          "--source boundary:BEGIN,END[,LOOP] takes arc-length fractions in [0, 1] (and a loop index)");
    }
    return source_from_boundary(mesh, v[0], v[1], v.size() == 3 ? source_index(v[2], "boundary loop") : 0);
  }
  if (kind == "boundary-vertices" || kind == "vertex") {
    std::vector<int> ids;
    for (double x : parse_numbers(args, kind)) ids.push_back(mapped_vertex(vertex_map, x, kind));
    if (kind == "vertex") {
      if (ids.size() != 1) throw InvalidInput("--source vertex:ID takes one vertex index");
      return source_from_vertex(mesh, ids[0]);
    }
    return source_from_boundary_vertices(mesh, ids);
  }
  if (kind == "polyline") {
    const auto lines = read_polylines_obj(args);
    if (lines.empty()) throw InvalidInput(args + ": no polyline (l element) in the file");
    std::vector<Vec3> pts = lines.front().points;
    for (Vec3& p : pts) p *= scale;
    return source_from_polyline(mesh, pts);
  }
  throw InvalidInput(
      fmt::format("--source '{}': unknown kind '{}'; use plane:NX,NY,NZ,D, boundary:BEGIN,END[,LOOP], "
                  "boundary-vertices:I,J,..., vertex:I or polyline:FILE.obj",
                  text, kind));
}

}  // namespace

void add_shortrow_command(CLI::App& app, Action& action) {
  auto* cmd = app.add_subcommand("shortrow",
                                 "3D surface -> knittable short-row stitch mesh and knitting map (seed 3.2)");
  struct Opts {
    std::string input, outdir, stitch = "3.5x2.8", units = "mm", source, cut;
    double diffusion = -1.0, diffusion_length = -1.0, lambda = -1.0, edge = kDefaultShapeEdgeLength;
    int relax_iterations = -1;
    double bending = -1;
    double field_tolerance = -1;
    double max_stitches = kDefaultMaxStitches;
    bool json = false, no_evaluate = false, ascii = false, no_report = false;
    TubeFlags tube_flags;
    DesignMachineOptions mach;
    DesignPredictOptions predict;
  };
  auto o = std::make_shared<Opts>();
  const std::string names = shape_name_list();
  cmd->add_option("input", o->input, "Surface mesh (.obj/.ply/.off/.stl) or a built-in shape: " + names)
      ->required();
  cmd->add_option("-o,--output", o->outdir, "Output directory")->required();
  add_stitch_option(*cmd, o->stitch);
  cmd->add_option("--units", o->units,
                  "Units of the input mesh and of --source/--cut coordinates: mm, cm, m");
  cmd->add_option("--source", o->source,
                  "Geodesic source: plane:NX,NY,NZ,D (default: plane x = centre of the bounding box), "
                  "boundary:BEGIN,END[,LOOP] (arc-length fractions), boundary-vertices:I,J,..., vertex:I, "
                  "polyline:FILE.obj");
  cmd->add_option("--edge", o->edge, "Edge length (mm) of a built-in shape's triangulation")
      ->check(positive_number());
  add_cut_option(*cmd, o->cut);
  cmd->add_option("--diffusion", o->diffusion,
                  "Apex diffusion weight mu in mm (default 100 x stitch width; 0 = off)")
      ->check(non_negative_number());
  cmd->add_option("--diffusion-length", o->diffusion_length,
                  "Length (mm) the apex distance D is divided by in exp(-D^2) (default: the stitch width)")
      ->check(positive_number());
  cmd->add_option("--lambda", o->lambda, "Initial bridge length limit in mm (default width + 2 x height)")
      ->check(positive_number());
  cmd->add_flag("--no-evaluate", o->no_evaluate, "Skip the relaxation and shape-error evaluation");
  cmd->add_option("--relax-iterations", o->relax_iterations,
                  "Shape-Up iterations of the evaluation's relaxation (default 60)")
      ->check(positive_number());
  cmd->add_option("--field-tolerance", o->field_tolerance,
                  "Accuracy of the geodesic field as a fraction of the stitch width (default 1e-3; 0 = exact)")
      ->check(non_negative_number());
  cmd->add_option("--bending", o->bending,
                  "Bending stiffness of the evaluation's rest shape, relative to the stitch shape (0 = none)")
      ->check(non_negative_number());
  add_max_stitches_option(*cmd, o->max_stitches);
  cmd->add_flag("--json", o->json, "Print report.json on stdout");
  cmd->add_flag("--no-report", o->no_report, "Do not write report.html");
  cmd->add_flag("--ascii", o->ascii, "Write ASCII PLY files instead of binary");
  add_tube_flags(*cmd, o->tube_flags);
  add_design_machine_options(*cmd, o->mach);
  add_design_predict_options(*cmd, o->predict);
  cmd->callback([=, &action] {
    action = [=]() -> int {
      if (auto t = tube_command(o->tube_flags, {cmd->get_option("--source"), cmd->get_option("--cut"),
                                                  cmd->get_option("--diffusion"), cmd->get_option("--lambda"),
                                                  cmd->get_option("--field-tolerance")})) {
        copy_common_options(*o, *t);
        return run_tube_design(*t);
      }
      Timer all;
      const KnitParams params = parse_stitch_size(o->stitch);
      const double scale = unit_scale(o->units);
      check_output_dir("-o", o->outdir, {o->input, o->cut});
      std::string description;
      Timer t;
      std::vector<int> vertex_map;
      const TriMesh input = load_design_surface(o->input, o->units, o->edge, description, nullptr, &vertex_map);
      // ~2.5 kB per stitch measured (5 GB for 2 million at 0.1 x 0.1 mm).
      check_surface_stitches(input, description, params, o->max_stitches, 2500.0);
      const double load_seconds = t.seconds();
      const GeodesicSource source = parse_source(input, o->source, scale, vertex_map);

      ShortRowOptions opt;
      opt.params = params;
      if (o->diffusion >= 0) opt.tessellation.mu = o->diffusion;
      if (o->lambda > 0) opt.tessellation.lambda = o->lambda;
      if (o->diffusion_length > 0) opt.tessellation.diffusion_length = o->diffusion_length;
      opt.evaluate = !o->no_evaluate;
      if (o->relax_iterations > 0) opt.evaluation.relax.max_iterations = o->relax_iterations;
      if (o->bending >= 0) opt.evaluation.relax.bending = o->bending;
      if (o->field_tolerance >= 0) opt.field_tolerance = o->field_tolerance;
      // Progress as the share of the route's stages begun (8, or 9 with the evaluation).
      const int stages = opt.evaluate ? 9 : 8;
      auto begun = std::make_shared<int>(0);
      opt.progress = [stages, begun](const std::string& stage) {
        note(fmt::format("[{:3d} %] {} ...", 100 * (*begun)++ / stages, stage));
      };
      if (!o->cut.empty()) opt.cuts = read_cuts(o->cut, scale);
      opt.surface_name = description;
      const ShortRowDesign d = design_short_rows(input, source, opt);
      const TriMesh& surface = d.surface;
      note_seams(d.seams, d.input_boundary_loops, d.input_genus,
                 d.source_on_seam ? "; the source lies on a seam" : "");

      // Outputs.
      note("writing outputs ...");
      t.reset();
      const std::filesystem::path dir(o->outdir);
      std::filesystem::create_directories(dir);
      auto out = [&](const char* name) { return (dir / name).string(); };
      StitchMeshPlyOptions ply;
      ply.ascii = o->ascii;
      const std::vector<double> designed_distortion =
          d.evaluation ? distortion_values(d.evaluation->designed_distortion) : std::vector<double>{};
      {
        // Per-stitch evaluation values go into the stitch mesh for viewers.
        StitchMeshPlyOptions designed = ply;
        if (d.evaluation) {
          designed.scalars.push_back({"distortion", designed_distortion});
          designed.scalars.push_back({"shape_error", d.evaluation->stitch_error});
        }
        write_stitch_mesh_ply(out("stitch_mesh.ply"), d.stitch_mesh, designed);
      }
      // The map pictures are written on the second core while this thread
      // writes the rest (they read `d` only).
      std::future<void> second = std::async(std::launch::async, [&d, &out] {
        write_knitting_map_png(out("knitting_map.png"), d.map);
        write_knitting_map_svg(out("knitting_map.svg"), d.map);
      });
      // The yarn follows the one-stroke knitting order, which only a
      // knittable stitch mesh has.
      if (d.mesh_check.ok()) write_yarn_obj(out("yarn.obj"), stitch_mesh_to_yarn(d.stitch_mesh, params));
      write_knitting_map_csv(out("knitting_map.csv"), d.map);
      std::vector<std::vector<Vec3>> wales;
      for (const auto& level : d.wales.wales) {
        for (const auto& w : level) wales.push_back(w.points);
      }
      write_polylines_obj(out("wales.obj"), wales);
      write_seams_obj(o->outdir, d.seams);
      if (!d.wales.cuts.empty()) {
        std::vector<std::vector<Vec3>> cuts;
        for (const auto& c : d.wales.cuts) cuts.push_back(c.path);
        write_polylines_obj(out("cuts.obj"), cuts);
      }
      {
        MeshWriteOptions w;
        w.ascii = o->ascii;
        double lo = d.field.empty() ? 0 : d.field[0], hi = lo;
        for (double f : d.field) lo = std::min(lo, f), hi = std::max(hi, f);
        for (const Rgb8& c : scalar_colours(d.field, lo, hi > lo ? hi : lo + 1))
          w.vertex_colours.push_back({c[0], c[1], c[2]});
        write_mesh(out("field.ply"), surface, w);
        MeshWriteOptions plain;
        plain.ascii = o->ascii;
        write_mesh(out("target.ply"), surface, plain);
      }
      nlohmann::json report;
      if (d.evaluation) write_evaluation_files(o->outdir, d.stitch_mesh, *d.evaluation, o->ascii);
      const std::vector<std::string> shape_notes =
          report_design_shape(report, o->predict, o->no_evaluate, o->outdir, d.stitch_mesh, params, surface,
                              d.evaluation ? &*d.evaluation : nullptr, o->ascii);
      const auto types = count_stitch_types(d.stitch_mesh);
      const int short_row_ends = types[static_cast<int>(StitchType::ShortRowLeft)] +
                                 types[static_cast<int>(StitchType::ShortRowRight)];
      double cut_length = 0;
      for (const auto& c : d.wales.cuts) cut_length += c.length;
      const double expected = d.surface_area / (params.stitch_width * params.stitch_height);
      report["input"] = {{"surface", description},
                         {"units", o->units},
                         {"vertices", input.num_vertices()},
                         {"faces", input.num_faces()},
                         {"boundary_loops", d.input_boundary_loops},
                         {"genus", d.input_genus},
                         {"area_mm2", d.surface_area},
                         {"source", d.source.description}};
      report["seams"] = seams_json(d.seams);
      report["seams"]["source_on_seam"] = d.source_on_seam;
      report["seams"]["source_candidates"] = d.source_seam_candidates;
      report["seams"]["designed_surface"] = {{"vertices", surface.num_vertices()}, {"faces", surface.num_faces()}};
      report["parameters"] = {
          {"stitch_width_mm", params.stitch_width},
          {"stitch_height_mm", params.stitch_height},
          {"lambda_mm", o->lambda > 0 ? o->lambda : params.stitch_width + 2 * params.stitch_height},
          {"diffusion_mu_mm", o->diffusion >= 0 ? o->diffusion : 100 * params.stitch_width},
          {"diffusion_length_mm", o->diffusion_length > 0 ? o->diffusion_length : params.stitch_width},
          {"field_tolerance_mm", opt.field_tolerance * params.stitch_width},
          {"evaluation_bending", opt.evaluation.relax.bending}};
      report["counts"] = {{"stitches", d.stitch_mesh.num_stitches()},
                          {"quads", types[static_cast<int>(StitchType::Knit)]},
                          {"short_row_ends", short_row_ends},
                          {"expected_stitches_area", expected},
                          {"stitches_vs_area", d.stitch_mesh.num_stitches() / expected - 1.0},
                          {"courses", d.map.rows},
                          {"map_columns", d.map.cols},
                          {"wales", d.wales.num_wales()},
                          {"wale_levels", static_cast<int>(d.wales.values.size())},
                          {"dropped_wale_pieces", d.wales.dropped_pieces},
                          {"shifted_wale_levels", static_cast<int>(d.wales.shifted_levels.size())},
                          {"strips", d.strips},
                          {"unpaired_wale_pieces", d.unpaired_pieces},
                          {"lambda_growths", d.lambda_growths},
                          {"max_lambda_mm", d.max_lambda},
                          {"interior_apexes", d.interior_apexes},
                          {"boundary_apex_triangles_to_quads", d.boundary_quads.triangles},
                          {"support_stitches", d.courses.support_stitches},
                          {"cuts", static_cast<int>(d.wales.cuts.size())},
                          {"cut_length_mm", cut_length}};
      report["apexes"] = {{"count", static_cast<int>(d.apex_spacing.apexes.size())},
                          {"nearest_apex_mm", scalar_stats_json(d.apex_spacing.stats)}};
      report["field"] = {
          {"signed", d.field_signed}, {"windows", d.field_windows}, {"approximate", d.field_approximate}};
      report["knittability"] = {{"map", to_json(d.map_check)}, {"stitch_mesh", to_json(d.mesh_check)}};
      Timer tm;
      bool machine_ok = true;
      nlohmann::json machine_check;
      report["machine"] = design_machine_end(o->mach, o->outdir, d.map, d.map_check.ok() && d.mesh_check.ok(),
                                             &d.stitch_mesh, machine_ok, machine_check);
      if (!machine_check.is_null()) report["machine_knittability"] = machine_check;
      const double machine_seconds = tm.seconds();
      report["knittable"] = d.map_check.ok() && d.mesh_check.ok() && machine_ok;
      second.get();  // rethrows what the second thread threw
      report["seconds"] = {{"load", load_seconds},
                           {"seams", d.seconds.seams},
                           {"field", d.seconds.field},
                           {"wales", d.seconds.wales},
                           {"tessellation", d.seconds.tessellation},
                           {"post_processing", d.seconds.post_processing},
                           {"courses", d.seconds.courses},
                           {"map", d.seconds.map},
                           {"knittability", d.seconds.check},
                           {"evaluation", d.seconds.evaluation},
                           {"design_total", d.seconds.total},
                           {"machine", machine_seconds},
                           {"output", t.seconds() - machine_seconds}};
      report["seconds"]["total"] = all.seconds();
      write_report_json(out("report.json"), report, o->json);
      if (!o->no_report) {
        write_report_html(o->outdir);
        note("report page -> " + out("report.html"));
      }

      note(fmt::format(
          "{} stitches ({} short-row ends), {} courses x {} columns, {} wales, {} cuts; {:.2f} s -> {}",
          d.stitch_mesh.num_stitches(), short_row_ends, d.map.rows, d.map.cols, d.wales.num_wales(),
          d.wales.cuts.size(), all.seconds(), o->outdir));
      for (const std::string& line : shape_notes) note(line);
      if (!(d.map_check.ok() && d.mesh_check.ok())) {
        const KnittabilityReport& r = d.map_check.ok() ? d.mesh_check : d.map_check;
        std::fprintf(stderr, "%s", r.text().c_str());
        note("the design is NOT knittable (details in report.json); outputs were written for inspection");
        int pieces = 1;
        bool user_seams = false;
        for (const Seam& seam : d.seams) user_seams = user_seams || seam.kind == SeamKind::User;
        try {
          StitchAdjacency(d.stitch_mesh).halfedges().face_components(&pieces);
        } catch (const Error&) {
          pieces = 1;  // the checker has said what is wrong with the mesh
        }
        if (pieces > 1) {
          note(fmt::format(
              "the stitches fall apart into {} separate pieces: the field has a ridge (a line of maxima "
              "where wales from two parts of the source meet, e.g. a plane that cuts the surface twice), "
              "which no course crosses; choose a source whose field rises to one side only, e.g. a "
              "plane that cuts the surface once, or a part of the boundary{}",
              pieces,
              user_seams ? "; or move the seams (--cut): the wales run from the source to the seams, so a seam "
                           "much shorter than the source makes them meet before it (without --cut the seam "
                           "between two rims follows the longest piece of the source that joins them)"
                         : ""));
        } else if (!d.wales.cuts.empty() || d.unpaired_pieces > 0) {
          note(fmt::format(
              "the field needed {} cut(s) and has {} unpaired wale piece(s): where it branches the "
              "courses cannot be knitted in one stroke; try a source that avoids the cut locus, e.g. "
              "the plane rotated by 90 degrees (see docs/shortrow.md)",
              d.wales.cuts.size(), d.unpaired_pieces));
        }
        return 1;
      }
      return machine_exit_code(machine_ok, o->mach.machine);
    };
  });
}

}  // namespace knitforge::cli
