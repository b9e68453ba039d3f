#include "knitforge/geometry/thicken_surface.h"

#include <cmath>

#include <fmt/core.h>

#include "knitforge/geometry/halfedges.h"
#include "knitforge/util/errors.h"

namespace knitforge {

namespace {

void check_finite(const TriMesh& mesh, const char* what) {
  for (int v = 0; v < mesh.num_vertices(); ++v) {
    if (!mesh.vertices[v].allFinite()) {
      throw InvalidInput(fmt::format("{}: vertex {} has a non-finite coordinate", what, v));
    }
  }
  for (int f = 0; f < mesh.num_faces(); ++f) {
    for (int v : mesh.faces[f]) {
      if (v < 0 || v >= mesh.num_vertices()) {
        throw InvalidInput(
            fmt::format("{}: face {} uses vertex {}, outside [0, {})", what, f, v, mesh.num_vertices()));
      }
    }
  }
}

Vec3 area_vector(const TriMesh& m, const std::array<int, 3>& t) {
  return (m.vertices[t[1]] - m.vertices[t[0]]).cross(m.vertices[t[2]] - m.vertices[t[0]]);
}

/// True when offsetting turned the face inside out: its area vector or one
/// of its edges reversed direction (the offset passed a focal point; a
/// sphere offset inwards beyond its radius keeps its area vectors but
/// reverses every edge).
bool turned_over(const TriMesh& before, const TriMesh& after, const std::array<int, 3>& t0,
                 const std::array<int, 3>& t1) {
  if (area_vector(before, t0).dot(area_vector(after, t1)) < 0.0) return true;
  for (int k = 0; k < 3; ++k) {
    const Vec3 e0 = before.vertices[t0[(k + 1) % 3]] - before.vertices[t0[k]];
    const Vec3 e1 = after.vertices[t1[(k + 1) % 3]] - after.vertices[t1[k]];
    if (e0.dot(e1) < 0.0) return true;
  }
  return false;
}

}  // namespace

std::vector<Vec3> offset_normals(const TriMesh& mesh, int* fallback_count) {
  check_finite(mesh, "offset_normals");
  const int nv = mesh.num_vertices();
  std::vector<Vec3> weighted(nv, Vec3::Zero()), unit(nv, Vec3::Zero());
  std::vector<double> area(nv, 0.0);
  std::vector<char> used(nv, 0);
  for (const auto& t : mesh.faces) {
    const Vec3 av = area_vector(mesh, t);
    const double len = av.norm();
    for (int v : t) {
      used[v] = 1;
      weighted[v] += av;
      area[v] += len;
      if (len > 0.0) unit[v] += av / len;
    }
  }
  int fallbacks = 0;
  std::vector<Vec3> out(nv, Vec3::Zero());
  for (int v = 0; v < nv; ++v) {
    if (!used[v]) continue;
    const double len = weighted[v].norm();
    if (len > 1e-6 * area[v] && len > 0.0) {
      out[v] = weighted[v] / len;
      continue;
    }
    ++fallbacks;
    const double ulen = unit[v].norm();
    if (!(ulen > 1e-9)) {
      throw InvalidInput(
          fmt::format("offset_normals: the faces around vertex {} cancel out (zero area or folded back on "
                      "themselves), so it has no normal; remove the degenerate faces or remesh the surface",
                      v));
    }
    out[v] = unit[v] / ulen;
  }
  if (fallback_count) *fallback_count = fallbacks;
  return out;
}

TriMesh offset_surface(const TriMesh& mesh, double distance, int* flipped_faces) {
  if (!std::isfinite(distance)) throw InvalidInput("offset_surface: the offset distance is not finite");
  const std::vector<Vec3> normals = offset_normals(mesh);
  TriMesh out = mesh;
  for (int v = 0; v < out.num_vertices(); ++v) out.vertices[v] += distance * normals[v];
  if (flipped_faces) {
    int flipped = 0;
    for (const auto& t : mesh.faces) flipped += turned_over(mesh, out, t, t) ? 1 : 0;
    *flipped_faces = flipped;
  }
  return out;
}

ThickenResult thicken_surface(const TriMesh& surface, const ThickenOptions& options) {
  if (!(std::isfinite(options.thickness) && options.thickness > 0.0)) {
    throw InvalidInput(fmt::format("thicken_surface: the thickness must be positive and finite (got {})",
                                   options.thickness));
  }
  if (surface.faces.empty()) throw InvalidInput("thicken_surface: the surface has no faces");
  check_finite(surface, "thicken_surface");
  const Halfedges he = build_halfedges(surface.num_vertices(), surface.faces);

  // Compact to the used vertices (order kept).
  std::vector<int> index(surface.num_vertices(), -1);
  TriMesh mid;
  for (const auto& t : surface.faces) {
    for (int v : t) {
      if (index[v] < 0) index[v] = 0;
    }
  }
  for (int v = 0; v < surface.num_vertices(); ++v) {
    if (index[v] == 0) {
      index[v] = mid.num_vertices();
      mid.vertices.push_back(surface.vertices[v]);
    }
  }
  for (const auto& t : surface.faces) mid.faces.push_back({index[t[0]], index[t[1]], index[t[2]]});

  ThickenResult result;
  const std::vector<Vec3> normals = offset_normals(mid, &result.fallback_normals);
  double up = 0.0, down = 0.0;
  switch (options.side) {
    case ThickenSide::Both:
      up = down = 0.5 * options.thickness;
      break;
    case ThickenSide::Outside:
      up = options.thickness;
      break;
    case ThickenSide::Inside:
      down = options.thickness;
      break;
  }
  const int nv = mid.num_vertices();
  TriMesh& solid = result.solid;
  solid.vertices.resize(2 * static_cast<std::size_t>(nv));
  for (int v = 0; v < nv; ++v) {
    solid.vertices[v] = mid.vertices[v] + up * normals[v];
    solid.vertices[nv + v] = mid.vertices[v] - down * normals[v];
  }
  for (const auto& t : mid.faces) {
    solid.faces.push_back(t);
    solid.faces.push_back({nv + t[0], nv + t[2], nv + t[1]});
  }
  for (const auto& t : mid.faces) {
    const std::array<int, 3> bottom{nv + t[0], nv + t[1], nv + t[2]};
    if (up > 0.0 && turned_over(mid, solid, t, t)) ++result.flipped_faces;
    if (down > 0.0 && turned_over(mid, solid, t, bottom)) ++result.flipped_faces;
  }
  // Side band: the top layer has half-edge t_k -> t_{k+1} along each boundary
  // loop, the reversed bottom layer b_{k+1} -> b_k; the quad
  // (t_{k+1}, t_k, b_k, b_{k+1}) uses both in the opposite direction.
  for (const auto& loop : he.boundary_loops()) {
    const std::size_t n = loop.size();
    for (std::size_t k = 0; k < n; ++k) {
      const int t0 = index[loop[k]], t1 = index[loop[(k + 1) % n]];
      const int b0 = nv + t0, b1 = nv + t1;
      const double d1 = (solid.vertices[t1] - solid.vertices[b0]).squaredNorm();
      const double d2 = (solid.vertices[t0] - solid.vertices[b1]).squaredNorm();
      if (d1 <= d2) {
        solid.faces.push_back({t1, t0, b0});
        solid.faces.push_back({t1, b0, b1});
      } else {
        solid.faces.push_back({t1, t0, b1});
        solid.faces.push_back({t0, b0, b1});
      }
    }
  }
  return result;
}

}  // namespace knitforge
