#include "knitforge/design/shortcolumn/boundary_shaping_quads.h"

#include "knitforge/core/stitch_adjacency.h"

namespace knitforge {

BoundaryShapingQuadStats boundary_shaping_quads(StitchMesh& mesh) {
  BoundaryShapingQuadStats stats;
  const StitchAdjacency adj(mesh);
  const int n = mesh.num_stitches();
  for (int s = 0; s < n; ++s) {
    Stitch& st = mesh.stitches[s];
    if (st.type != StitchType::Increase && st.type != StitchType::Decrease) continue;
    const int a = apex_vertex(st);
    if (!adj.is_boundary_vertex(a)) continue;
    const bool left = adj.neighbor(s, Side::Left) >= 0;
    const bool right = adj.neighbor(s, Side::Right) >= 0;
    if (left && right) {
      ++stats.left_alone;
      continue;
    }
    const Vec3 p = mesh.vertices[a];
    const int copy = mesh.num_vertices();
    if (st.type == StitchType::Increase) {
      const int tr = st.v[1], tl = st.v[2];
      if (!right) {
        mesh.vertices.push_back(p + mesh.vertices[tr] - mesh.vertices[tl]);
        st.v = {a, copy, tr, tl};
      } else {
        mesh.vertices.push_back(p + mesh.vertices[tl] - mesh.vertices[tr]);
        st.v = {copy, a, tr, tl};
      }
      ++stats.increases;
    } else {
      const int bl = st.v[0], br = st.v[1];
      if (!right) {
        mesh.vertices.push_back(p + mesh.vertices[br] - mesh.vertices[bl]);
        st.v = {bl, br, copy, a};
      } else {
        mesh.vertices.push_back(p + mesh.vertices[bl] - mesh.vertices[br]);
        st.v = {bl, br, a, copy};
      }
      ++stats.decreases;
    }
    st.type = StitchType::Knit;
  }
  return stats;
}

}  // namespace knitforge
