#include "knitforge/design/shortrow/finish_stitch_mesh.h"

#include <fmt/format.h>

#include "knitforge/convert/map_knittability.h"
#include "knitforge/convert/stitch_mesh_to_map.h"
#include "knitforge/geometry/split_nonmanifold_vertices.h"
#include "knitforge/util/errors.h"
#include "knitforge/util/timer.h"

namespace knitforge {

int split_touching_vertices(StitchMesh& mesh) {
  std::vector<int> start{0}, corners;
  for (const Stitch& s : mesh.stitches) {
    for (int k = 0; k < s.corners(); ++k) corners.push_back(s.v[k]);
    start.push_back(static_cast<int>(corners.size()));
  }
  const VertexFanSplit split = split_nonmanifold_vertices(mesh.num_vertices(), start, corners);
  if (split.num_split == 0) return 0;
  for (size_t v = mesh.vertices.size(); v < split.vertex_origin.size(); ++v)
    mesh.vertices.push_back(mesh.vertices[split.vertex_origin[v]]);
  for (int s = 0; s < mesh.num_stitches(); ++s) {
    Stitch& st = mesh.stitches[s];
    for (int k = 0; k < st.corners(); ++k) st.v[k] = split.face_vertices[start[s] + k];
  }
  return split.num_split;
}

MapStages courses_map_and_checks(StitchMesh& mesh, const KnitParams& params, const std::string& route,
                                 const std::function<void(const std::string&)>& stage) {
  auto begin = [&](const char* name) {
    if (stage) stage(name);
  };
  MapStages r;
  Timer t;
  begin("courses");
  r.courses = order_courses(mesh);
  r.seconds_courses = t.seconds();

  begin("knitting map");
  t.reset();
  try {
    r.map = stitch_mesh_to_map(mesh);
  } catch (const InvalidInput& e) {
    throw InvalidInput(fmt::format("{}: the stitch mesh cannot be laid out as a knitting map: {}", route, e.what()));
  }
  r.seconds_map = t.seconds();

  begin("knittability");
  t.reset();
  r.mesh_check = check_knittability(mesh);
  r.map_check = check_knittability(r.map, params);
  r.seconds_check = t.seconds();
  return r;
}

}  // namespace knitforge
