#include "knitforge/design/flatten/knit_flattened_pattern.h"

#include "knitforge/convert/map_to_stitch_mesh.h"
#include "knitforge/design/flatten/lift_map_to_surface.h"
#include "knitforge/util/timer.h"

namespace knitforge {

namespace {

// lift_map_to_surface() for a map with bands (RasterizedPattern::
// short_row_holes > 0), whose map rows are not the pattern rows: every
// stitch-mesh vertex goes to the mean pattern position of the grid corners
// the stitches use for it, each corner placed by its cell's
// cell_pattern_row, then to 3D through the pattern triangles.
StitchMesh lift_banded_map(const RasterizedPattern& raster, const TriMesh& mesh, const std::vector<Vec2>& uv,
                           const KnitParams& params) {
  StitchMesh sm = map_to_stitch_mesh_topology(raster.map, params);
  const int cols = raster.map.cols;
  std::vector<Vec2> sum(sm.vertices.size(), Vec2::Zero());
  std::vector<int> count(sm.vertices.size(), 0);
  for (const Stitch& s : sm.stitches) {
    const int r = s.course;
    const int c = s.wale;
    const double y0 = raster.cell_pattern_row[static_cast<size_t>(r) * cols + c] * params.stitch_height;
    auto corner = [&](int dx, int dy) -> Vec2 {
      return Vec2(raster.origin.x() + (c + dx) * params.stitch_width,
                  raster.origin.y() + y0 + dy * params.stitch_height);
    };
    const Vec2 bl = corner(0, 0);
    const Vec2 br = corner(1, 0);
    const Vec2 tr = corner(1, 1);
    const Vec2 tl = corner(0, 1);
    // Grid corners per stitch corner, in the order of core/stitch.h (an
    // apex stands for the two grid corners it merges).
    Vec2 p[4] = {bl, br, tr, tl};
    switch (s.type) {
      case StitchType::Knit:
        break;
      case StitchType::ShortRowLeft:
        p[0] = 0.5 * (bl + tl), p[1] = br, p[2] = tr;
        break;
      case StitchType::ShortRowRight:
        p[0] = bl, p[1] = 0.5 * (br + tr), p[2] = tl;
        break;
      case StitchType::Increase:
        p[0] = 0.5 * (bl + br), p[1] = tr, p[2] = tl;
        break;
      case StitchType::Decrease:
        p[0] = bl, p[1] = br, p[2] = 0.5 * (tr + tl);
        break;
    }
    for (int q = 0; q < s.corners(); ++q) {
      sum[s.v[q]] += p[q];
      ++count[s.v[q]];
    }
  }
  std::vector<Vec2> pts(sm.vertices.size());
  for (size_t v = 0; v < pts.size(); ++v)
    pts[v] = count[v] > 0 ? Vec2(sum[v] / static_cast<double>(count[v])) : raster.origin;
  const std::vector<Vec3> lifted = pattern_points_to_surface(mesh, uv, pts);
  for (size_t v = 0; v < pts.size(); ++v) sm.vertices[v] = lifted[v];
  return sm;
}

}  // namespace

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
  out.designed = out.raster.short_row_holes > 0
                     ? lift_banded_map(out.raster, flattening.mesh, flattening.uv, params)
                     : lift_map_to_surface(out.raster, flattening.mesh, flattening.uv, params);
  out.seconds.lift = timer.seconds();
  if (options.evaluate) {
    timer.reset();
    out.evaluation = evaluate_stitch_mesh(out.designed, target, params, options.evaluation);
    out.seconds.evaluate = timer.seconds();
  }
  return out;
}

}  // namespace knitforge
