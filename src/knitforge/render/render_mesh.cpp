#include "knitforge/render/render_mesh.h"

#include <cmath>

#include <fmt/core.h>

#include "knitforge/util/errors.h"

namespace knitforge {

void validate_render_mesh(const RenderMesh& m) {
  const auto nv = m.mesh.vertices.size();
  const auto nf = m.mesh.faces.size();
  const std::string who = m.name.empty() ? std::string("render mesh") : "mesh '" + m.name + "'";
  for (size_t v = 0; v < nv; ++v) {
    if (!m.mesh.vertices[v].allFinite())
      throw InvalidInput(fmt::format("{}: vertex {} is not finite", who, v));
  }
  for (size_t f = 0; f < nf; ++f) {
    for (int i : m.mesh.faces[f]) {
      if (i < 0 || static_cast<size_t>(i) >= nv) {
        throw InvalidInput(
            fmt::format("{}: face {} has vertex index {} out of range [0, {})", who, f, i, nv));
      }
    }
  }
  if (!m.normals.empty() && m.normals.size() != nv) {
    throw InvalidInput(fmt::format("{}: {} normals for {} vertices", who, m.normals.size(), nv));
  }
  if (!m.vertex_colours.empty() && m.vertex_colours.size() != nv) {
    throw InvalidInput(
        fmt::format("{}: {} vertex colours for {} vertices", who, m.vertex_colours.size(), nv));
  }
  if (!m.face_colours.empty() && m.face_colours.size() != nf) {
    throw InvalidInput(fmt::format("{}: {} face colours for {} faces", who, m.face_colours.size(), nf));
  }
  for (size_t l = 0; l < m.lines.size(); ++l) {
    for (int i : m.lines[l]) {
      if (i < 0 || static_cast<size_t>(i) >= nv) {
        throw InvalidInput(
            fmt::format("{}: line {} has vertex index {} out of range [0, {})", who, l, i, nv));
      }
    }
  }
}

}  // namespace knitforge
