#include "knitforge/design/shortcolumn/design_short_columns.h"

#include <fmt/format.h>

#include "knitforge/design/shortcolumn/boundary_shaping_quads.h"
#include "knitforge/design/shortrow/finish_stitch_mesh.h"
#include "knitforge/geometry/mesh_measures.h"
#include "knitforge/util/errors.h"
#include "knitforge/util/timer.h"

namespace knitforge {

ShortColumnCounts count_short_column_stitches(const StitchMesh& mesh) {
  const auto t = count_stitch_types(mesh);
  ShortColumnCounts c;
  c.stitches = mesh.num_stitches();
  c.knit = t[static_cast<int>(StitchType::Knit)];
  c.short_row_ends = t[static_cast<int>(StitchType::ShortRowLeft)] + t[static_cast<int>(StitchType::ShortRowRight)];
  c.increases = t[static_cast<int>(StitchType::Increase)];
  c.decreases = t[static_cast<int>(StitchType::Decrease)];
  return c;
}

ShortColumnDesign design_short_columns(const TriMesh& surface, const std::vector<double>& field,
                                       const ShortColumnOptions& options) {
  const Timer total;
  auto stage = [&](const std::string& name) {
    if (options.progress) options.progress(name);
  };
  ShortColumnDesign d;
  d.field = field;
  d.surface_area = total_area(surface);
  Timer t;

  stage("divergence metric");
  d.metric = divergence_metric(surface, field);
  d.seconds.metric = t.seconds();

  stage("wale curves");
  t.reset();
  d.wales = extract_column_wales(surface, field, options.params, options.wales);
  d.seconds.wales = t.seconds();

  stage("tessellation");
  t.reset();
  ColumnTessellation tess = tessellate_columns(d.wales, options.params, options.tessellation);
  d.lambda_growths = tess.lambda_growths;
  d.max_lambda = tess.max_lambda;
  d.stitch_mesh = std::move(tess.mesh);
  d.seconds.tessellation = t.seconds();

  stage("post-processing");
  t.reset();
  remove_unused_vertices(d.stitch_mesh);
  d.split_vertices = split_touching_vertices(d.stitch_mesh);
  d.boundary_quads = boundary_apex_quads(d.stitch_mesh);
  d.boundary_shaping = boundary_shaping_quads(d.stitch_mesh);
  d.seconds.post_processing = t.seconds();

  map_stages_into(d, options.params, "short-column design", stage);
  d.counts = count_short_column_stitches(d.stitch_mesh);

  if (options.evaluate) {
    stage("evaluation");
    t.reset();
    d.evaluation = evaluate_stitch_mesh(d.stitch_mesh, surface, options.params, options.evaluation);
    d.seconds.evaluation = t.seconds();
  }
  d.seconds.total = total.seconds();
  return d;
}

}  // namespace knitforge
