// Example 04: a short-row design, stage by stage (seed §3.2).
//
// A hemisphere, the geodesic field from its symmetry plane, the wale curves,
// the strips between them, the boundary post-processing, the knitting order
// and the knitting map — each stage a call you can stop after
// (design/pipeline.h) — then the map as CSV.
//
//   build/examples/example_04_short_row_design [map.csv]
#include <cstdio>

#include "knitforge/convert/map_knittability.h"
#include "knitforge/convert/stitch_mesh_to_map.h"
#include "knitforge/design/pipeline.h"
#include "knitforge/geometry/geodesic_distance.h"
#include "knitforge/geometry/shapes.h"
#include "knitforge/io/knitting_map_csv.h"

int main(int argc, char** argv) {
  using namespace knitforge;
  const KnitParams params{3.2, 2.2};
  const TriMesh surface = hemisphere(60.0, 3.0);
  const GeodesicSource source = source_from_plane(surface, Vec3(1, 0, 0), 0.0);

  const GeodesicField field = geodesic_distance(surface, source);
  const WaleCurves wales = compute_wale_curves(surface, field.distance, params);
  WaleTessellation strips = tessellate_wales(wales, params);
  StitchMesh mesh = std::move(strips.mesh);
  const BoundaryApexQuadStats quads = boundary_apex_quads(mesh);
  const CourseOrder order = order_courses(mesh);
  const KnittingMap map = stitch_mesh_to_map(mesh);
  const KnittabilityReport check = check_knittability(map, params);

  std::printf("%d wales on %zu levels, %d strips, %zu short-row-end pairs placed\n", wales.num_wales(),
              wales.values.size(), strips.num_strips, strips.apexes.size());
  std::printf("%d boundary triangles became quads, %d support stitches, %d courses\n", quads.triangles,
              order.support_stitches, order.num_courses);
  std::printf("%d stitches, map %d x %d: %s\n", mesh.num_stitches(), map.rows, map.cols,
              check.ok() ? "knittable" : "NOT knittable");
  const char* out = argc > 1 ? argv[1] : "short_row_map.csv";
  write_knitting_map_csv(out, map);
  std::printf("wrote %s\n", out);
  return check.ok() ? 0 : 1;
}
