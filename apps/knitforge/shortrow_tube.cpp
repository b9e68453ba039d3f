// knitforge shortrow --tube (see shortrow_tube.h).
#include "shortrow_tube.h"

#include <algorithm>
#include <filesystem>
#include <future>

#include <fmt/core.h>
#include <nlohmann/json.hpp>

#include "knitforge/convert/stitch_mesh_to_yarn.h"
#include "knitforge/core/stitch.h"
#include "knitforge/design/tube/design_tube.h"
#include "knitforge/evaluate/scalar_colours.h"
#include "knitforge/io/knittability_json.h"
#include "knitforge/io/knitting_map_csv.h"
#include "knitforge/io/knitting_map_image.h"
#include "knitforge/io/mesh_io.h"
#include "knitforge/io/polyline_obj.h"
#include "knitforge/io/stitch_mesh_ply.h"
#include "knitforge/report/report_html.h"
#include "knitforge/util/timer.h"

namespace knitforge::cli {

void add_tube_flags(CLI::App& cmd, TubeFlags& f) {
  cmd.add_flag("--tube", f.tube,
               "Knit a surface with two boundary loops in the round: closed rounds between the rims, increases "
               "and decreases, a tubular map (docs/tubes.md); without it such a surface is cut open by a seam. "
               "A surface with one boundary loop (a beanie, a sock) is knitted from its rim to its crown and closed "
               "there");
  cmd.add_option("--crown-stitches", f.crown_stitches,
                 "With --tube on a surface with one boundary loop: stitches of the last round, joined in pairs "
                 "across the beds to close the crown (8..64)")
      ->check(CLI::Range(8, 64));
  cmd.add_option(
      "--tube-field", f.tube_field,
      "With --tube: the governing field whose isocurves are the rounds (seed 3.3.8; docs/tubes.md "
      "\"Choosing the field\"): auto (default: the knittable candidate with the lowest divergence "
      "estimate of increases + decreases; harmonic unless another scores at least one stitch lower), "
      "harmonic (0 on one rim, 1 on the other rim or the crown segment), fiedler (the Fiedler vector of "
      "the cotangent Laplacian) or orthogonal (the field orthogonal to it); a forced field that cannot be "
      "knitted in rounds is refused, saying why");
  cmd.add_flag("--no-tube-short-rows", f.no_tube_short_rows,
               "With --tube: plain rounds only, one stitch height apart on average, even where the tube bends "
               "(default: full rounds one stitch height apart on the inside of a bend and wedges of short rows "
               "where the outside lies further apart)");
}

std::optional<TubeCommandOptions> tube_command(const TubeFlags& f, const std::vector<const CLI::Option*>& sheet_only) {
  if (!f.tube) {
    if (f.no_tube_short_rows)
      throw UsageError("--no-tube-short-rows applies to --tube only; leave it out or add --tube");
    if (f.tube_field != "auto")
      throw UsageError("--tube-field applies to --tube only; leave it out or add --tube");
    return std::nullopt;
  }
  for (const CLI::Option* opt : sheet_only)
    if (opt->count() > 0)
      throw UsageError(fmt::format("--tube takes no {}: the rounds follow the field between the rims; leave it out "
                                   "(or drop --tube to knit the surface as a sheet)",
                                   opt->get_name()));
  TubeCommandOptions t;
  t.short_rows = !f.no_tube_short_rows;
  t.crown_stitches = f.crown_stitches;
  try {
    t.field = parse_tube_field(f.tube_field);
  } catch (const InvalidInput& e) {
    throw UsageError(fmt::format("--tube-field: {}", e.what()));
  }
  return t;
}

int run_tube_design(const TubeCommandOptions& o) {
  Timer all;
  const KnitParams params = parse_stitch_size(o.stitch);
  check_output_dir("-o", o.outdir, {o.input});
  std::string description;
  const TriMesh input = load_design_surface(o.input, o.units, o.edge, description, nullptr, nullptr);
  check_surface_stitches(input, description, params, o.max_stitches, 2500.0);
  TubeDesignOptions opt;
  opt.params = params;
  opt.surface_name = description;
  opt.short_rows = o.short_rows;
  auto begun = std::make_shared<int>(0);
  opt.progress = [begun](const std::string& stage) { note(fmt::format("[{:3d} %] {} ...", 100 * (*begun)++ / 5, stage)); };
  opt.crown_stitches = o.crown_stitches;
  opt.field = o.field;
  const TubeDesign d = design_tube(input, opt);
  const bool closed_end = d.map.closed_end;
  const TriMesh& field_mesh = closed_end ? d.cut_surface : input;

  note("writing outputs ...");
  Timer t;
  const std::filesystem::path dir(o.outdir);
  std::filesystem::create_directories(dir);
  auto out = [&](const char* name) { return (dir / name).string(); };
  StitchMeshPlyOptions ply;
  ply.ascii = o.ascii;
  write_stitch_mesh_ply(out("stitch_mesh.ply"), d.stitch_mesh, ply);
  std::future<void> second = std::async(std::launch::async, [&d, &out] {
    write_knitting_map_png(out("knitting_map.png"), d.map);
    write_knitting_map_svg(out("knitting_map.svg"), d.map);
  });
  const bool knittable = d.map_check.ok() && d.mesh_check.ok();
  if (d.mesh_check.ok()) write_yarn_obj(out("yarn.obj"), stitch_mesh_to_yarn(d.stitch_mesh, params));
  write_knitting_map_csv(out("knitting_map.csv"), d.map);
  std::vector<std::vector<Vec3>> rounds;
  for (const RoundCurve& r : d.rounds) {
    rounds.push_back(r.points);
    rounds.back().push_back(r.points.front());
  }
  write_polylines_obj(out("rounds.obj"), rounds);
  {
    MeshWriteOptions w;
    w.ascii = o.ascii;
    for (const Rgb8& c : scalar_colours(d.field.value, 0.0, 1.0)) w.vertex_colours.push_back({c[0], c[1], c[2]});
    write_mesh(out("field.ply"), field_mesh, w);
    const auto [mag, p99] = divergence_magnitude(d.divergence.divergence);
    write_vertex_coloured(out("divergence.ply"), field_mesh, mag, 0.0, p99, o.ascii);
    MeshWriteOptions plain;
    plain.ascii = o.ascii;
    write_mesh(out("target.ply"), input, plain);
  }
  const auto types = count_stitch_types(d.stitch_mesh);
  int off_by_more = 0;
  for (size_t k = 0; k < d.round_stitches.size(); ++k)
    off_by_more += std::abs(d.round_stitches[k] - d.ideal_stitches[k]) > 1 ? 1 : 0;
  const double expected = d.surface_area / (params.stitch_width * params.stitch_height);
  nlohmann::json report;
  report["input"] = {{"surface", description},
                     {"units", o.units},
                     {"vertices", input.num_vertices()},
                     {"faces", input.num_faces()},
                     {"boundary_loops", closed_end ? 1 : 2},
                     {"genus", 0},
                     {"area_mm2", d.surface_area}};
  report["route"] = "tube";
  report["parameters"] = {{"stitch_width_mm", params.stitch_width}, {"stitch_height_mm", params.stitch_height}};
  nlohmann::json candidates = nlohmann::json::array();
  for (const TubeFieldCandidate& c : d.candidates) {
    nlohmann::json j = {{"name", tube_field_name(c.kind)},
                        {"initial_shaping_stitches_estimate", c.initial_estimate},
                        {"knittable", c.knittable}};
    if (c.knittable) {
      j["shaping_stitches_estimate"] = c.estimate;
    } else {
      j["why_not"] = c.why_not;
    }
    candidates.push_back(j);
  }
  report["field"] = {
      {"kind", d.field_kind == TubeFieldKind::Harmonic
                   ? "harmonic, 0 on the start rim, 1 on the end rim (or crown segment)"
                   : std::string(tube_field_name(d.field_kind)) + ", 0 on the start rim, 1 on the end rim"},
      {"chosen", tube_field_name(d.field_kind)},
      {"asked", tube_field_name(o.field)},
      {"candidates", candidates},
      {"fiedler_eigenvalue_per_mm2", d.initial.fiedler_eigenvalue},
      {"orthogonal_gradient_alignment", d.initial.orthogonal_alignment},
      {"start_rim_mm", d.field.start_length},
      {"end_rim_mm", d.field.end_length},
      {"interior_extrema", d.field.interior_extrema},
      {"mean_rim_to_rim_mm", d.levels.mean_length},
      {"divergence",
       {{"of", "the normalised gradient (seed 3.3.8), on the surface the field lives on"},
        {"metric_mm", d.divergence.total},
        {"per_area_per_mm", d.divergence.normalised()},
        {"shaping_stitches_estimate", d.divergence.transfer_estimate(params.stitch_width)},
        {"shaping_stitches_designed", d.increases + d.decreases},
        {"flat_faces", d.divergence.flat_faces}}}};
  report["counts"] = {{"stitches", d.stitch_mesh.num_stitches()},
                      {"quads", types[static_cast<int>(StitchType::Knit)]},
                      {"increases", d.increases},
                      {"decreases", d.decreases},
                      {"short_row_ends", types[static_cast<int>(StitchType::ShortRowLeft)] +
                                             types[static_cast<int>(StitchType::ShortRowRight)]},
                      {"short_rows", d.short_rows},
                      {"short_row_wedges", d.wedges},
                      {"short_row_turns", d.turns},
                      {"expected_stitches_area", expected},
                      {"stitches_vs_area", d.stitch_mesh.num_stitches() / expected - 1.0},
                      {"rounds", static_cast<int>(d.rounds.size())},
                      {"courses", d.map.rows},
                      {"map_columns", d.map.cols},
                      {"round_stitches", d.round_stitches},
                      {"ideal_round_stitches", d.ideal_stitches},
                      {"rounds_off_ideal_by_more_than_1", off_by_more}};
  auto side = [](const SideSpacing& s) {
    return nlohmann::json{{"stitches", s.stitches}, {"min_height_over_sh", s.min}, {"max_height_over_sh", s.max},
                          {"taller_than_1_25_sh", s.taller}};
  };
  report["course_spacing"] = {{"short_rows", o.short_rows},
                              {"bend_ratio", d.bend_ratio},
                              {"inside", side(d.course_spacing.inside)},
                              {"outside", side(d.course_spacing.outside)},
                              {"all", side(d.course_spacing.all)}};
  report["knittability"] = {{"map", to_json(d.map_check)}, {"stitch_mesh", to_json(d.mesh_check)}};
  // The converged predicted shape against the whole surface (a closed
  // tube's crown cap included), as the sheet routes report it; none for a
  // design that cannot be knitted (report_design_shape() still removes a
  // predicted.ply an earlier run left in the directory).
  DesignPredictOptions predict = o.predict;
  predict.skip = predict.skip || !knittable;
  const std::vector<std::string> shape_notes =
      report_design_shape(report, predict, o.no_evaluate, o.outdir, d.stitch_mesh, params, input, nullptr, o.ascii);
  const int pairs = closed_end ? static_cast<int>(closing_pairs(d.map).size()) : 0;
  if (closed_end)
    report["closed_end"] = {{"crown_stitches", d.round_stitches.back()},
                            {"closing_pairs", pairs},
                            {"rim_to_crown_mm", d.rim_to_crown},
                            {"crown_cap_radius_mm", d.crown_radius},
                            {"crown_cap_area_mm2", d.crown_area},
                            {"crown_segment_mm", d.crown_segment},
                            {"crown_ring_mm", d.crown_ring},
                            {"crown_segment_direction_degrees", d.crown_direction},
                            {"crown_direction_shaping_estimates", d.crown_direction_scores}};
  Timer tm;
  bool machine_ok = true;
  nlohmann::json machine_check;
  report["machine"] = design_machine_end(o.mach, o.outdir, d.map, knittable, &d.stitch_mesh, machine_ok, machine_check);
  if (!machine_check.is_null()) report["machine_knittability"] = machine_check;
  const double machine_seconds = tm.seconds();
  report["knittable"] = knittable && machine_ok;
  second.get();
  report["seconds"] = {{"field", d.seconds.field},       {"rounds", d.seconds.rounds},
                       {"tessellation", d.seconds.tessellation}, {"map", d.seconds.map},
                       {"knittability", d.seconds.check}, {"design_total", d.seconds.total},
                       {"machine", machine_seconds},      {"output", t.seconds() - machine_seconds}};
  report["seconds"]["total"] = all.seconds();
  write_report_json(out("report.json"), report, o.json);
  if (!o.no_report) {
    write_report_html(o.outdir);
    note("report page -> " + out("report.html"));
  }
  note(fmt::format("tube: {} stitches in {} courses ({} rounds) x {} columns ({} to {} stitches round), {} increases, {} "
                   "decreases; {:.2f} s -> {}",
                   d.stitch_mesh.num_stitches(), d.map.rows, static_cast<int>(d.rounds.size()) - 1, d.map.cols, d.round_stitches.front(),
                   d.round_stitches.back(), d.increases, d.decreases, all.seconds(), o.outdir));
  note(fmt::format("tube: {} short rows ({} turns) in {} wedges{}, stitches {:+.1f} % of area / (sw sh); course spacing / sh along the inside of the bend "
                   "{:.2f}..{:.2f}, along the outside {:.2f}..{:.2f}, taller than 1.25 sh: {} of {} stitches (outside / inside rim to rim {:.2f})",
                   d.short_rows, d.turns, d.wedges, o.short_rows ? "" : " (--no-tube-short-rows)",
                   100.0 * (d.stitch_mesh.num_stitches() / expected - 1.0),
                   d.course_spacing.inside.min, d.course_spacing.inside.max, d.course_spacing.outside.min,
                   d.course_spacing.outside.max, d.course_spacing.all.taller, d.course_spacing.all.stitches, d.bend_ratio));
  note(fmt::format("tube: divergence of the field's normalised gradient {:.0f} mm: about {:.0f} shaping stitches "
                   "(estimate; {} increases + decreases designed) -> divergence.ply",
                   d.divergence.total, d.divergence.transfer_estimate(params.stitch_width), d.increases + d.decreases));
  {
    std::string line;
    for (const TubeFieldCandidate& c : d.candidates)
      line += c.knittable
                  ? fmt::format("{}{} {:.0f}", line.empty() ? "" : ", ", tube_field_name(c.kind), c.estimate)
                  : fmt::format("{}{} not knittable", line.empty() ? "" : ", ", tube_field_name(c.kind));
    note(fmt::format("tube: field {} ({}); candidates' shaping estimates: {}", tube_field_name(d.field_kind),
                     o.field == TubeFieldKind::Auto ? "the lowest knittable" : "forced by --tube-field",
                     line));
  }
  if (closed_end)
    note(fmt::format(
        "tube: closed at the crown: last round {} stitches ({} asked; {} pairs joined across the beds "
        "and bound off) along a {:.1f} mm crown segment at {:.0f} degrees (ring {:.1f} mm, slit "
        "{:.1f} mm wide, {:.0f} mm^2), crown {:.1f} mm from the rim",
        d.round_stitches.back(), o.crown_stitches, pairs, d.crown_segment, d.crown_direction, d.crown_ring,
        2.0 * d.crown_radius, d.crown_area, d.rim_to_crown));
  for (const std::string& line : shape_notes) note(line);
  if (!knittable) {
    const KnittabilityReport& r = d.map_check.ok() ? d.mesh_check : d.map_check;
    std::fprintf(stderr, "%s", r.text().c_str());
    note("the design is NOT knittable (details in report.json); outputs were written for inspection");
    return 1;
  }
  return machine_exit_code(machine_ok, o.mach.machine);
}

}  // namespace knitforge::cli
