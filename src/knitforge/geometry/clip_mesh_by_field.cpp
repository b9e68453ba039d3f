#include "knitforge/geometry/clip_mesh_by_field.h"

#include <cmath>
#include <cstdint>
#include <unordered_map>

#include <fmt/core.h>

#include "knitforge/geometry/edge_key.h"
#include "knitforge/util/errors.h"

namespace knitforge {

namespace {

bool strict_sign_change(double fa, double fb) { return (fa > 0.0 && fb < 0.0) || (fa < 0.0 && fb > 0.0); }

}  // namespace

ClippedMesh clip_mesh_by_field(const TriMesh& mesh, const std::vector<double>& field, const ClipFieldOptions& options) {
  const int V = mesh.num_vertices();
  if (static_cast<int>(field.size()) != V)
    throw InvalidInput(fmt::format("clip_mesh_by_field: {} field values for {} vertices", field.size(), V));
  if (!(options.snap_fraction >= 0.0 && options.snap_fraction < 0.5))
    throw InvalidInput(fmt::format("clip_mesh_by_field: snap fraction {} must be in [0, 0.5)", options.snap_fraction));
  for (int i = 0; i < V; ++i)
    if (!std::isfinite(field[static_cast<size_t>(i)]))
      throw InvalidInput(fmt::format("clip_mesh_by_field: the field at vertex {} is not finite", i));
  for (size_t f = 0; f < mesh.faces.size(); ++f)
    for (int v : mesh.faces[f])
      if (v < 0 || v >= V) throw InvalidInput(fmt::format("clip_mesh_by_field: face {} has vertex {} out of range", f, v));

  std::vector<Vec3> pos = mesh.vertices;
  std::vector<double> val = field;

  // 1. Snapping: each vertex to its nearest crossing within the fraction.
  std::vector<double> snap_dist(static_cast<size_t>(V), -1.0);
  std::vector<Vec3> snap_to(static_cast<size_t>(V), Vec3::Zero());
  auto offer = [&](int v, const Vec3& p, double d) {
    double& best = snap_dist[static_cast<size_t>(v)];
    if (best < 0.0 || d < best) {
      best = d;
      snap_to[static_cast<size_t>(v)] = p;
    }
  };
  for (const auto& t : mesh.faces) {
    for (int k = 0; k < 3; ++k) {
      const int a = t[static_cast<size_t>(k)], b = t[static_cast<size_t>((k + 1) % 3)];
      const double fa = field[static_cast<size_t>(a)], fb = field[static_cast<size_t>(b)];
      if (!strict_sign_change(fa, fb)) continue;
      const double s = fa / (fa - fb);  // from a to b
      const Vec3 p = mesh.vertices[static_cast<size_t>(a)] +
                     s * (mesh.vertices[static_cast<size_t>(b)] - mesh.vertices[static_cast<size_t>(a)]);
      const double len = (mesh.vertices[static_cast<size_t>(b)] - mesh.vertices[static_cast<size_t>(a)]).norm();
      if (s < options.snap_fraction) offer(a, p, s * len);
      if (1.0 - s < options.snap_fraction) offer(b, p, (1.0 - s) * len);
    }
  }
  ClippedMesh out;
  for (int v = 0; v < V; ++v) {
    if (snap_dist[static_cast<size_t>(v)] < 0.0) continue;
    pos[static_cast<size_t>(v)] = snap_to[static_cast<size_t>(v)];
    val[static_cast<size_t>(v)] = 0.0;
    ++out.snapped_vertices;
  }

  // 2. Clipping.
  std::vector<Vec3> verts = pos;
  std::vector<int> origin(static_cast<size_t>(V));
  for (int v = 0; v < V; ++v) origin[static_cast<size_t>(v)] = v;
  std::unordered_map<std::uint64_t, int> crossing;
  auto cross = [&](int a, int b) {
    const auto [it, fresh] = crossing.try_emplace(undirected_edge_key(a, b), static_cast<int>(verts.size()));
    if (fresh) {
      const double fa = val[static_cast<size_t>(a)], fb = val[static_cast<size_t>(b)];
      const double s = fa / (fa - fb);
      verts.push_back(pos[static_cast<size_t>(a)] + s * (pos[static_cast<size_t>(b)] - pos[static_cast<size_t>(a)]));
      origin.push_back(-1);
    }
    return it->second;
  };
  std::vector<std::array<int, 3>> faces;
  for (const auto& t : mesh.faces) {
    bool positive = false;
    for (int v : t) positive = positive || val[static_cast<size_t>(v)] > 0.0;
    if (!positive) continue;
    int poly[4];
    int n = 0;
    for (int k = 0; k < 3; ++k) {
      const int a = t[static_cast<size_t>(k)], b = t[static_cast<size_t>((k + 1) % 3)];
      const double fa = val[static_cast<size_t>(a)], fb = val[static_cast<size_t>(b)];
      if (fa >= 0.0) poly[n++] = a;
      if (strict_sign_change(fa, fb)) poly[n++] = cross(a, b);
    }
    if (n == 3) {
      faces.push_back({poly[0], poly[1], poly[2]});
    } else if (n == 4) {
      auto at = [&](int k) { return verts[static_cast<size_t>(poly[k])]; };
      if ((at(0) - at(2)).squaredNorm() <= (at(1) - at(3)).squaredNorm()) {
        faces.push_back({poly[0], poly[1], poly[2]});
        faces.push_back({poly[0], poly[2], poly[3]});
      } else {
        faces.push_back({poly[1], poly[2], poly[3]});
        faces.push_back({poly[1], poly[3], poly[0]});
      }
    }
  }

  // 3. Drop unused vertices, keeping the order.
  std::vector<int> map(verts.size(), -1);
  for (const auto& f : faces)
    for (int v : f) map[static_cast<size_t>(v)] = 0;
  for (size_t v = 0; v < verts.size(); ++v) {
    if (map[v] < 0) continue;
    map[v] = static_cast<int>(out.mesh.vertices.size());
    out.mesh.vertices.push_back(verts[v]);
    out.vertex_origin.push_back(origin[v]);
  }
  out.mesh.faces.reserve(faces.size());
  for (const auto& f : faces)
    out.mesh.faces.push_back({map[static_cast<size_t>(f[0])], map[static_cast<size_t>(f[1])], map[static_cast<size_t>(f[2])]});
  return out;
}

}  // namespace knitforge
