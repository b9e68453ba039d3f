#include "knitforge/design/flatten/dart.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <numeric>

#include <fmt/format.h>

#include "knitforge/geometry/cut_mesh_along_path.h"
#include "knitforge/geometry/geodesic_path.h"
#include "knitforge/geometry/geodesic_source.h"
#include "knitforge/geometry/halfedges.h"
#include "knitforge/geometry/split_mesh_along_path.h"
#include "knitforge/util/errors.h"

namespace knitforge {

double dart_angle_limit(DartOrientation orientation, double stitch_width, double stitch_height) {
  if (!(stitch_width > 0.0) || !(stitch_height > 0.0)) {
    throw InvalidInput("dart_angle_limit: the stitch size must be positive");
  }
  const double ratio = orientation == DartOrientation::Horizontal ? stitch_height / stitch_width
                                                                  : stitch_width / (2.0 * stitch_height);
  return 2.0 * std::atan(ratio) * 180.0 / std::numbers::pi;
}

namespace {

// closest_surface_point() can return coordinates like -3e-17 on an edge;
// geodesic_path() rejects any negative coordinate.
SurfacePoint clean(SurfacePoint p) {
  for (int k = 0; k < 3; ++k) {
    if (p.bary[k] < 1e-14) p.bary[k] = 0.0;
  }
  p.bary /= p.bary.sum();
  return p;
}

// The waypoint as a point of `current` (the input mesh after earlier cuts,
// which keeps the input's vertex indices and positions).
SurfacePoint locate_waypoint(const TriMesh& input, const TriMesh& current, const DartWaypoint& w, size_t dart,
                             size_t k) {
  const std::string where = fmt::format("dart {}, point {}", dart, k);
  if (w.vertex >= 0) {
    if (w.vertex >= input.num_vertices()) {
      throw InvalidInput(fmt::format("{}: \"vertex\" {} is off the surface (the mesh has {} vertices)", where,
                                     w.vertex, input.num_vertices()));
    }
    return clean(surface_point_at_vertex(current, w.vertex));
  }
  Vec3 pos;
  if (w.face >= 0) {
    if (w.face >= input.num_faces()) {
      throw InvalidInput(fmt::format("{}: \"face\" {} is off the surface (the mesh has {} faces)", where,
                                     w.face, input.num_faces()));
    }
    if (!w.bary.allFinite() || w.bary.minCoeff() < -1e-9 || std::abs(w.bary.sum() - 1.0) > 1e-6) {
      throw InvalidInput(fmt::format(
          "{}: \"bary\" ({}, {}, {}) must be non-negative and sum to 1 (the point must lie in the face)",
          where, w.bary.x(), w.bary.y(), w.bary.z()));
    }
    const auto& t = input.faces[w.face];
    pos = w.bary.x() * input.vertices[t[0]] + w.bary.y() * input.vertices[t[1]] +
          w.bary.z() * input.vertices[t[2]];
  } else if (w.has_position) {
    if (!w.position.allFinite()) throw InvalidInput(where + ": \"position\" is not finite");
    pos = w.position;
  } else {
    throw InvalidInput(where + ": give \"vertex\", \"face\" + \"bary\", or \"position\"");
  }
  return clean(closest_surface_point(current, pos));
}

MeshPoint to_mesh_point(const GeodesicPathPoint& p) {
  if (p.is_face_point())
    return MeshPoint::in_face(p.point.face, {p.point.bary.x(), p.point.bary.y(), p.point.bary.z()});
  if (p.is_vertex()) return MeshPoint::at_vertex(p.v0);
  return MeshPoint::on_edge(p.v0, p.v1, p.ratio);
}

void append_path(std::vector<GeodesicPathPoint>& out, const std::vector<GeodesicPathPoint>& piece) {
  for (const auto& p : piece) {
    if (!out.empty() && (out.back().position - p.position).norm() <= 1e-12 * (1.0 + p.position.norm())) {
      continue;
    }
    out.push_back(p);
  }
}

}  // namespace

TriMesh closed_darts_mesh(const CutDarts& cut) {
  if (cut.vertex_class.empty()) return cut.mesh;
  if (cut.vertex_class.size() != cut.mesh.vertices.size()) {
    throw InvalidInput("closed_darts_mesh: one vertex class per vertex of the cut mesh needed");
  }
  TriMesh closed;
  const int k = *std::max_element(cut.vertex_class.begin(), cut.vertex_class.end()) + 1;
  closed.vertices.assign(static_cast<size_t>(k), Vec3::Zero());
  for (size_t v = 0; v < cut.mesh.vertices.size(); ++v)
    closed.vertices[static_cast<size_t>(cut.vertex_class[v])] = cut.mesh.vertices[v];
  closed.faces.reserve(cut.mesh.faces.size());
  for (const auto& t : cut.mesh.faces)
    closed.faces.push_back({cut.vertex_class[t[0]], cut.vertex_class[t[1]], cut.vertex_class[t[2]]});
  return closed;
}

CutDarts cut_darts(const TriMesh& mesh, const std::vector<DartSpec>& darts) {
  CutDarts out;
  out.mesh = mesh;
  for (size_t i = 0; i < darts.size(); ++i) append_dart(out, mesh, darts[i]);
  return out;
}

void append_dart(CutDarts& out, const TriMesh& mesh, const DartSpec& spec) {
  const size_t i = out.darts.size();
  {
    const size_t min_points = spec.to_boundary ? 1 : 2;
    if (spec.points.size() < min_points) {
      throw InvalidInput(
          fmt::format("dart {}: \"points\" has {} point(s); give at least {} (or set \"to_boundary\" for a "
                      "one-end dart from one inner point)",
                      i, spec.points.size(), min_points));
    }
    if (spec.to_boundary && spec.type == DartType::TwoEnd) {
      throw InvalidInput(fmt::format("dart {}: \"to_boundary\" is only for one-end darts", i));
    }
    const TriMesh& current = out.mesh;
    std::vector<SurfacePoint> sp;
    for (size_t k = 0; k < spec.points.size(); ++k)
      sp.push_back(locate_waypoint(mesh, current, spec.points[k], i, k));
    if (spec.to_boundary) {
      // The closest point of the input's boundary (not of earlier darts'
      // slits), reached on the current mesh by a shortest path.
      const SurfacePoint start = locate_waypoint(mesh, mesh, spec.points[0], i, 0);
      const Vec3 end = geodesic_path_to_boundary(mesh, start).points.back().position;
      sp.insert(sp.begin(), clean(closest_surface_point(current, end)));
    }
    std::vector<GeodesicPathPoint> gp;
    for (size_t k = 0; k + 1 < sp.size(); ++k) {
      // The exact propagation is much slower from a boundary point, so the
      // first piece of a one-end dart (which starts there) is traced back.
      if (k == 0 && spec.type == DartType::OneEnd) {
        auto piece = geodesic_path(current, sp[k + 1], sp[k]).points;
        std::reverse(piece.begin(), piece.end());
        append_path(gp, piece);
      } else {
        append_path(gp, geodesic_path(current, sp[k], sp[k + 1]).points);
      }
    }
    if (gp.size() < 2) {
      throw InvalidInput(fmt::format("dart {}: its points coincide; give points apart on the surface", i));
    }
    std::vector<MeshPoint> mp;
    mp.reserve(gp.size());
    for (const auto& p : gp) mp.push_back(to_mesh_point(p));
    SplitMeshResult split = split_mesh_along_path(current, mp);
    if (out.vertex_class.size() != current.vertices.size()) {
      out.vertex_class.resize(current.vertices.size());
      std::iota(out.vertex_class.begin(), out.vertex_class.end(), 0);
    }
    std::vector<int> split_class = out.vertex_class;
    int num_classes = split_class.empty() ? 0 : *std::max_element(split_class.begin(), split_class.end()) + 1;
    while (split_class.size() < split.mesh.vertices.size()) split_class.push_back(num_classes++);
    std::vector<int> path = split.path;
    if (path.size() < 2) {
      throw InvalidInput(fmt::format("dart {}: the path is shorter than the mesh resolution", i));
    }
    const Halfedges he = build_halfedges(split.mesh.num_vertices(), split.mesh.faces);
    if (spec.type == DartType::OneEnd) {
      const bool b0 = he.is_boundary_vertex(path.front());
      const bool b1 = he.is_boundary_vertex(path.back());
      if (b0 && b1) {
        throw InvalidInput(
            fmt::format("dart {}: both ends of the one-end dart are on the boundary; it would cut the piece "
                        "in two. End it inside the surface",
                        i));
      }
      if (!b0 && !b1) {
        throw InvalidInput(fmt::format(
            "dart {}: the one-end dart does not reach the boundary; start it at a boundary vertex "
            "or set \"to_boundary\": true",
            i));
      }
      if (b1) std::reverse(path.begin(), path.end());
      for (size_t k = 1; k < path.size(); ++k) {
        if (he.is_boundary_vertex(path[k])) {
          throw InvalidInput(
              fmt::format("dart {}: the path touches the boundary again at its vertex {} (of {}); move the "
                          "points away from the boundary",
                          i, k, path.size()));
        }
      }
    } else {
      for (size_t k = 0; k < path.size(); ++k) {
        if (he.is_boundary_vertex(path[k])) {
          throw InvalidInput(
              fmt::format("dart {}: the two-end dart touches the boundary (at its path vertex {}); keep both "
                          "ends and the whole path inside the surface",
                          i, k));
        }
      }
      if (path.size() < 3) {
        throw InvalidInput(
            fmt::format("dart {}: the two-end dart spans a single mesh edge; make it longer", i));
      }
    }
    CutMeshResult cut = cut_mesh_along_path(split.mesh, path);
    if (cut.num_components != 1) {
      throw InvalidInput(
          fmt::format("dart {}: cutting along it splits the piece in {} parts", i, cut.num_components));
    }
    DartResult r;
    r.type = spec.type;
    r.orientation = spec.orientation;
    r.path = cut.left;
    for (size_t k = 0; k + 1 < path.size(); ++k) {
      r.length += (split.mesh.vertices[path[k + 1]] - split.mesh.vertices[path[k]]).norm();
    }
    size_t notch = 0;
    if (spec.type == DartType::OneEnd) {
      r.tips = {cut.left.back()};
    } else {
      double acc = 0.0;
      double best = 1e300;
      for (size_t k = 1; k + 1 < path.size(); ++k) {
        acc += (split.mesh.vertices[path[k]] - split.mesh.vertices[path[k - 1]]).norm();
        if (std::abs(acc - 0.5 * r.length) < best) {
          best = std::abs(acc - 0.5 * r.length);
          notch = k;
        }
      }
      r.tips = {cut.left.front(), cut.left.back()};
    }
    r.notch_a = cut.left[notch];
    r.notch_b = cut.right[notch];
    if (r.notch_a < 0 || r.notch_b < 0 || r.notch_a == r.notch_b) {
      throw InvalidInput(fmt::format("dart {}: the path runs along the boundary; it cuts nothing", i));
    }
    out.darts.push_back(std::move(r));
    out.vertex_class.resize(cut.mesh.vertices.size());
    for (size_t v = 0; v < cut.mesh.vertices.size(); ++v)
      out.vertex_class[v] = split_class[static_cast<size_t>(cut.vertex_origin[v])];
    out.mesh = std::move(cut.mesh);
  }
}

}  // namespace knitforge
