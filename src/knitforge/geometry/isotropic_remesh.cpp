#include "knitforge/geometry/isotropic_remesh.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <numbers>

#include <CGAL/AABB_face_graph_triangle_primitive.h>
#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/exceptions.h>
#include <CGAL/Polygon_mesh_processing/remesh.h>
#include <CGAL/Surface_mesh.h>
#include <fmt/core.h>

#include "knitforge/geometry/halfedges.h"
#include "knitforge/geometry/mesh_measures.h"
#include "knitforge/geometry/surface_checks.h"
#include "knitforge/util/errors.h"

namespace knitforge {

namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = Kernel::Point_3;
using SurfaceMesh = CGAL::Surface_mesh<Point>;
using VertexIndex = SurfaceMesh::Vertex_index;
using Primitive = CGAL::AABB_face_graph_triangle_primitive<SurfaceMesh>;
using Tree = CGAL::AABB_tree<CGAL::AABB_traits<Kernel, Primitive>>;
namespace PMP = CGAL::Polygon_mesh_processing;

Point to_point(const Vec3& p) { return Point(p.x(), p.y(), p.z()); }
Vec3 to_vec(const Point& p) { return Vec3(p.x(), p.y(), p.z()); }

// Closest point on the input mesh (the default surface projection).
class InputSurface {
 public:
  explicit InputSurface(const TriMesh& mesh) {
    std::vector<VertexIndex> vs;
    vs.reserve(mesh.vertices.size());
    for (const Vec3& p : mesh.vertices) vs.push_back(mesh_.add_vertex(to_point(p)));
    for (const auto& t : mesh.faces) mesh_.add_face(vs[t[0]], vs[t[1]], vs[t[2]]);
    tree_ = std::make_unique<Tree>(faces(mesh_).first, faces(mesh_).second, mesh_);
    tree_->accelerate_distance_queries();
  }
  Vec3 operator()(const Vec3& p) const { return to_vec(tree_->closest_point(to_point(p))); }

 private:
  SurfaceMesh mesh_;
  std::unique_ptr<Tree> tree_;
};

// Closest point on the input boundary polylines (the default boundary projection).
class InputBoundary {
 public:
  InputBoundary(const TriMesh& mesh, const std::vector<std::vector<int>>& loops) {
    for (const auto& loop : loops) {
      for (size_t i = 0; i < loop.size(); ++i) {
        segments_.emplace_back(mesh.vertices[loop[i]], mesh.vertices[loop[(i + 1) % loop.size()]]);
      }
    }
  }
  Vec3 operator()(const Vec3& p) const {
    Vec3 best = p;
    double best_d2 = std::numeric_limits<double>::infinity();
    for (const auto& [a, b] : segments_) {
      const Vec3 q = closest_point_on_segment(p, a, b);
      const double d2 = (q - p).squaredNorm();
      if (d2 < best_d2) {
        best_d2 = d2;
        best = q;
      }
    }
    return best;
  }

 private:
  std::vector<std::pair<Vec3, Vec3>> segments_;
};

struct Topology {
  int components, loops, genus;
  bool operator==(const Topology&) const = default;
};

Topology topology_of(const SurfaceReport& r) { return {r.num_components, r.num_boundary_loops, r.genus}; }

}  // namespace

