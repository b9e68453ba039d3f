// knitforge shortcolumn: 3D surface -> stitch mesh and knitting map with short
// rows and short columns whose transfer stitches are few, by the optimised
// harmonic field of seed §3.3; machine program, report and a comparison
// with the short-row-only design of the same surface.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <sstream>

#include <fmt/core.h>
#include <nlohmann/json.hpp>

#include "cli_common.h"
#include "shortrow_tube.h"
#include "knitforge/convert/stitch_mesh_to_yarn.h"
#include "knitforge/core/stitch.h"
#include "knitforge/design/shortcolumn/design_short_columns.h"
#include "knitforge/design/shortcolumn/harmonic_field.h"
#include "knitforge/design/shortcolumn/optimise_boundary.h"
#include "knitforge/design/shortrow/design_short_rows.h"
#include "knitforge/evaluate/scalar_colours.h"
#include "knitforge/evaluate/stitch_distortion.h"
#include "knitforge/geometry/cut_to_disk.h"
#include "knitforge/geometry/geodesic_source.h"
#include "knitforge/geometry/mesh_measures.h"
#include "knitforge/geometry/shapes.h"
#include "knitforge/geometry/surface_checks.h"
#include "knitforge/io/knittability_json.h"
#include "knitforge/io/knitting_map_csv.h"
#include "knitforge/io/knitting_map_image.h"
#include "knitforge/io/mesh_io.h"
#include "knitforge/io/png_image.h"
#include "knitforge/io/polyline_obj.h"
#include "knitforge/io/stitch_mesh_ply.h"
#include "knitforge/io/vertex_field.h"
#include "knitforge/machine/knitout_writer.h"
#include "knitforge/machine/machine_profile.h"
#include "knitforge/report/machine_report.h"
#include "knitforge/report/optimisation_plot.h"
#include "knitforge/render/camera.h"
#include "knitforge/render/raster_preview.h"
#include "knitforge/report/report_html.h"
#include "knitforge/util/atomic_file.h"
#include "knitforge/util/number_list.h"
#include "knitforge/util/timer.h"

