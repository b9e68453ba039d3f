// knitforge flatten: 3D surface -> 2D pattern with darts -> knitting map
// (seed ch. 2). Parses options, calls the library, writes the files.
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <fmt/core.h>
#include <nlohmann/json.hpp>

#include "cli_common.h"
#include "knitforge/core/stitch.h"
#include "knitforge/design/flatten/dart_hints.h"
#include "knitforge/design/flatten/dart_json.h"
#include "knitforge/design/flatten/flatten_surface.h"
#include "knitforge/design/flatten/knit_flattened_pattern.h"
#include "knitforge/geometry/mesh_measures.h"
#include "knitforge/geometry/shapes.h"
#include "knitforge/geometry/cut_to_disk.h"
#include "knitforge/io/knittability_json.h"
#include "knitforge/io/mesh_io.h"
#include "knitforge/report/report_html.h"
#include "knitforge/io/stitch_mesh_ply.h"
#include "knitforge/util/atomic_file.h"
#include "knitforge/util/timer.h"

namespace knitforge::cli {

namespace {

nlohmann::json distortion_json(const DistortionStats& s) {
  return {{"min_log_sigma", s.min_log_sigma},   {"max_log_sigma", s.max_log_sigma},
          {"mean_log_sigma", s.mean_log_sigma}, {"rms_log_sigma", s.rms_log_sigma},
          {"area_3d_mm2", s.area_3d},           {"area_2d_mm2", s.area_2d},
          {"max_abs_log_sigma", s.max_abs_log_sigma()}, {"flipped_faces", s.flipped_faces}};
}


}  // namespace

void add_flatten_command(CLI::App& app, Action& action) {
  auto* cmd = app.add_subcommand(
      "flatten", "3D surface -> flattened 2D pattern with darts -> knittable knitting map (seed ch. 2)");
  struct Opts {
    std::string input, outdir, stitch = "3.5x2.8", units = "mm", darts, cut;
    int auto_darts = 0;
    double edge = kDefaultShapeEdgeLength, max_stitches = kDefaultMaxStitches;
    bool allow_wide = false, rms_only = false, no_evaluate = false, no_long_rows = false, json = false, ascii = false;
    bool tube = false;
    DesignMachineOptions mach;
    DesignPredictOptions predict;
  };
  auto o = std::make_shared<Opts>();
  const std::string names = shape_name_list();
  cmd->add_option("input", o->input,
                  "Surface mesh (.obj/.ply/.off/.stl), a disk, or a built-in shape: " + names)
      ->required();
  cmd->add_option("-o,--output", o->outdir, "Output directory")->required();
  add_stitch_option(*cmd, o->stitch);
  cmd->add_option("--units", o->units, "Units of the input mesh and of dart positions: mm, cm, m");
  cmd->add_option("--darts", o->darts, "Darts to cut, as JSON (see docs/flatten.md)");
  add_cut_option(*cmd, o->cut);
  cmd->add_option("--auto-darts", o->auto_darts,
                  "Add up to N darts where the distortion is worst, while it goes down")
      ->check(non_negative_number());
  cmd->add_flag("--auto-darts-rms-only", o->rms_only,
                "Keep an automatic dart when it lowers the RMS distortion even if its tip raises the largest "
                "(domes: by default such a dart is not kept)");
  cmd->add_option("--edge", o->edge, "Edge length (mm) of a built-in shape's triangulation")
      ->check(positive_number());
  cmd->add_flag("--allow-wide-darts", o->allow_wide,
                "Accept darts wider than the knittable angle (report them instead of failing)");
  cmd->add_flag("--no-long-rows", o->no_long_rows, "Do not add long rows at the bottom / top of the map");
  cmd->add_flag("--no-evaluate", o->no_evaluate, "Skip the relaxation and shape-error evaluation");
  add_max_stitches_option(*cmd, o->max_stitches);
  cmd->add_flag("--json", o->json, "Print report.json on stdout");
  cmd->add_flag("--ascii", o->ascii, "Write ASCII PLY files instead of binary");
  add_design_machine_options(*cmd, o->mach);
  add_design_predict_options(*cmd, o->predict);
  cmd->add_flag("--tube", o->tube,
                "Refused: a flattened pattern is a sheet; knit a tube in the round with shortrow or shortcolumn --tube");
  cmd->callback([=, &action] {
    action = [=]() -> int {
      if (o->tube)
        throw UsageError("flatten knits a flat pattern (a sheet), not a tube in the round: use `knitforge shortrow " +
                         o->input + " --tube` (or shortcolumn --tube), or drop --tube to flatten it with a seam");
      Timer all;
      const KnitParams params = parse_stitch_size(o->stitch);
      const double scale = unit_scale(o->units);
      check_output_dir("-o", o->outdir, {o->input, o->darts, o->cut});
      Timer t;
      std::string description;
      bool builtin = false;
      const TriMesh input = load_design_surface(o->input, o->units, o->edge, description, &builtin);
      check_surface_stitches(input, description, params, o->max_stitches, 2500.0);
      // A surface that is not a disk is cut into one; its seams prefer the
      // plane x = centre (the symmetry plane of a garment), the longest piece
      // of it between two boundary loops first: on the built-in cap a seam
      // down the back flattens with RMS log sigma 0.085 where one under the
      // chin gives 0.223 (docs/flatten.md).
      CutToDiskOptions seam_options;
      seam_options.longest_source_seam = true;
      if (!o->cut.empty()) seam_options.cuts = read_cuts(o->cut, scale);
      seam_options.source = symmetry_plane_source(input);
      CutToDisk opened = cut_to_disk(input, seam_options, description);
      const TriMesh surface = std::move(opened.mesh);
      const std::vector<Seam> seams = std::move(opened.seams);
      note_seams(seams, opened.input_boundary_loops, opened.input_genus);
      std::vector<DartSpec> darts;
      if (!o->darts.empty()) darts = parse_darts_json(read_text_file(o->darts, "darts file"), o->darts, builtin ? 1.0 : scale);
      const double load_seconds = t.seconds();

      FlattenOptions fo;
      fo.stitch_width = params.stitch_width;
      fo.stitch_height = params.stitch_height;
      fo.enforce_dart_angle = !o->allow_wide;
      // The stage line, repeated with the solver's iteration at most every
      // 2 s while a stage runs long (the fold-free solver on a large panel).
      std::string stage = "[  0 %] flattening without darts";
      Timer since_note;
      fo.progress = [&](const std::string& what) {
        if (since_note.seconds() < 2.0) return;
        note(fmt::format("{}: {} ...", stage, what));
        since_note.reset();
      };
      note(stage + " ...");
      t.reset();
      Flattening plain = flatten_surface(surface, {}, fo);
      const double plain_seconds = t.seconds();
      nlohmann::json sequence = nlohmann::json::array();
      sequence.push_back({{"darts", 0}, {"distortion", distortion_json(plain.stats)}});
      t.reset();
      Flattening flat;
      std::vector<DartHint> added;
      std::string auto_stop;
      std::vector<DartSpec> all_darts = darts;
      if (!darts.empty() || o->auto_darts > 0) {
        stage = fmt::format("[ 25 %] flattening with {} dart(s){}", darts.size(),
                            o->auto_darts > 0 ? fmt::format(", adding up to {} more", o->auto_darts) : "");
        note(stage + " ...");
        since_note.reset();
        DartHintOptions ho;
        ho.require_lower_maximum = !o->rms_only;
        AutoDarts a = add_darts_automatically(surface, darts, o->auto_darts, fo, ho);
        flat = std::move(a.flattening);
        added = std::move(a.added);
        auto_stop = a.stop_reason;
        all_darts = a.darts;
        for (size_t k = 0; k < a.rms_sequence.size(); ++k) {
          const size_t n = darts.size() + k;
          if (n == 0) continue;
          sequence.push_back(
              {{"darts", n}, {"rms_log_sigma", a.rms_sequence[k]}, {"max_abs_log_sigma", a.max_sequence[k]}});
        }
        sequence.back()["distortion"] = distortion_json(flat.stats);
      } else {
        flat = std::move(plain);
      }
      const double darts_seconds = t.seconds();

      note("[ 50 %] rasterising the pattern and checking the map ...");
      KnitPatternOptions ko;
      ko.raster.long_rows = !o->no_long_rows;
      ko.evaluate = !o->no_evaluate;
      const KnitPatternResult k = knit_flattened_pattern(flat, surface, params, ko);

      note("[ 90 %] writing outputs ...");
      t.reset();
      const std::filesystem::path dir(o->outdir);
      std::filesystem::create_directories(dir);
      auto out = [&](const char* name) { return (dir / name).string(); };
      std::vector<Vec2> marks;
      for (const auto& d : flat.darts) {
        marks.push_back(flat.uv[d.notch_a]);
        marks.push_back(flat.uv[d.notch_b]);
      }
      const std::string svg = pattern_svg(flat.mesh, flat.uv, flat.distortion, marks);
      write_file_atomically(out("pattern.svg"), [&](std::ostream& os) { os << svg; });
      MeshWriteOptions coloured;
      coloured.ascii = o->ascii;
      for (const Rgb8& c : distortion_colours(flat.distortion))
        coloured.face_colours.push_back({c[0], c[1], c[2]});
      write_mesh(out("distortion.ply"), flat.mesh, coloured);
      TriMesh pattern;
      pattern.faces = flat.mesh.faces;
      for (const auto& p : flat.uv) pattern.vertices.emplace_back(p.x(), p.y(), 0.0);
      write_mesh(out("flattened.obj"), pattern);
      write_map_by_extension(out("knitting_map.csv"), k.raster.map);
      write_map_by_extension(out("knitting_map.png"), k.raster.map);
      write_map_by_extension(out("knitting_map.svg"), k.raster.map);
      MeshWriteOptions plain_ply;
      plain_ply.ascii = o->ascii;
      write_mesh(out("target.ply"), surface, plain_ply);
      write_seams_obj(o->outdir, seams);
      const std::string darts_text = darts_to_json(all_darts, builtin ? 1.0 : scale);
      write_file_atomically(out("darts.json"), [&](std::ostream& os) { os << darts_text; });
      if (k.knittability.ok()) {
        StitchMeshPlyOptions ply;
        ply.ascii = o->ascii;
        write_stitch_mesh_ply(out("stitch_mesh.ply"), k.designed, ply);
      }

      nlohmann::json report;
      report["input"] = {{"surface", description},
                         {"units", builtin ? std::string("mm") : o->units},
                         {"vertices", input.num_vertices()},
                         {"faces", input.num_faces()},
                         {"boundary_loops", opened.input_boundary_loops},
                         {"genus", opened.input_genus},
                         {"area_mm2", total_area(surface)}};
      report["seams"] = seams_json(seams);
      report["parameters"] = {{"stitch_width_mm", params.stitch_width},
                              {"stitch_height_mm", params.stitch_height},
                              {"darts_file", o->darts},
                              {"auto_darts", o->auto_darts},
                              {"auto_darts_rms_only", o->rms_only},
                              {"allow_wide_darts", o->allow_wide},
                              {"long_rows", !o->no_long_rows},
                              {"arap_tolerance", fo.tolerance},
                              {"arap_max_iterations", fo.max_iterations}};
      report["flattening"] = {{"vertices", flat.mesh.num_vertices()},
                              {"faces", flat.mesh.num_faces()},
                              {"iterations", flat.iterations},
                              {"converged", flat.converged},
                              {"relative_energy", flat.relative_energy},
                              {"flipped_faces", flat.flipped_faces},
                              {"arap_flipped_faces", flat.arap_flipped_faces},
                              {"injective_solver", flat.injective_solver},
                              {"distortion_before_darts", sequence.front()["distortion"]},
                              {"distortion", distortion_json(flat.stats)},
                              {"stitch_max_abs_log_sigma", flat.stitch_max_abs_log_sigma},
                              {"distortion_sequence", sequence}};
      nlohmann::json dl = nlohmann::json::array();
      for (size_t i = 0; i < flat.darts.size(); ++i) {
        const DartResult& d = flat.darts[i];
        nlohmann::json tips = nlohmann::json::array();
        for (int v : d.tips)
          tips.push_back({flat.mesh.vertices[v].x(), flat.mesh.vertices[v].y(), flat.mesh.vertices[v].z()});
        nlohmann::json j = {{"type", std::string(to_string(d.type))},
                            {"orientation", std::string(to_string(d.orientation))},
                            {"automatic", i >= darts.size()},
                            {"length_mm", d.length},
                            {"angle_deg", d.angle_deg},
                            {"angle_limit_deg", d.angle_limit_deg},
                            {"angle_ok", d.angle_ok},
                            {"alignment_error_mm", d.alignment_error},
                            {"notches_2d",
                             {{flat.uv[d.notch_a].x(), flat.uv[d.notch_a].y()},
                              {flat.uv[d.notch_b].x(), flat.uv[d.notch_b].y()}}},
                            {"tips_3d", tips}};
        if (i >= darts.size() && i - darts.size() < added.size())
          j["reason"] = added[i - darts.size()].reason;
        dl.push_back(j);
      }
      report["darts"] = dl;
      if (o->auto_darts > 0) report["auto_darts_stop_reason"] = auto_stop;
      const auto& r = k.raster;
      report["map"] = {{"rows", r.map.rows},
                       {"cols", r.map.cols},
                       {"stitches", r.map.num_stitches()},
                       {"origin_mm", {r.origin.x(), r.origin.y()}},
                       {"bitmap_rows", r.bitmap_rows},
                       {"pattern_cells", r.pattern_cells},
                       {"added_long_rows", r.added_long_rows},
                       {"extended_cells", r.extended_cells},
                       {"filled_gap_cells", r.filled_gap_cells},
                       {"short_row_holes", r.short_row_holes},
                       {"shifted_turns", r.shifted_turns}};
      std::array<int, 7> cells{};
      for (CellType c : r.map.cells) ++cells[static_cast<int>(c)];
      report["map"]["cells"] = {
          {"knit", cells[0]},     {"short_row_left", cells[1]}, {"short_row_right", cells[2]},
          {"increase", cells[3]}, {"decrease", cells[4]},       {"collapsed", cells[5]},
          {"empty", cells[6]}};
      report["knittability"] = to_json(k.knittability);
      Timer tm;
      bool machine_ok = true;
      nlohmann::json machine_check;
      report["machine"] = design_machine_end(o->mach, o->outdir, r.map, k.knittability.ok(),
                                             k.designed.num_stitches() > 0 ? &k.designed : nullptr, machine_ok,
                                             machine_check);
      if (!machine_check.is_null()) report["machine_knittability"] = machine_check;
      const double machine_seconds = tm.seconds();
      report["knittable"] = k.knittability.ok() && machine_ok;
      // The lifted stitch mesh the route evaluated, against the surface it was designed for.
      const std::vector<std::string> shape_notes =
          report_design_shape(report, o->predict, o->no_evaluate, o->outdir, k.designed, params, surface,
                              k.evaluation ? &*k.evaluation : nullptr, o->ascii);
      report["seconds"] = {{"load", load_seconds},
                           {"flatten_without_darts", plain_seconds},
                           {"flatten_with_darts", darts_seconds},
                           {"cut_darts", flat.seconds_cut},
                           {"rasterize", k.seconds.rasterize},
                           {"knittability", k.seconds.check},
                           {"lift", k.seconds.lift},
                           {"evaluation", k.seconds.evaluate},
                           {"machine", machine_seconds},
                           {"output", t.seconds() - machine_seconds}};
      report["seconds"]["total"] = all.seconds();
      write_report_json(out("report.json"), report, o->json);
      write_report_html(o->outdir);

      note(fmt::format(
          "{} dart(s), distortion RMS log sigma {:.4f} -> {:.4f}, largest |log sigma| {:.4f} (at stitch scale "
          "{:.4f}){}; map {} rows x {} columns, {} stitches; {:.2f} s -> {}",
          flat.darts.size(), sequence.front()["distortion"]["rms_log_sigma"].get<double>(),
          flat.stats.rms_log_sigma, flat.stats.max_abs_log_sigma(), flat.stitch_max_abs_log_sigma,
          !flat.injective_solver ? std::string()
          : flat.arap_flipped_faces > 0
              ? fmt::format(" (fold-free solver: ARAP folded {} face(s))", flat.arap_flipped_faces)
              : fmt::format(" (fold-free solver: ARAP's largest was {:.4f})", flat.arap_max_abs_log_sigma),
          r.map.rows, r.map.cols, r.map.num_stitches(), all.seconds(), o->outdir));
      if (o->auto_darts > 0) note("automatic darts: " + auto_stop);
      if (!flat.flipped_faces.empty()) {
        // Cannot happen (the flattening is injective by construction); never reported as a success.
        note(fmt::format("error: {} face(s) are flipped in the pattern (listed in report.json)",
                         flat.flipped_faces.size()));
        return 1;
      }
      for (const std::string& line : shape_notes) note(line);
      if (!k.knittability.ok()) {
        std::fprintf(stderr, "%s", k.knittability.text().c_str());
        note("the map is NOT knittable (details in report.json); outputs were written for inspection");
        return 1;
      }
      return machine_exit_code(machine_ok, o->mach.machine);
    };
  });
}

}  // namespace knitforge::cli
