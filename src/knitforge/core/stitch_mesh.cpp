#include "knitforge/core/stitch_mesh.h"

namespace knitforge {

std::vector<int> bottom_vertices(const Stitch& s) {
  if (s.type == StitchType::Increase) return {apex_vertex(s)};
  const int k = edge_of_side(s.type, Side::Bottom);
  if (k < 0) return {};
  return {s.v[static_cast<size_t>(k)], s.v[static_cast<size_t>((k + 1) % s.corners())]};
}

std::vector<int> top_vertices(const Stitch& s) {
  if (s.type == StitchType::Decrease) return {apex_vertex(s)};
  const int k = edge_of_side(s.type, Side::Top);
  if (k < 0) return {};
  return {s.v[static_cast<size_t>(k)], s.v[static_cast<size_t>((k + 1) % s.corners())]};
}

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
