// Example 03: the yarn model of a design (seed §1.3.3).
//
// Relaxes a random knittable map with short rows and short columns, builds its
// yarn model (a canonical loop per stitch type, deformed into each stitch and
// joined in knitting order) and writes it as OBJ polylines.
//
//   build/examples/example_03_yarn_model [out.obj]
#include <cstdio>

#include "knitforge/convert/map_to_stitch_mesh.h"
#include "knitforge/convert/random_knitting_map.h"
#include "knitforge/convert/stitch_mesh_to_yarn.h"
#include "knitforge/io/polyline_obj.h"

int main(int argc, char** argv) {
  using namespace knitforge;
  RandomMapOptions o;
  o.rows = 30;
  o.cols = 30;
  o.short_row_ends = 12;
  o.short_columns = 3;
  o.seed = 42;
  const KnittingMap map = random_knitting_map(o);
  const KnitParams params{3.5, 2.8};
  const StitchMesh mesh = map_to_stitch_mesh(map, params);
  const YarnModel yarn = stitch_mesh_to_yarn(mesh, params);

  double length = 0;
  const auto& pts = yarn.yarns.front().points;
  for (size_t i = 1; i < pts.size(); ++i) length += (pts[i] - pts[i - 1]).norm();
  std::printf("%d stitches, yarn of %zu points, %.2f m long (%.1f mm per stitch)\n", mesh.num_stitches(),
              pts.size(), length / 1000.0, length / mesh.num_stitches());
  const char* out = argc > 1 ? argv[1] : "yarn.obj";
  write_yarn_obj(out, yarn);
  std::printf("wrote %s\n", out);
  return 0;
}
