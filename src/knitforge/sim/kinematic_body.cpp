#include "knitforge/sim/kinematic_body.h"

#include <algorithm>
#include <cmath>

#include <fmt/core.h>

#include "knitforge/util/errors.h"
#include "knitforge/util/union_find.h"

namespace knitforge {

Mat3 face_frame(const TriMesh& mesh, const std::vector<Vec3>& positions, int face) {
  const auto& t = mesh.faces[face];
  const Vec3 e = positions[t[1]] - positions[t[0]];
  Mat3 F;
  F.col(0) = e.normalized();
  F.col(2) = e.cross(positions[t[2]] - positions[t[0]]).normalized();
  F.col(1) = F.col(2).cross(F.col(0));
  return F;
}

std::vector<Aabb> face_boxes(const TriMesh& mesh, const std::vector<Vec3>* end) {
  std::vector<Aabb> boxes(mesh.faces.size());
  for (size_t f = 0; f < mesh.faces.size(); ++f) {
    const auto& t = mesh.faces[f];
    boxes[f] = Aabb::of({mesh.vertices[t[0]], mesh.vertices[t[1]], mesh.vertices[t[2]]});
    if (end) boxes[f] = boxes[f].merged(Aabb::of({(*end)[t[0]], (*end)[t[1]], (*end)[t[2]]}));
  }
  return boxes;
}

namespace {

TrianglePoint closest_on_face(const TriMesh& m, int f, const Vec3& p) {
  const auto& t = m.faces[f];
  return closest_triangle_point(p, m.vertices[t[0]], m.vertices[t[1]], m.vertices[t[2]]);
}

}  // namespace

std::vector<int> mesh_component_parts(const TriMesh& mesh, int* count) {
  UnionFind uf(mesh.vertices.size());
  for (const auto& t : mesh.faces) {
    uf.unite(t[0], t[1]);
    uf.unite(t[0], t[2]);
  }
  std::vector<int> label_of_root(mesh.vertices.size(), -1), parts(mesh.faces.size());
  int n = 0;
  for (size_t f = 0; f < mesh.faces.size(); ++f) {
    int& l = label_of_root[uf.find(mesh.faces[f][0])];
    if (l < 0) l = n++;
    parts[f] = l;
  }
  if (count) *count = n;
  return parts;
}

KinematicBody::KinematicBody(TriMesh mesh, std::vector<int> face_parts)
    : mesh_(std::move(mesh)), face_parts_(std::move(face_parts)) {
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
  if (face_parts_.empty()) {
    face_parts_ = mesh_component_parts(mesh_, &num_parts_);
  } else {
    if (static_cast<int>(face_parts_.size()) != mesh_.num_faces()) {
      throw InvalidInput(fmt::format("body: {} part labels for {} faces (one per face)", face_parts_.size(),
                                     mesh_.num_faces()));
    }
    num_parts_ = 0;
    for (int f = 0; f < mesh_.num_faces(); ++f) {
      if (face_parts_[f] < 0 || face_parts_[f] >= mesh_.num_faces()) {
        throw InvalidInput(fmt::format("body: face {} has part {} (parts are 0..P-1)", f, face_parts_[f]));
      }
      num_parts_ = std::max(num_parts_, face_parts_[f] + 1);
    }
    std::vector<char> used(num_parts_, 0);
    for (int l : face_parts_) used[l] = 1;
    for (int l = 0; l < num_parts_; ++l) {
      if (!used[l]) {
        throw InvalidInput(fmt::format("body: part {} has no face (parts are 0..{}, each used)", l, num_parts_ - 1));
      }
    }
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
  return closest_point_of_part_within(p, -1, max_distance);
}

std::vector<BodyPoint> KinematicBody::closest_points_per_part_within(const Vec3& p, double max_distance) const {
  std::vector<BodyPoint> out;
  if (empty()) return out;
  if (num_parts_ == 1) {
    if (auto q = closest_point_within(p, max_distance)) out.push_back(*q);
    return out;
  }
  // Every face within the bound is visited (the bound is not lowered: a
  // near point of one part says nothing about the others); the best per part
  // is kept in a short list, sorted by part at the end.
  const double limit2 = max_distance * max_distance;
  tree_.nearest(p, limit2, [&](int f, double&) {
    const TrianglePoint q = closest_on_face(mesh_, f, p);
    const double d2 = (q.point - p).squaredNorm();
    if (d2 > limit2) return;
    const int part = face_parts_[f];
    auto it = std::find_if(out.begin(), out.end(), [&](const BodyPoint& b) { return b.part == part; });
    if (it == out.end()) {
      out.push_back({f, part, q, d2});
    } else if (d2 < it->distance2 || (d2 == it->distance2 && f < it->face)) {
      *it = {f, part, q, d2};
    }
  });
  std::sort(out.begin(), out.end(), [](const BodyPoint& a, const BodyPoint& b) { return a.part < b.part; });
  return out;
}

std::optional<BodyPoint> KinematicBody::closest_point_of_part_within(const Vec3& p, int part,
                                                                     double max_distance) const {
  if (empty()) return std::nullopt;
  BodyPoint best;
  bool found = false;
  tree_.nearest(p, max_distance * max_distance, [&](int f, double& bound2) {
    if (part >= 0 && face_parts_[f] != part) return;
    const TrianglePoint q = closest_on_face(mesh_, f, p);
    const double d2 = (q.point - p).squaredNorm();
    if (d2 < bound2 || (d2 == bound2 && (!found || f < best.face))) {
      bound2 = d2;
      best = {f, face_parts_[f], q, d2};
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
