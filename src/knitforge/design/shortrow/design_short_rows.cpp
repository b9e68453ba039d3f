#include "knitforge/design/shortrow/design_short_rows.h"

#include <cmath>

#include <fmt/format.h>

#include "knitforge/convert/map_knittability.h"
#include "knitforge/convert/stitch_mesh_to_map.h"
#include "knitforge/geometry/geodesic_distance.h"
#include "knitforge/geometry/mesh_measures.h"
#include "knitforge/design/shortrow/finish_stitch_mesh.h"
#include "knitforge/util/errors.h"
#include "knitforge/util/timer.h"

namespace knitforge {

ShortRowDesign design_short_rows(const TriMesh& surface, const GeodesicSource& source,
                                 const ShortRowOptions& options) {
  const Timer total;
  auto stage = [&](const std::string& name) {
    if (options.progress) options.progress(name);
  };
  ShortRowDesign d;
  Timer t;

  stage("seams");
  {
    CutToDiskOptions co;
    co.source = source;
    co.cuts = options.cuts;
    co.seams_on_source = options.seams_on_source;
    co.longest_source_seam = true;
    CutToDisk opened = cut_to_disk(surface, co, options.surface_name);
    d.surface = std::move(opened.mesh);
    d.source = std::move(opened.source);
    d.seams = std::move(opened.seams);
    d.input_boundary_loops = opened.input_boundary_loops;
    d.input_genus = opened.input_genus;
    d.source_on_seam = opened.source_on_seam;
    d.source_seam_candidates = opened.source_seam_candidates;
  }
  d.surface_area = total_area(d.surface);
  d.seconds.seams = t.seconds();

  stage("geodesic field");
  t.reset();
  if (!(std::isfinite(options.field_tolerance) && options.field_tolerance >= 0)) {
    throw InvalidInput(fmt::format("short-row design: field tolerance {} must be finite and >= 0",
                                   options.field_tolerance));
  }
  GeodesicOptions field_options;
  field_options.tolerance = options.field_tolerance * options.params.stitch_width;
  const GeodesicField field = geodesic_distance(d.surface, d.source, field_options);
  d.field = field.distance;
  d.field_signed = field.is_signed;
  d.field_windows = field.num_windows;
  d.field_approximate = field.approximate;
  d.seconds.field = t.seconds();

  stage("wale curves");
  t.reset();
  d.wales = compute_wale_curves(d.surface, d.field, options.params, options.wales);
  d.seconds.wales = t.seconds();

  stage("tessellation");
  t.reset();
  WaleTessellation tess = tessellate_wales(d.wales, options.params, options.tessellation);
  d.strips = tess.num_strips;
  d.unpaired_pieces = tess.unpaired_pieces;
  d.lambda_growths = tess.lambda_growths;
  d.max_lambda = tess.max_lambda;
  for (char end : tess.apex_on_wale_end) d.interior_apexes += end ? 0 : 1;
  d.stitch_mesh = std::move(tess.mesh);
  d.seconds.tessellation = t.seconds();

  stage("post-processing");
  t.reset();
  remove_unused_vertices(d.stitch_mesh);
  d.split_vertices = split_touching_vertices(d.stitch_mesh);
  d.boundary_quads = boundary_apex_quads(d.stitch_mesh);
  d.seconds.post_processing = t.seconds();

  map_stages_into(d, options.params, "short-row design", stage);
  d.apex_spacing = apex_spacing(d.stitch_mesh);

  if (options.evaluate) {
    stage("evaluation");
    t.reset();
    d.evaluation = evaluate_stitch_mesh(d.stitch_mesh, d.surface, options.params, options.evaluation);
    d.seconds.evaluation = t.seconds();
  }
  d.seconds.total = total.seconds();
  return d;
}

}  // namespace knitforge
