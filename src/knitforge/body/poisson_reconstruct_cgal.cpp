// poisson_reconstruct() with CGAL's Poisson surface reconstruction
// (declared in poisson_reconstruct.h).
#ifndef CGAL_EIGEN3_ENABLED
#define CGAL_EIGEN3_ENABLED  // CGAL's Poisson solver uses Eigen (found by CMake)
#endif

#include <algorithm>
#include <array>
#include <cmath>
#include <numeric>
#include <utility>
#include <vector>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Random.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/compute_average_spacing.h>
#include <CGAL/poisson_surface_reconstruction.h>
#include <CGAL/property_map.h>
#include <fmt/core.h>

#include "knitforge/body/poisson_reconstruct.h"
#include "knitforge/util/errors.h"
#include "knitforge/util/work_limit.h"

namespace knitforge {

namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = Kernel::Point_3;
using Vector = Kernel::Vector_3;
using PointWithNormal = std::pair<Point, Vector>;

// The mesher hands its facets over from containers ordered by memory
// address, so the same surface comes out in another face (and possibly
// vertex) order from call to call. Canonical order: vertices sorted by
// position, each face rotated to start at its smallest index (orientation
// kept), faces sorted.
TriMesh in_canonical_order(const TriMesh& mesh) {
  std::vector<int> order(mesh.vertices.size());
  std::iota(order.begin(), order.end(), 0);
  const auto key = [&](int i) {
    const Vec3& p = mesh.vertices[static_cast<size_t>(i)];
    return std::array<double, 3>{p.x(), p.y(), p.z()};
  };
  std::sort(order.begin(), order.end(), [&](int a, int b) { return key(a) < key(b); });
  TriMesh out;
  std::vector<int> new_index(mesh.vertices.size());
  for (size_t k = 0; k < order.size(); ++k) {
    new_index[static_cast<size_t>(order[k])] = static_cast<int>(k);
    out.vertices.push_back(mesh.vertices[static_cast<size_t>(order[k])]);
  }
  for (const auto& f : mesh.faces) {
    std::array<int, 3> g{new_index[static_cast<size_t>(f[0])], new_index[static_cast<size_t>(f[1])],
                         new_index[static_cast<size_t>(f[2])]};
    std::rotate(g.begin(), std::min_element(g.begin(), g.end()), g.end());
    out.faces.push_back(g);
  }
  std::sort(out.faces.begin(), out.faces.end());
  return out;
}

}  // namespace

PoissonResult poisson_reconstruct(const OrientedPoints& cloud, const PoissonOptions& o) {
  const size_t n = cloud.points.size();
  if (cloud.normals.size() != n) throw InvalidInput("poisson_reconstruct: every point needs one normal");
  if (n < 10) throw InvalidInput(fmt::format("poisson_reconstruct: {} points; a surface needs at least 10", n));
  check_work({"Poisson reconstruction", static_cast<double>(n), "points", o.max_points, 0.0,
              "average the points on a coarser voxel grid (body fuse --voxel MM)"});
  if (!(o.spacing_mm >= 0.0) || !(o.angle_deg > 0.0) || !(o.radius > 0.0) || !(o.distance > 0.0))
    throw InvalidInput("poisson_reconstruct: spacing >= 0, angle, radius and distance > 0");
  std::vector<PointWithNormal> pts;
  pts.reserve(n);
  for (size_t i = 0; i < n; ++i) {
    const Vec3& p = cloud.points[i];
    const Vec3& q = cloud.normals[i];
    if (!p.allFinite() || !q.allFinite() || !(q.norm() > 0.5))
      throw InvalidInput(fmt::format("poisson_reconstruct: point {} or its normal is not finite or not unit", i));
    pts.emplace_back(Point(p.x(), p.y(), p.z()), Vector(q.x(), q.y(), q.z()));
  }
  PoissonResult result;
  const CGAL::First_of_pair_property_map<PointWithNormal> point_map;
  const CGAL::Second_of_pair_property_map<PointWithNormal> normal_map;
  result.spacing_mm = o.spacing_mm > 0.0
                          ? o.spacing_mm
                          : CGAL::compute_average_spacing<CGAL::Sequential_tag>(
                                pts, 6, CGAL::parameters::point_map(point_map));
  CGAL::Surface_mesh<Point> surface;
  bool ok = false;
  // The surface mesher draws its initial points from CGAL's default random
  // generator (per thread, seeded by the clock, and advanced by every call):
  // a fixed seed makes the mesh the same for the same cloud.
  CGAL::get_default_random() = CGAL::Random(0);
  try {
    ok = CGAL::poisson_surface_reconstruction_delaunay(pts.begin(), pts.end(), point_map, normal_map, surface,
                                                       result.spacing_mm, o.angle_deg, o.radius, o.distance);
  } catch (const std::exception& e) {  // CGAL's failure exceptions (precondition, assertion)
    throw SolverError(fmt::format("Poisson reconstruction failed in CGAL: {}", e.what()));
  }
  if (!ok || surface.number_of_faces() == 0)
    throw SolverError(fmt::format("Poisson reconstruction of {} points found no surface (the solver did not "
                                  "converge or the normals are inconsistent: they must point out of the object)",
                                  n));
  // A fresh Surface_mesh has no removed elements: indices are 0..n-1.
  TriMesh mesh;
  for (const auto v : surface.vertices()) {
    const Point& p = surface.point(v);
    mesh.vertices.emplace_back(p.x(), p.y(), p.z());
  }
  for (const auto f : surface.faces()) {
    const auto h = surface.halfedge(f);
    if (surface.next(surface.next(surface.next(h))) != h)
      throw SolverError("Poisson reconstruction: the mesher returned a face that is not a triangle");
    mesh.faces.push_back({static_cast<int>(surface.target(h).idx()),
                          static_cast<int>(surface.target(surface.next(h)).idx()),
                          static_cast<int>(surface.source(h).idx())});
  }
  result.mesh = in_canonical_order(mesh);
  return result;
}

}  // namespace knitforge
