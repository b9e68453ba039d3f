#include "knitforge/sim/kinematic_body.h"

#include <cmath>

#include <fmt/core.h>

#include "knitforge/util/errors.h"

namespace knitforge {

std::vector<Aabb> face_boxes(const TriMesh& mesh, const std::vector<Vec3>* end) {
  std::vector<Aabb> boxes(mesh.faces.size());
  for (size_t f = 0; f < mesh.faces.size(); ++f) {
    const auto& t = mesh.faces[f];
    boxes[f] = Aabb::of({mesh.vertices[t[0]], mesh.vertices[t[1]], mesh.vertices[t[2]]});
    if (end) boxes[f] = boxes[f].merged(Aabb::of({(*end)[t[0]], (*end)[t[1]], (*end)[t[2]]}));
  }
  return boxes;
}

KinematicBody::KinematicBody(TriMesh mesh) : mesh_(std::move(mesh)) {
  if (mesh_.faces.empty()) throw InvalidInput("body: the mesh has no faces");
  const int nv = mesh_.num_vertices();
  for (int f = 0; f < mesh_.num_faces(); ++f) {
    for (int k = 0; k < 3; ++k) {
      const int v = mesh_.faces[f][k];
      if (v < 0 || v >= nv) {
        throw InvalidInput(fmt::format("body: face {} corner {} is vertex {} (valid: 0..{})", f, k, v, nv - 1));
      }
    }
  }
  for (int v = 0; v < nv; ++v) {
    if (!mesh_.vertices[v].allFinite()) throw InvalidInput(fmt::format("body: vertex {} is not finite", v));
  }
  tree_ = AabbTree(face_boxes(mesh_));
}

void KinematicBody::move_to(const std::vector<Vec3>& vertices) {
  if (vertices.size() != mesh_.vertices.size()) {
    throw InvalidInput(fmt::format("body: a frame with {} vertices for a body of {} (every frame needs the same mesh)",
                                   vertices.size(), mesh_.vertices.size()));
  }
  for (size_t v = 0; v < vertices.size(); ++v) {
    if (!vertices[v].allFinite()) throw InvalidInput(fmt::format("body: vertex {} of the frame is not finite", v));
  }
  mesh_.vertices = vertices;
  tree_.refit(face_boxes(mesh_));
}

std::optional<BodyPoint> KinematicBody::closest_point_within(const Vec3& p, double max_distance) const {
  if (empty()) return std::nullopt;
  BodyPoint best;
  double best2 = max_distance * max_distance;
  bool found = false;
  tree_.nearest(p, best2, [&](int f, double& bound2) {
    const auto& t = mesh_.faces[f];
    const TrianglePoint q = closest_triangle_point(p, mesh_.vertices[t[0]], mesh_.vertices[t[1]], mesh_.vertices[t[2]]);
    const double d2 = (q.point - p).squaredNorm();
    if (d2 < bound2 || (d2 == bound2 && (!found || f < best.face))) {
      bound2 = d2;
      best = {f, q, d2};
      found = true;
    }
  });
  if (!found) return std::nullopt;
  return best;
}

Vec3 KinematicBody::point(int face, const Vec3& bary) const {
  const auto& t = mesh_.faces[face];
  return bary[0] * mesh_.vertices[t[0]] + bary[1] * mesh_.vertices[t[1]] + bary[2] * mesh_.vertices[t[2]];
}

Vec3 KinematicBody::face_normal(int face) const {
  const auto& t = mesh_.faces[face];
  const Vec3 n = (mesh_.vertices[t[1]] - mesh_.vertices[t[0]]).cross(mesh_.vertices[t[2]] - mesh_.vertices[t[0]]);
  const double l = n.norm();
  return l > 0 ? Vec3(n / l) : Vec3::Zero();
}

}  // namespace knitforge
