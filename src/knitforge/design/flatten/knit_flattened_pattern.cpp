#include "knitforge/design/flatten/knit_flattened_pattern.h"

#include "knitforge/design/flatten/lift_map_to_surface.h"
#include "knitforge/util/timer.h"

namespace knitforge {

KnitPatternResult knit_flattened_pattern(const Flattening& flattening, const TriMesh& target,
                                         const KnitParams& params, const KnitPatternOptions& options) {
  KnitPatternResult out;
  Timer timer;
  out.raster = rasterize_pattern(flattening.mesh, flattening.uv, params, options.raster);
  out.seconds.rasterize = timer.seconds();
  timer.reset();
  out.knittability = check_knittability(out.raster.map, params);
  out.seconds.check = timer.seconds();
  if (!out.knittability.ok()) return out;
  timer.reset();
  out.designed = lift_map_to_surface(out.raster, flattening.mesh, flattening.uv, params);
  out.seconds.lift = timer.seconds();
  if (options.evaluate) {
    timer.reset();
    out.evaluation = evaluate_stitch_mesh(out.designed, target, params, options.evaluation);
    out.seconds.evaluate = timer.seconds();
  }
  return out;
}

}  // namespace knitforge