TriMesh isotropic_remesh(const TriMesh& mesh, const RemeshOptions& options) {
  const double l = options.target_edge_length;
  if (!(l > 0.0) || !std::isfinite(l)) {
    throw InvalidInput(fmt::format("isotropic_remesh: target_edge_length must be a positive length in mm, got {}", l));
  }
  if (options.iterations < 0 || options.relaxation_steps < 1) {
    throw InvalidInput(fmt::format(
        "isotropic_remesh: iterations must be >= 0 and relaxation_steps >= 1, got {} and {}",
        options.iterations, options.relaxation_steps));
  }
  for (int v : options.fixed_vertices) {
    if (v < 0 || v >= mesh.num_vertices()) {
      throw InvalidInput(fmt::format("isotropic_remesh: fixed vertex {} is out of range (the mesh has {} vertices)",
                                     v, mesh.num_vertices()));
    }
  }
  const SurfaceReport input_report = validate_surface(mesh);
  if (!input_report.ok()) require_valid_surface(mesh, "isotropic_remesh input");  // throws, saying why
  const Halfedges he = build_halfedges(mesh.num_vertices(), mesh.faces);
  const auto loops = he.boundary_loops();

  std::vector<char> fixed(mesh.vertices.size(), 0);
  for (int v : options.fixed_vertices) fixed[v] = 1;
  if (options.boundary_corner_angle_deg > 0.0) {
    const double cos_limit = std::cos(options.boundary_corner_angle_deg * std::numbers::pi / 180.0);
    for (const auto& loop : loops) {
      const size_t n = loop.size();
      for (size_t i = 0; i < n; ++i) {
        const Vec3 d1 = mesh.vertices[loop[i]] - mesh.vertices[loop[(i + n - 1) % n]];
        const Vec3 d2 = mesh.vertices[loop[(i + 1) % n]] - mesh.vertices[loop[i]];
        const double denom = d1.norm() * d2.norm();
        if (denom > 0.0 && d1.dot(d2) < cos_limit * denom) fixed[loop[i]] = 1;
      }
    }
  }

  std::unique_ptr<InputSurface> default_surface;
  std::unique_ptr<InputBoundary> default_boundary;
  PointProjection project = options.project;
  PointProjection project_boundary = options.project_boundary;
  if (!project) {
    default_surface = std::make_unique<InputSurface>(mesh);
    project = [s = default_surface.get()](const Vec3& p) { return (*s)(p); };
  }
  if (!project_boundary) {
    default_boundary = std::make_unique<InputBoundary>(mesh, loops);
    project_boundary = [b = default_boundary.get()](const Vec3& p) { return (*b)(p); };
  }

  SurfaceMesh sm;
  std::vector<VertexIndex> vs;
  vs.reserve(mesh.vertices.size());
  for (const Vec3& p : mesh.vertices) vs.push_back(sm.add_vertex(to_point(p)));
  for (int f = 0; f < mesh.num_faces(); ++f) {
    const auto& t = mesh.faces[f];
    if (sm.add_face(vs[t[0]], vs[t[1]], vs[t[2]]) == SurfaceMesh::null_face()) {
      throw TopologyError(fmt::format("isotropic_remesh: face {} could not be added (non-manifold input)", f));
    }
  }
  auto is_fixed = sm.add_property_map<VertexIndex, bool>("v:knitforge_fixed", false).first;
  std::vector<std::pair<VertexIndex, Point>> fixed_points;
  for (size_t v = 0; v < vs.size(); ++v) {
    if (fixed[v]) {
      is_fixed[vs[v]] = true;
      fixed_points.emplace_back(vs[v], sm.point(vs[v]));
    }
  }

  auto identity = [&sm](VertexIndex v) { return sm.point(v); };
  for (int it = 0; it < options.iterations; ++it) {
    try {
      PMP::isotropic_remeshing(faces(sm), l, sm,
                               CGAL::parameters::number_of_iterations(1)
                                   .number_of_relaxation_steps(static_cast<unsigned>(options.relaxation_steps))
                                   .relax_constraints(true)
                                   .vertex_is_constrained_map(is_fixed)
                                   .projection_functor(identity)
                                   .do_project(false));
    } catch (const CGAL::Failure_exception& e) {
      throw SolverError(fmt::format("isotropic_remesh: CGAL failed in iteration {}: {}", it + 1, e.what()));
    }
    for (VertexIndex v : sm.vertices()) {
      if (is_fixed[v] || sm.is_isolated(v)) continue;
      const Vec3 p = to_vec(sm.point(v));
      const Vec3 q = sm.is_border(v, true) ? project_boundary(p) : project(p);
      if (!q.allFinite()) {
        throw InvalidInput(fmt::format(
            "isotropic_remesh: the {} projection returned a non-finite point for ({}, {}, {})",
            sm.is_border(v, true) ? "boundary" : "surface", p.x(), p.y(), p.z()));
      }
      sm.point(v) = to_point(q);
    }
    // CGAL's relaxation does not consult the constrained-vertex map; restore.
    for (const auto& [v, p] : fixed_points) sm.point(v) = p;
  }

  TriMesh out;
  std::vector<int> index(sm.num_vertices(), -1);  // used and removed slots
  for (VertexIndex v : sm.vertices()) {
    if (sm.is_isolated(v)) continue;
    index[v.idx()] = out.num_vertices();
    out.vertices.push_back(to_vec(sm.point(v)));
  }
  for (auto f : sm.faces()) {
    std::array<int, 3> t{};
    int k = 0;
    for (VertexIndex v : CGAL::vertices_around_face(sm.halfedge(f), sm)) t[k++] = index[v.idx()];
    out.faces.push_back(t);
  }

  const SurfaceReport output_report = validate_surface(out);
  if (!output_report.ok() || !(topology_of(output_report) == topology_of(input_report))) {
    throw SolverError(fmt::format(
        "isotropic_remesh changed the surface: input {}; output {}; try a smaller target edge "
        "length relative to the features of the surface",
        input_report.summary(), output_report.summary()));
  }
  return out;
}

}  // namespace knitforge