namespace knitforge::cli {

namespace {

nlohmann::json bvec(const BoundaryVector& b) { return {b[0], b[1], b[2], b[3]}; }

/// "NX,NY,NZ,D" (--mirror, coordinates in the input's units).
MirrorPlane parse_mirror(const std::string& text, double scale) {
  const std::vector<double> v = parse_number_list(text, "--mirror " + text);
  if (v.size() != 4) throw InvalidInput("--mirror NX,NY,NZ,D takes four numbers (the plane n . x = D)");
  return {Vec3(v[0], v[1], v[2]), v[3] * scale};
}

/// The same colours as a picture (640 x 480, framed as `knitforge render`
/// frames a mesh; both sides drawn).
void write_vertex_coloured_png(const std::string& path, const TriMesh& surface, const std::vector<double>& value,
                               double lo, double hi) {
  RenderMesh m;
  m.name = "surface";
  m.mesh = surface;
  m.normals = vertex_normals(surface);
  for (const Rgb8& c : scalar_colours(value, lo, hi > lo ? hi : lo + 1)) m.vertex_colours.push_back({c[0], c[1], c[2]});
  RasterOptions ro;
  ro.width = 640;
  ro.height = 480;
  ro.cull_back_faces = false;
  const Camera camera = frame_points(surface.vertices, static_cast<double>(ro.width) / ro.height);
  write_png(path, rasterize(std::span<const RenderMesh>(&m, 1), camera, ro));
}

nlohmann::json counts_json(const ShortColumnCounts& c) {
  return {{"stitches", c.stitches},
          {"quads", c.knit},
          {"short_row_ends", c.short_row_ends},
          {"increases", c.increases},
          {"decreases", c.decreases},
          {"transfer_stitches", c.transfers()}};
}

/// The short-row-only design of the same surface (plane x = centre), for the
/// comparison section: counts, knittability, knit time and distortion.
nlohmann::json short_row_comparison(const TriMesh& surface, const KnitParams& params, bool evaluate,
                                    const DesignMachineOptions& mach) {
  nlohmann::json j;
  try {
    const BoundingBox box = bounding_box(surface);
    const GeodesicSource source = source_from_plane(surface, Vec3(1, 0, 0), box.center().x());
    ShortRowOptions so;
    so.params = params;
    so.evaluate = evaluate;
    const ShortRowDesign d = design_short_rows(surface, source, so);
    const auto types = count_stitch_types(d.stitch_mesh);
    j = {{"source", source.description},
         {"stitches", d.stitch_mesh.num_stitches()},
         {"short_row_ends", types[static_cast<int>(StitchType::ShortRowLeft)] +
                                types[static_cast<int>(StitchType::ShortRowRight)]},
         {"transfer_stitches", types[static_cast<int>(StitchType::Increase)] +
                                   types[static_cast<int>(StitchType::Decrease)]},
         {"cuts", static_cast<int>(d.wales.cuts.size())},
         {"courses", d.map.rows},
         {"knittable", d.map_check.ok() && d.mesh_check.ok()}};
    if (d.evaluation) {
      j["distortion_designed"] = scalar_stats_json(d.evaluation->designed_distortion_stats);
      j["shape_error_rms_mm"] = d.evaluation->rms_error;
    }
    if (j["knittable"].get<bool>() && !mach.no_knitout) {
      const MachineProfile& prof = machine_profile(mach.machine);
      if (!prof.manual) {
        KnitoutOptions ko;
        ko.waste_rows = mach.waste_rows;
        try {
          const KnitoutProgram p = write_knitout(d.map, prof, ko);
          const nlohmann::json m = machine_report_json(p, prof, d.map, "", &d.stitch_mesh);
          j["machine"] = {{"verdict", m["verdict"]},
                          {"matches_map", m.value("matches_map", false)},
                          {"knit_time_s", m.value("knit_time_s", 0.0)},
                          {"transfers", m["shaping"].value("transfers", 0)}};
        } catch (const InvalidInput& e) {
          j["machine"] = {{"verdict", "CANNOT KNIT"}, {"reason", e.what()}};
        }
      }
    }
  } catch (const Error& e) {
    j = {{"error", e.what()}};
  }
  return j;
}

}  // namespace

void add_shortcolumn_command(CLI::App& app, Action& action) {
  auto* cmd = app.add_subcommand(
      "shortcolumn",
      "3D surface -> knittable stitch mesh with short rows and short columns, few transfers (optimised harmonic field, "
      "seed 3.3)");
  struct Opts {
    std::string input, outdir, stitch = "3.5x2.8", units = "mm", bc, field, mirror, cut;
    double max_stitches = kDefaultMaxStitches;
    double edge = kDefaultShapeEdgeLength, diffusion = -1.0;
    bool optimise = false, symmetric = false, json = false, no_evaluate = false, ascii = false, no_report = false,
         no_compare = false;
    int budget = 100, alternatives = 10, proxy_faces = 3000;
    uint64_t seed = 0;
    DesignMachineOptions mach;
    DesignPredictOptions predict;
    TubeFlags tube_flags;
  };
  auto o = std::make_shared<Opts>();
  const std::string names = shape_name_list();
  cmd->add_option("input", o->input, "Surface mesh (.obj/.ply/.off/.stl) of one piece (cut into a disk when it is not one), or a built-in shape: " + names)
      ->required();
  cmd->add_option("-o,--output", o->outdir, "Output directory")->required();
  add_stitch_option(*cmd, o->stitch);
  cmd->add_option("--units", o->units, "Units of the input mesh and of --mirror: mm, cm, m");
  cmd->add_option("--edge", o->edge, "Edge length (mm) of a built-in shape's triangulation")
      ->check(CLI::PositiveNumber);
  auto* bc = cmd->add_option("--bc", o->bc,
                             "Dirichlet intervals b0,b1,b2,b3 on the boundary parameterised anticlockwise by arc length "
                             "from 0 to 1 (f = 0 on [b0,b1], f = 1 on [b2,b3]; 0 <= b0 <= b1 < b2 <= b3 < 1 + b0 < 2)");
  auto* field = cmd->add_option("--field", o->field,
                                "Governing field instead of the harmonic one: 'fiedler' or a file with one value per "
                                "vertex (its minimum must lie on the boundary)");
  auto* opt = cmd->add_flag("--optimise,--optimize", o->optimise,
                            "Optimise b by TuRBO to minimise the divergence metric (default when neither --bc nor "
                            "--field is given)");
  cmd->add_option("--budget", o->budget, "Objective evaluations of the optimisation (default 100)")
      ->check(CLI::Range(1, 100000));
  cmd->add_flag("--symmetric", o->symmetric,
                "Optimise the 2D symmetric variant (R_s and R_e centred on the mirror plane)");
  cmd->add_option("--mirror", o->mirror,
                  "Mirror plane NX,NY,NZ,D of --symmetric (default: x = centre or y = centre, whichever fits)");
  cmd->add_option("--seed", o->seed, "Random seed of the optimisation (default 0)");
  cmd->add_option("--alternatives", o->alternatives,
                  "Keep the K best distinct boundary vectors (design alternatives, default 10); they are designed "
                  "best first until one is knittable")
      ->check(CLI::Range(1, 1000));
  cmd->add_option("--proxy-faces", o->proxy_faces,
                  "Optimise on the surface remeshed to about this many triangles (default 3000; 0 = the surface)")
      ->check(CLI::NonNegativeNumber);
  cmd->add_option("--diffusion", o->diffusion, "Apex diffusion weight mu in mm (default 100 x stitch width; 0 = off)")
      ->check(CLI::NonNegativeNumber);
  cmd->add_flag("--no-evaluate", o->no_evaluate, "Skip the relaxation and shape-error evaluation");
  cmd->add_flag("--no-compare", o->no_compare, "Skip the comparison with the short-row-only design");
  cmd->add_flag("--json", o->json, "Print report.json on stdout");
  cmd->add_flag("--no-report", o->no_report, "Do not write report.html");
  cmd->add_flag("--ascii", o->ascii, "Write ASCII PLY files instead of binary");
  add_cut_option(*cmd, o->cut);
  add_max_stitches_option(*cmd, o->max_stitches);
  add_design_machine_options(*cmd, o->mach);
  add_design_predict_options(*cmd, o->predict);
  add_tube_flags(*cmd, o->tube_flags);
  bc->excludes(field);
  field->excludes(bc);
  opt->excludes(field);
  field->excludes(opt);
  cmd->callback([=, &action] {
    action = [=]() -> int {
      // In the round (seed 3.3.8): the rounds follow the field's isocurves
      // and the wales start and end as increases and decreases (short
      // columns) where the rounds grow and shrink: the tube route.
      std::vector<const CLI::Option*> sheet_only;
      for (const char* name : {"--bc", "--field", "--optimise", "--budget", "--symmetric", "--mirror", "--seed",
                               "--alternatives", "--proxy-faces", "--diffusion", "--no-compare", "--cut"})
        sheet_only.push_back(cmd->get_option(name));
      if (auto t = tube_command(o->tube_flags, sheet_only)) {
        copy_common_options(*o, *t);
        return run_tube_design(*t);
      }
      Timer all;
      const KnitParams params = parse_stitch_size(o->stitch);
      const double scale = unit_scale(o->units);
      const bool field_file = !o->field.empty() && o->field != "fiedler";
      check_output_dir("-o", o->outdir, {o->input, o->cut, field_file ? o->field : std::string()});
      std::string description;
      Timer t;
      const TriMesh input = load_design_surface(o->input, o->units, o->edge, description);
      // ~2.5 kB per stitch as the short-row route (the same stages after the wales).
      check_surface_stitches(input, description, params, o->max_stitches, 2500.0);
      // A surface that is not a disk is cut into one (seams prefer the plane
      // x = centre, as flatten's); the field lives on the disk.
      CutToDiskOptions seam_options;
      seam_options.source = symmetry_plane_source(input);
      if (!o->cut.empty()) seam_options.cuts = read_cuts(o->cut, scale);
      CutToDisk opened = cut_to_disk(input, seam_options, description);
      const TriMesh surface = std::move(opened.mesh);
      const std::vector<Seam> seams = std::move(opened.seams);
      note_seams(seams, opened.input_boundary_loops, opened.input_genus);
      if (field_file && !seams.empty())
        throw InvalidInput(fmt::format("--field {}: {} is not a disk and was cut open (its vertices changed); give "
                                       "a field for a disk surface, or cut it first",
                                       o->field, description));
      const double load_seconds = t.seconds();
      const std::filesystem::path dir(o->outdir);
      auto out = [&](const char* name) { return (dir / name).string(); };

      // The governing field.
      nlohmann::json field_json;
      std::vector<double> f;
      std::vector<BoundaryVector> candidates;  // harmonic fields to try, best first
      std::optional<BoundaryOptimisation> optimisation;
      const bool optimise = o->optimise || (o->bc.empty() && o->field.empty());
      t.reset();
      if (!o->field.empty()) {
        if (o->field == "fiedler") {
          note("Fiedler field ...");
          const FiedlerField ff = fiedler_field(surface);
          f = ff.value;
          field_json = {{"kind", "fiedler"},
                        {"eigenvalue_per_mm2", ff.eigenvalue},
                        {"residual", ff.residual},
                        {"iterations", ff.iterations},
                        {"converged", ff.converged},
                        {"interior_extrema", ff.interior_extrema}};
        } else {
          f = read_vertex_field(o->field, surface.num_vertices());
          field_json = {{"kind", "file"}, {"file", o->field}, {"interior_extrema", count_interior_extrema(surface, f)}};
        }
      } else if (!optimise) {
        candidates.push_back(parse_boundary_vector(o->bc));
      } else {
        BoundaryOptimisationOptions bo;
        bo.stitch_width = params.stitch_width;
        bo.turbo.max_evaluations = o->budget;
        bo.turbo.seed = o->seed;
        bo.symmetric = o->symmetric;
        if (!o->mirror.empty()) bo.mirror = parse_mirror(o->mirror, scale);
        bo.alternatives = o->alternatives;
        bo.proxy_faces = o->proxy_faces;
        const int budget = o->budget;
        bo.progress = [budget](const BoundaryEvaluation& e, int i) {
          note(fmt::format("evaluation {}/{}: b = ({}){} estimated transfers {:.1f} (best {:.1f})", i + 1, budget,
                           format_boundary_vector(e.evaluated), e.projected ? " projected," : "", e.value, e.best));
        };
        note(fmt::format("optimising the boundary conditions ({} evaluations{}) ...", o->budget,
                         o->symmetric ? ", symmetric" : ""));
        optimisation = optimise_boundary(surface, bo);
        for (int i : optimisation->alternatives) candidates.push_back(optimisation->history[static_cast<size_t>(i)].evaluated);
        std::filesystem::create_directories(dir);
        write_file_atomically(out("optimisation.json"),
                              [&](std::ostream& os) { os << optimisation_json(*optimisation).dump(1) << "\n"; });
        write_file_atomically(out("optimisation.svg"), [&](std::ostream& os) { os << optimisation_plot_svg(*optimisation); });
        note(fmt::format("optimisation: best b = ({}), estimated {:.1f} transfer stitches on the {}-face proxy; {:.2f} s",
                         format_boundary_vector(optimisation->best), optimisation->best_value, optimisation->proxy_faces,
                         optimisation->seconds));
      }
      const double field_seconds = t.seconds();

      ShortColumnOptions sopt;
      sopt.params = params;
      if (o->diffusion >= 0) sopt.tessellation.mu = o->diffusion;
      sopt.evaluate = !o->no_evaluate;
      sopt.progress = [](const std::string& stage) { note(stage + " ..."); };
      // Design: the field given, or the candidates in order until one is knittable.
      std::optional<ShortColumnDesign> design;
      nlohmann::json tried = nlohmann::json::array();
      if (candidates.empty()) {
        design = design_short_columns(surface, f, sopt);
      } else {
        HarmonicFieldSolver solver(surface);
        for (size_t k = 0; k < candidates.size(); ++k) {
          HarmonicField h;
          try {
            h = solver.solve(candidates[k]);
          } catch (const TopologyError& e) {
            if (k + 1 == candidates.size() && !design) throw;
            note(fmt::format("b = ({}): {}; trying the next alternative", format_boundary_vector(candidates[k]),
                             e.what()));
            tried.push_back({{"b", bvec(candidates[k])}, {"error", e.what()}});
            continue;
          }
          if (candidates.size() > 1) note(fmt::format("design with b = ({}) ...", format_boundary_vector(candidates[k])));
          std::optional<ShortColumnDesign> attempt;
          try {
            attempt = design_short_columns(surface, h.value, sopt);
          } catch (const Error& e) {
            // A stage that fails (e.g. a strip without a tessellation) makes
            // this b unusable, not the run: try the next one.
            if (k + 1 == candidates.size() && !design) throw;
            note(fmt::format("b = ({}): {}; {}", format_boundary_vector(candidates[k]), e.what(),
                             k + 1 < candidates.size() ? "trying the next alternative" : "keeping the best design so far"));
            tried.push_back({{"b", bvec(candidates[k])}, {"error", e.what()}});
            continue;
          }
          ShortColumnDesign& d = *attempt;
          tried.push_back({{"b", bvec(candidates[k])},
                           {"knittable", d.knittable()},
                           {"transfer_stitches", d.counts.transfers()},
                           {"estimated_transfers", d.metric.transfer_estimate(params.stitch_width)}});
          const bool ok = d.knittable();
          if (!design || ok) {
            design = std::move(d);
            field_json = {{"kind", "harmonic"},
                          {"b", bvec(h.b)},
                          {"candidate", k},
                          {"dirichlet_zero_vertices", h.sets.zero.size()},
                          {"dirichlet_one_vertices", h.sets.one.size()},
                          {"adjusted", h.sets.adjusted},
                          {"interior_extrema", h.interior_extrema}};
            f = h.value;
          }
          if (ok) break;
          note(fmt::format("b = ({}) gives a design that is not knittable{}", format_boundary_vector(candidates[k]),
                           k + 1 < candidates.size() ? "; trying the next alternative" : ""));
        }
      }
      const ShortColumnDesign& d = *design;

      // Outputs.
      note("writing outputs ...");
      t.reset();
      std::filesystem::create_directories(dir);
      StitchMeshPlyOptions ply;
      ply.ascii = o->ascii;
      {
        StitchMeshPlyOptions designed = ply;
        if (d.evaluation) {
          designed.scalars.push_back({"distortion", distortion_values(d.evaluation->designed_distortion)});
          designed.scalars.push_back({"shape_error", d.evaluation->stitch_error});
        }
        write_stitch_mesh_ply(out("stitch_mesh.ply"), d.stitch_mesh, designed);
      }
      write_knitting_map_png(out("knitting_map.png"), d.map);
      write_knitting_map_svg(out("knitting_map.svg"), d.map);
      write_knitting_map_csv(out("knitting_map.csv"), d.map);
      if (d.mesh_check.ok()) write_yarn_obj(out("yarn.obj"), stitch_mesh_to_yarn(d.stitch_mesh, params));
      write_polylines_obj(out("wales.obj"), d.wales.wales);
      {
        double lo = f.empty() ? 0 : f[0], hi = lo;
        for (double x : f) lo = std::min(lo, x), hi = std::max(hi, x);
        write_vertex_coloured(out("field.ply"), surface, f, lo, hi, o->ascii);
        write_vertex_field(out("field.txt"), f);
        const auto [mag, p99] = divergence_magnitude(d.metric.divergence);
        write_vertex_coloured(out("divergence.ply"), surface, mag, 0.0, p99, o->ascii);
        write_vertex_coloured_png(out("field.png"), surface, f, lo, hi);
        write_vertex_coloured_png(out("divergence.png"), surface, mag, 0.0, p99);
        MeshWriteOptions plain;
        plain.ascii = o->ascii;
        write_mesh(out("target.ply"), surface, plain);
      }
      nlohmann::json report;
      if (d.evaluation) write_evaluation_files(o->outdir, d.stitch_mesh, *d.evaluation, o->ascii);
      const std::vector<std::string> shape_notes =
          report_design_shape(report, o->predict, o->no_evaluate, o->outdir, d.stitch_mesh, params, surface,
                              d.evaluation ? &*d.evaluation : nullptr, o->ascii);
      const double expected = d.surface_area / (params.stitch_width * params.stitch_height);
      report["input"] = {{"surface", description},
                         {"units", o->units},
                         {"vertices", surface.num_vertices()},
                         {"faces", surface.num_faces()},
                         {"area_mm2", d.surface_area}};
      report["parameters"] = {{"stitch_width_mm", params.stitch_width},
                              {"stitch_height_mm", params.stitch_height},
                              {"diffusion_mu_mm", o->diffusion >= 0 ? o->diffusion : 100 * params.stitch_width},
                              {"min_segment_factor", sopt.wales.min_segment_factor},
                              {"refine_reference", sopt.wales.refine_reference},
                              {"distance_tolerance_mm", sopt.wales.distance_tolerance * params.stitch_width}};
      report["seams"] = seams_json(seams);
      report["seams"]["designed_surface"] = {{"vertices", surface.num_vertices()}, {"faces", surface.num_faces()}};
      write_seams_obj(o->outdir, seams);
      report["field"] = field_json;
      if (!tried.empty()) report["field"]["tried"] = tried;
      report["metric"] = {{"total_mm", d.metric.total},
                          {"normalised_per_mm", d.metric.normalised()},
                          {"spreading_mm", d.metric.positive},
                          {"converging_mm", d.metric.negative},
                          {"estimated_transfer_stitches", d.metric.transfer_estimate(params.stitch_width)},
                          {"flat_faces", d.metric.flat_faces}};
      nlohmann::json counts = counts_json(d.counts);
      counts["expected_stitches_area"] = expected;
      counts["stitches_vs_area"] = d.counts.stitches / expected - 1.0;
      counts["courses"] = d.map.rows;
      counts["map_columns"] = d.map.cols;
      counts["strips"] = static_cast<int>(d.wales.strips.size());
      counts["wales"] = static_cast<int>(d.wales.wales.size());
      counts["advances"] = d.wales.steps;
      counts["whole_front_advances"] = d.wales.whole_steps;
      counts["short_wale_advances"] = d.wales.fill_steps;
      counts["refined_references"] = d.wales.refined_steps;
      counts["region_splits"] = d.wales.region_splits;
      counts["dropped_front_pieces"] = d.wales.dropped_pieces;
      counts["dropped_remnants"] = d.wales.dropped_remnants;
      counts["moved_forks"] = d.wales.moved_forks;
      counts["joined_boundary_arcs"] = d.wales.joined_arcs;
      counts["tiny_arcs"] = d.wales.tiny_arcs;
      counts["sampleless_regions"] = d.wales.sampleless_regions;
      counts["pinched_vertices"] = d.wales.pinched_vertices;
      counts["split_vertices"] = d.split_vertices;
      counts["last_strips"] = d.wales.last_strips;
      counts["uncovered_area_mm2"] = d.wales.uncovered_area;
      counts["lambda_growths"] = d.lambda_growths;
      counts["max_lambda_mm"] = d.max_lambda;
      counts["boundary_apex_triangles_to_quads"] = d.boundary_quads.triangles;
      counts["boundary_shaping_to_quads"] = d.boundary_shaping.increases + d.boundary_shaping.decreases;
      counts["boundary_shaping_split_apexes"] = d.boundary_shaping.split_apexes;
      counts["support_stitches"] = d.courses.support_stitches;
      report["counts"] = counts;
      if (optimisation)
        report["optimisation"] = {{"best_b", bvec(optimisation->best)},
                                  {"best_estimated_transfers", optimisation->best_value},
                                  {"evaluations", static_cast<int>(optimisation->history.size())},
                                  {"trust_regions", optimisation->regions},
                                  {"unplaceable_evaluations", optimisation->unplaceable},
                                  {"symmetric", optimisation->symmetric},
                                  {"proxy_faces", optimisation->proxy_faces},
                                  {"seed", o->seed},
                                  {"history", "optimisation.json"},
                                  {"plot", "optimisation.svg"},
                                  {"seconds", optimisation->seconds}};
      report["knittability"] = {{"map", to_json(d.map_check)}, {"stitch_mesh", to_json(d.mesh_check)}};
      Timer tm;
      bool machine_ok = true;
      nlohmann::json machine_check;
      report["machine"] = design_machine_end(o->mach, o->outdir, d.map, d.knittable(), &d.stitch_mesh, machine_ok,
                                             machine_check);
      if (!machine_check.is_null()) report["machine_knittability"] = machine_check;
      const double machine_seconds = tm.seconds();
      report["knittable"] = d.knittable() && machine_ok;
      double compare_seconds = 0.0;
      if (!o->no_compare) {
        note("short-row-only design for the comparison ...");
        Timer tc;
        nlohmann::json c = short_row_comparison(surface, params, !o->no_evaluate, o->mach);
        nlohmann::json ours = counts_json(d.counts);
        if (d.evaluation) ours["distortion_designed"] = scalar_stats_json(d.evaluation->designed_distortion_stats);
        if (report["machine"].contains("knit_time_s")) ours["knit_time_s"] = report["machine"]["knit_time_s"];
        report["comparison"] = {{"short_column", ours}, {"short_row_only", c}};
        compare_seconds = tc.seconds();
      }
      report["seconds"] = {{"load", load_seconds},
                           {"field_or_optimisation", field_seconds},
                           {"metric", d.seconds.metric},
                           {"wales", d.seconds.wales},
                           {"tessellation", d.seconds.tessellation},
                           {"post_processing", d.seconds.post_processing},
                           {"courses", d.seconds.courses},
                           {"map", d.seconds.map},
                           {"knittability", d.seconds.check},
                           {"evaluation", d.seconds.evaluation},
                           {"design_total", d.seconds.total},
                           {"machine", machine_seconds},
                           {"comparison", compare_seconds},
                           {"output", t.seconds() - machine_seconds - compare_seconds}};
      report["seconds"]["total"] = all.seconds();
      write_report_json(out("report.json"), report, o->json);
      if (!o->no_report) {
        write_report_html(o->outdir);
        note("report page -> " + out("report.html"));
      }
      note(fmt::format("{} stitches ({} short-row ends, {} increases + {} decreases = {} transfer stitches; metric "
                       "estimate {:.1f}), {} courses x {} columns; {:.2f} s -> {}",
                       d.counts.stitches, d.counts.short_row_ends, d.counts.increases, d.counts.decreases,
                       d.counts.transfers(), d.metric.transfer_estimate(params.stitch_width), d.map.rows, d.map.cols,
                       all.seconds(), o->outdir));
      for (const std::string& line : shape_notes) note(line);
      if (!d.knittable()) {
        const KnittabilityReport& r = d.map_check.ok() ? d.mesh_check : d.map_check;
        std::fprintf(stderr, "%s", r.text().c_str());
        note("the design is NOT knittable (details in report.json); outputs were written for inspection");
        return 1;
      }
      return machine_exit_code(machine_ok, o->mach.machine);
    };
  });
}

}  // namespace knitforge::cli
