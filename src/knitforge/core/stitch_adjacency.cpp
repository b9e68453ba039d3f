#include "knitforge/core/stitch_adjacency.h"

#include <fmt/core.h>

#include "knitforge/util/errors.h"

namespace knitforge {

StitchAdjacency::StitchAdjacency(const StitchMesh& mesh) : mesh_(&mesh) {
  const int n = mesh.num_stitches();
  std::vector<int> start(n + 1, 0);
  std::vector<int> verts;
  verts.reserve(4 * static_cast<size_t>(n));
  for (int s = 0; s < n; ++s) {
    const Stitch& st = mesh.stitches[s];
    if (static_cast<int>(st.type) >= kNumStitchTypes) {
      throw TopologyError(fmt::format("stitch {} has an unknown type {}", s, static_cast<int>(st.type)));
    }
    if (st.direction != 1 && st.direction != -1) {
      throw TopologyError(fmt::format("stitch {} has direction {}; it must be +1 or -1", s, st.direction));
    }
    const int k = st.corners();
    for (int i = 0; i < k; ++i) verts.push_back(st.v[i]);
    if (k == 3 && st.v[3] != -1) {
      throw TopologyError(fmt::format("stitch {} is a {} (a triangle) but lists a fourth vertex {}", s,
                                      name(st.type), st.v[3]));
    }
    start[s + 1] = static_cast<int>(verts.size());
  }
  he_ = build_halfedges(mesh.num_vertices(), start, verts);
  nb_.assign(4 * static_cast<size_t>(n), -1);
  nb_side_.assign(4 * static_cast<size_t>(n), Side::Bottom);
  for (int s = 0; s < n; ++s) {
    const auto sides = edge_sides(mesh.stitches[s].type);
    for (int k = 0; k < static_cast<int>(sides.size()); ++k) {
      const int o = he_.opposite(he_.halfedge(s, k));
      if (o < 0) continue;
      const int t = he_.face(o);
      nb_[4 * s + static_cast<int>(sides[k])] = t;
      nb_side_[4 * s + static_cast<int>(sides[k])] = edge_sides(mesh.stitches[t].type)[he_.corner(o)];
    }
  }
}

int StitchAdjacency::next_in_course(int s) const {
  const Side side = mesh_->stitches[s].direction > 0 ? Side::Right : Side::Left;
  const int t = neighbor(s, side);
  if (t < 0 || neighbor_side(s, side) != opposite_side(side)) return -1;
  return t;
}

int StitchAdjacency::previous_in_course(int s) const {
  const Side side = mesh_->stitches[s].direction > 0 ? Side::Left : Side::Right;
  const int t = neighbor(s, side);
  if (t < 0 || neighbor_side(s, side) != opposite_side(side)) return -1;
  return t;
}

int StitchAdjacency::next_stitch(int s) const {
  const int t = next_in_course(s);
  if (t >= 0) return t;
  const int up = neighbor(s, Side::Top);
  if (up < 0 || neighbor_side(s, Side::Top) != Side::Bottom) return -1;
  return previous_in_course(up) < 0 ? up : -1;
}

int StitchAdjacency::previous_stitch(int s) const {
  const int t = previous_in_course(s);
  if (t >= 0) return t;
  const int down = neighbor(s, Side::Bottom);
  if (down < 0 || neighbor_side(s, Side::Bottom) != Side::Top) return -1;
  return next_in_course(down) < 0 ? down : -1;
}

}  // namespace knitforge
