// Example 01: a knitting map becomes a 3D stitch mesh.
//
// Builds the short-row "cup" map, converts it to a stitch mesh (the coarse
// knitting simulation of seed §1.3.2) and relaxes it with Shape-Up, then
// writes the stitch mesh as PLY and prints how deep the cup came out.
//
//   build/examples/example_01_map_to_stitch_mesh [out.ply]
#include <cstdio>

#include "knitforge/convert/map_to_stitch_mesh.h"
#include "knitforge/convert/sample_knitting_map.h"
#include "knitforge/io/stitch_mesh_ply.h"

int main(int argc, char** argv) {
  using namespace knitforge;
  const KnittingMap map = cup_knitting_map();  // 40 wales, 6 turns per side
  const KnitParams params{3.5, 2.8};           // stitch width x height (mm)
  const StitchMesh mesh = map_to_stitch_mesh(map, params);

  double zmin = 1e300, zmax = -1e300;
  for (const Vec3& v : mesh.vertices) {
    zmin = std::min(zmin, v.z());
    zmax = std::max(zmax, v.z());
  }
  std::printf("%d stitches on a %d x %d map; the relaxed cup is %.1f mm deep\n", mesh.num_stitches(),
              map.rows, map.cols, zmax - zmin);
  const char* out = argc > 1 ? argv[1] : "cup_stitch_mesh.ply";
  write_stitch_mesh_ply(out, mesh);
  std::printf("wrote %s\n", out);
  return 0;
}
