// alpha_close() with CGAL::alpha_wrap_3 (declared in alpha_close.h).
#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <vector>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/alpha_wrap_3.h>
#include <fmt/core.h>

#include "knitforge/geometry/alpha_close.h"
#include "knitforge/geometry/halfedges.h"
#include "knitforge/util/errors.h"
#include "knitforge/util/work_limit.h"

namespace knitforge {

namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point3 = Kernel::Point_3;
using CgalMesh = CGAL::Surface_mesh<Point3>;

/// Adds a centroid fan over every boundary loop of a manifold mesh; returns
/// the number of loops closed (0 when the mesh is not an oriented manifold).
int cap_boundary_loops(TriMesh& mesh) {
  Halfedges he;
  try {
    he = build_halfedges(mesh.num_vertices(), mesh.faces);
  } catch (const TopologyError&) {
    return 0;
  }
  const auto loops = he.boundary_loops();
  for (const auto& loop : loops) {
    Vec3 c = Vec3::Zero();
    for (int v : loop) c += mesh.vertices[v];
    c /= static_cast<double>(loop.size());
    const int centre = mesh.num_vertices();
    mesh.vertices.push_back(c);
    // The loop runs with the mesh on its left: the cap runs against it.
    for (std::size_t k = 0; k < loop.size(); ++k) {
      mesh.faces.push_back({centre, loop[(k + 1) % loop.size()], loop[k]});
    }
  }
  return static_cast<int>(loops.size());
}

}  // namespace

double enclosed_volume(const TriMesh& mesh) {
  double v = 0.0;
  for (const auto& t : mesh.faces) {
    v += mesh.vertices[t[0]].dot(mesh.vertices[t[1]].cross(mesh.vertices[t[2]]));
  }
  return v / 6.0;
}

AlphaCloseResult alpha_close(const TriMesh& input, const AlphaCloseOptions& options) {
  if (!std::isfinite(options.alpha) || options.alpha < 0.0) {
    throw InvalidInput(fmt::format(
        "alpha_close: alpha must be a finite length >= 0 mm (0: automatic), got {}", options.alpha));
  }
  if (!std::isfinite(options.offset) || options.offset < 0.0) {
    throw InvalidInput(fmt::format(
        "alpha_close: the offset must be a finite length >= 0 mm (0: automatic), got {}", options.offset));
  }
  const bool point_set = input.faces.empty();
  if (point_set && input.num_vertices() < 4) {
    throw InvalidInput(
        fmt::format("alpha_close: a point set needs at least 4 points (got {})", input.num_vertices()));
  }
  for (int v = 0; v < input.num_vertices(); ++v) {
    if (!input.vertices[v].allFinite()) {
      throw InvalidInput(fmt::format("alpha_close: vertex {} has a non-finite coordinate", v));
    }
  }
  for (int f = 0; f < input.num_faces(); ++f) {
    for (int v : input.faces[f]) {
      if (v < 0 || v >= input.num_vertices()) {
        throw InvalidInput(
            fmt::format("alpha_close: face {} uses vertex {}, outside [0, {})", f, v, input.num_vertices()));
      }
    }
  }
  AlphaCloseResult result;
  TriMesh work = input;
  if (!point_set && options.cap_holes) result.capped_holes = cap_boundary_loops(work);

  Vec3 lo = work.vertices.front(), hi = lo;
  for (const Vec3& p : work.vertices) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  const double diagonal = (hi - lo).norm();
  if (!(diagonal > 0.0)) throw InvalidInput("alpha_close: the input has no extent (all points coincide)");
  result.alpha = options.alpha > 0.0 ? options.alpha : diagonal / 20.0;
  result.offset = options.offset > 0.0 ? options.offset : result.alpha / 30.0;
  {
    // The wrap's triangles scale with the wrapped area over alpha² (a point
    // set: its bounding box's surface).
    const Vec3 e = hi - lo;
    double area = 0.0;
    for (const auto& t : work.faces)
      area += 0.5 * (work.vertices[t[1]] - work.vertices[t[0]]).cross(work.vertices[t[2]] - work.vertices[t[0]]).norm();
    if (point_set || !(area > 0.0)) area = 2.0 * (e.x() * e.y() + e.y() * e.z() + e.z() * e.x());
    const double faces = 2.0 * area / (result.alpha * result.alpha);
    check_work({fmt::format("alpha_close: wrapping {:.4g} mm^2 with alpha {:.3g} mm", area, result.alpha), faces,
                "triangles", options.max_faces, 1500.0,
                fmt::format("use --alpha {:.3g} or larger (or raise the limit with --max-faces)",
                            std::sqrt(2.0 * area / options.max_faces))});
  }

  std::vector<Point3> points;
  points.reserve(work.vertices.size());
  for (const Vec3& p : work.vertices) points.emplace_back(p.x(), p.y(), p.z());
  CgalMesh wrap;
  if (point_set) {
    CGAL::alpha_wrap_3(points, result.alpha, result.offset, wrap);
  } else {
    std::vector<std::array<std::size_t, 3>> faces;
    faces.reserve(work.faces.size());
    for (const auto& t : work.faces) {
      faces.push_back(
          {static_cast<std::size_t>(t[0]), static_cast<std::size_t>(t[1]), static_cast<std::size_t>(t[2])});
    }
    CGAL::alpha_wrap_3(points, faces, result.alpha, result.offset, wrap);
  }

  std::vector<int> id(wrap.number_of_vertices() + wrap.number_of_removed_vertices(), -1);
  for (const auto v : wrap.vertices()) {
    const Point3& p = wrap.point(v);
    id[static_cast<std::size_t>(v.idx())] = result.mesh.num_vertices();
    result.mesh.vertices.emplace_back(p.x(), p.y(), p.z());
  }
  for (const auto f : wrap.faces()) {
    std::array<int, 3> tri{};
    int k = 0;
    for (const auto v : CGAL::vertices_around_face(wrap.halfedge(f), wrap)) {
      if (k == 3) throw SolverError("alpha_close: the wrap has a face that is not a triangle");
      tri[k++] = id[static_cast<std::size_t>(v.idx())];
    }
    if (k != 3) throw SolverError("alpha_close: the wrap has a face that is not a triangle");
    result.mesh.faces.push_back(tri);
  }
  if (result.mesh.faces.empty()) {
    throw SolverError(fmt::format("alpha_close: the wrap is empty (alpha {} mm, offset {} mm)", result.alpha,
                                  result.offset));
  }
  Halfedges he;
  try {
    he = build_halfedges(result.mesh.num_vertices(), result.mesh.faces);
  } catch (const TopologyError& e) {
    throw SolverError(fmt::format("alpha_close: the wrap is not a manifold mesh ({})", e.what()));
  }
  if (!he.boundary_loops().empty()) throw SolverError("alpha_close: the wrap is not closed");
  result.volume = enclosed_volume(result.mesh);
  return result;
}

}  // namespace knitforge
