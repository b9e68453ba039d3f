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

int remove_unused_vertices(StitchMesh& mesh) {
  std::vector<int> index(static_cast<size_t>(mesh.num_vertices()), -1);
  for (const Stitch& s : mesh.stitches) {
    for (int k = 0; k < s.corners(); ++k) index[static_cast<size_t>(s.v[k])] = 0;
  }
  std::vector<Vec3> kept;
  for (int v = 0; v < mesh.num_vertices(); ++v) {
    if (index[static_cast<size_t>(v)] < 0) continue;
    index[static_cast<size_t>(v)] = static_cast<int>(kept.size());
    kept.push_back(mesh.vertices[static_cast<size_t>(v)]);
  }
  for (Stitch& s : mesh.stitches) {
    for (int k = 0; k < s.corners(); ++k) s.v[k] = index[static_cast<size_t>(s.v[k])];
  }
  const int dropped = mesh.num_vertices() - static_cast<int>(kept.size());
  mesh.vertices = std::move(kept);
  return dropped;
}

}  // namespace knitforge
