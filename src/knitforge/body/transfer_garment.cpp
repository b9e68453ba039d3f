#include "knitforge/body/transfer_garment.h"

#include <cmath>

#include <Eigen/Dense>
#include <fmt/core.h>

#include "knitforge/evaluate/surface_distance.h"
#include "knitforge/util/errors.h"

namespace knitforge {

namespace {

// The frame (f1 - f0, f2 - f0, n) of face f and its origin f0; false when
// the face has (near) zero area.
bool face_frame(const TriMesh& m, int f, Mat3& frame, Vec3& origin) {
  const auto& t = m.faces[static_cast<size_t>(f)];
  const Vec3& a = m.vertices[static_cast<size_t>(t[0])];
  const Vec3 e1 = m.vertices[static_cast<size_t>(t[1])] - a, e2 = m.vertices[static_cast<size_t>(t[2])] - a;
  const Vec3 c = e1.cross(e2);
  const double len = c.norm();
  if (!(len > 1e-12 * std::max(1e-300, e1.squaredNorm() + e2.squaredNorm()))) return false;
  frame.col(0) = e1;
  frame.col(1) = e2;
  frame.col(2) = c / len;
  origin = a;
  return true;
}

}  // namespace

GarmentRig rig_garment(const TriMesh& body_a, const std::vector<Vec3>& garment_vertices) {
  if (body_a.faces.empty()) throw InvalidInput("body transfer: body A has no faces");
  GarmentRig rig;
  rig.body_vertices = body_a.num_vertices();
  rig.body_faces = body_a.num_faces();
  // Faces around each body vertex.
  std::vector<std::vector<int>> ring(static_cast<size_t>(body_a.num_vertices()));
  for (int f = 0; f < body_a.num_faces(); ++f)
    for (int v : body_a.faces[static_cast<size_t>(f)]) ring[static_cast<size_t>(v)].push_back(f);
  const SurfaceBvh bvh(body_a);
  rig.vertices.resize(garment_vertices.size());
  for (size_t i = 0; i < garment_vertices.size(); ++i) {
    const Vec3& v = garment_vertices[i];
    if (!v.allFinite()) throw InvalidInput(fmt::format("body transfer: garment vertex {} is not finite", i));
    const ClosestPoint cp = bvh.closest_point(v);
    const auto& t = body_a.faces[static_cast<size_t>(cp.face)];
    int best = t[0];
    for (int c : t)
      if ((body_a.vertices[static_cast<size_t>(c)] - v).squaredNorm() <
          (body_a.vertices[static_cast<size_t>(best)] - v).squaredNorm())
        best = c;
    GarmentVertexRig& r = rig.vertices[i];
    r.body_vertex = best;
    for (int f : ring[static_cast<size_t>(best)]) {
      Mat3 frame;
      Vec3 origin;
      if (!face_frame(body_a, f, frame, origin)) continue;
      r.faces.push_back(f);
      r.weights.push_back(frame.partialPivLu().solve(v - origin));
    }
    if (r.faces.empty())
      throw InvalidInput(fmt::format("body transfer: garment vertex {}: every face around its closest body vertex {} "
                                     "has zero area",
                                     i, best));
  }
  return rig;
}

std::vector<Vec3> deform_rigged_garment(const GarmentRig& rig, const TriMesh& body_b) {
  if (body_b.num_vertices() != rig.body_vertices || body_b.num_faces() != rig.body_faces)
    throw InvalidInput(fmt::format("body transfer: body B has {} vertices and {} faces, body A {} and {}: the two "
                                   "must be bodies of the same model (same topology)",
                                   body_b.num_vertices(), body_b.num_faces(), rig.body_vertices, rig.body_faces));
  std::vector<Vec3> out(rig.vertices.size());
  for (size_t i = 0; i < rig.vertices.size(); ++i) {
    const GarmentVertexRig& r = rig.vertices[i];
    Vec3 sum = Vec3::Zero();
    int n = 0;
    for (size_t k = 0; k < r.faces.size(); ++k) {
      Mat3 frame;
      Vec3 origin;
      if (!face_frame(body_b, r.faces[k], frame, origin)) continue;  // collapsed on B: the other faces decide
      sum += origin + frame * r.weights[k];
      ++n;
    }
    if (n == 0)
      throw InvalidInput(fmt::format("body transfer: every face around body B's vertex {} has zero area",
                                     r.body_vertex));
    out[i] = sum / static_cast<double>(n);
  }
  return out;
}

TriMesh transfer_garment(const TriMesh& garment, const TriMesh& body_a, const TriMesh& body_b) {
  if (body_a.num_vertices() != body_b.num_vertices() || body_a.faces != body_b.faces)
    throw InvalidInput(fmt::format("body transfer: body A ({} vertices, {} faces) and body B ({} vertices, {} faces) "
                                   "are not bodies of the same model with the same faces",
                                   body_a.num_vertices(), body_a.num_faces(), body_b.num_vertices(),
                                   body_b.num_faces()));
  TriMesh out = garment;
  out.vertices = deform_rigged_garment(rig_garment(body_a, garment.vertices), body_b);
  return out;
}

}  // namespace knitforge
