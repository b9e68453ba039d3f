#include "knitforge/design/tube/design_tube.h"

#include <fmt/format.h>

#include "knitforge/convert/map_knittability.h"
#include "knitforge/convert/stitch_mesh_to_map.h"
#include "knitforge/geometry/mesh_measures.h"
#include "knitforge/util/errors.h"
#include "knitforge/util/timer.h"

namespace knitforge {

TubeDesign design_tube(const TriMesh& surface, const TubeDesignOptions& options) {
  auto begin = [&](const char* stage) {
    if (options.progress) options.progress(stage);
  };
  Timer all, t;
  TubeDesign d;
  begin("tube field");
  d.field = tube_field(surface, options.surface_name);
  d.surface_area = total_area(surface);
  d.seconds.field = t.seconds();

  begin("rounds");
  t.reset();
  d.levels = round_levels(surface, d.field, options.params.stitch_height);
  d.rounds = tube_round_curves(surface, d.field, d.levels.levels);
  d.seconds.rounds = t.seconds();

  begin("tessellation");
  t.reset();
  RoundsTessellation tess = tessellate_rounds(d.rounds, options.params);
  d.stitch_mesh = std::move(tess.mesh);
  d.round_stitches = std::move(tess.stitches);
  d.ideal_stitches = std::move(tess.ideal);
  d.increases = tess.increases;
  d.decreases = tess.decreases;
  d.seconds.tessellation = t.seconds();

  begin("knitting map");
  t.reset();
  try {
    d.map = stitch_mesh_to_map(d.stitch_mesh);
  } catch (const InvalidInput& e) {
    throw InvalidInput(fmt::format("tube design: the stitch mesh cannot be laid out as a knitting map: {}", e.what()));
  }
  d.seconds.map = t.seconds();

  begin("knittability");
  t.reset();
  KnittabilityOptions closed;
  closed.closed_courses = true;
  d.mesh_check = check_knittability(d.stitch_mesh, closed);
  d.map_check = check_knittability(d.map, options.params);
  d.seconds.check = t.seconds();
  d.seconds.total = all.seconds();
  return d;
}

}  // namespace knitforge
