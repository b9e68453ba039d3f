#include "knitforge/geometry/geodesic_path.h"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "knitforge/geometry/geodesic_propagation.h"
#include "knitforge/util/errors.h"

namespace knitforge {
namespace {

// Reverses the traced points (end -> start) into a path from the start,
// dropping repeated points, and measures it.
GeodesicPath finish(std::vector<GeodesicPathPoint> traced, bool reverse) {
  GeodesicPath path;
  if (reverse) std::reverse(traced.begin(), traced.end());
  for (GeodesicPathPoint& p : traced) {
    if (!path.points.empty() && (p.position - path.points.back().position).norm() == 0.0) {
      // Keep the more specific description (vertex or edge rather than face).
      if (path.points.back().is_face_point() && !p.is_face_point()) path.points.back() = p;
      continue;
    }
    if (!path.points.empty()) path.length += (p.position - path.points.back().position).norm();
    path.points.push_back(p);
  }
  return path;
}

void check_point(const TriMesh& mesh, const SurfacePoint& p, const char* what) {
  if (p.face < 0 || p.face >= mesh.num_faces())
    throw InvalidInput(fmt::format("geodesic path: the {} point is in face {} but the mesh has {} faces",
                                   what, p.face, mesh.num_faces()));
  if (!p.bary.allFinite() || p.bary.minCoeff() < 0.0 || std::abs(p.bary.sum() - 1.0) > 1e-9)
    throw InvalidInput(
        fmt::format("geodesic path: the {} point has barycentric coordinates ({}, {}, {}); they must be >= 0 "
                    "and sum to 1",
                    what, p.bary[0], p.bary[1], p.bary[2]));
}

}  // namespace

GeodesicPath geodesic_path_to_boundary(const TriMesh& mesh, const SurfacePoint& start) {
  const detail::GeodesicGeometry g = detail::build_geodesic_geometry(mesh);
  check_point(mesh, start, "start");
  detail::GeodesicPropagation prop(g, true);
  prop.add_point(start);
  prop.run();
  if (!std::isfinite(prop.boundary_hit().dist))
    throw TopologyError(fmt::format(
        "geodesic path: no boundary is reachable from the start point in face {} (the surface is closed "
        "around it); cut the surface open first",
        start.face));
  GeodesicPath path = finish(prop.trace_boundary(), true);
  return path;
}

GeodesicPath geodesic_path_from_source(const TriMesh& mesh, const GeodesicSource& source,
                                       const std::vector<int>& targets) {
  if (targets.empty()) throw InvalidInput("geodesic path: no target vertex given");
  for (int v : targets)
    if (v < 0 || v >= mesh.num_vertices())
      throw InvalidInput(fmt::format("geodesic path: target vertex {} is out of range (the mesh has {} vertices)", v,
                                     mesh.num_vertices()));
  bool any = false;
  for (const auto& line : source.polylines) any = any || !line.empty();
  if (!any) throw InvalidInput("geodesic path: the source has no points");
  const detail::GeodesicGeometry g = detail::build_geodesic_geometry(mesh);
  detail::GeodesicPropagation prop(g);
  prop.add_source(source);
  prop.run();
  int best = -1;
  for (int v : targets)
    if (std::isfinite(prop.distance()[v]) && (best < 0 || prop.distance()[v] < prop.distance()[best])) best = v;
  if (best < 0)
    throw TopologyError("geodesic path: no target vertex can be reached from the source; they are on different "
                        "components of the surface");
  return finish(prop.trace_vertex(best), true);
}

GeodesicPath geodesic_path(const TriMesh& mesh, const SurfacePoint& from, const SurfacePoint& to) {
  const detail::GeodesicGeometry g = detail::build_geodesic_geometry(mesh);
  check_point(mesh, from, "start");
  check_point(mesh, to, "end");
  detail::GeodesicPropagation prop(g);
  prop.add_point(from);
  prop.run();
  std::vector<GeodesicPathPoint> traced;
  const double d = prop.trace_point(to, &traced);
  if (!std::isfinite(d))
    throw TopologyError(fmt::format(
        "geodesic path: the end point (face {}) cannot be reached from the start point (face {}); they are "
        "on different components of the surface",
        to.face, from.face));
  return finish(std::move(traced), true);
}

}  // namespace knitforge
