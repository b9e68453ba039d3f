#include "knitforge/core/stitch_mesh.h"

namespace knitforge {

Vec3 stitch_centroid(const StitchMesh& mesh, int stitch) {
  const Stitch& s = mesh.stitches[stitch];
  Vec3 c = Vec3::Zero();
  for (int k = 0; k < s.corners(); ++k) c += mesh.vertices[s.v[k]];
  return c / s.corners();
}

std::array<int, kNumStitchTypes> count_stitch_types(const StitchMesh& mesh) {
  std::array<int, kNumStitchTypes> n{};
  for (const Stitch& s : mesh.stitches) ++n[static_cast<int>(s.type)];
  return n;
}

}  // namespace knitforge
