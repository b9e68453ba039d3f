#include "knitforge/body/cut_body_region.h"

#include <algorithm>
#include <cmath>
#include <map>

#include <fmt/core.h>

#include "knitforge/evaluate/surface_distance.h"
#include "knitforge/geometry/clip_mesh_by_field.h"
#include "knitforge/geometry/halfedges.h"
#include "knitforge/geometry/isotropic_remesh.h"
#include "knitforge/geometry/marching_tetrahedra.h"
#include "knitforge/geometry/mesh_measures.h"
#include "knitforge/geometry/surface_checks.h"
#include "knitforge/util/errors.h"
#include "knitforge/util/union_find.h"

namespace knitforge {

namespace {

// Undirected edges of the faces, each once.
std::vector<std::array<int, 2>> unique_edges(const TriMesh& mesh, std::vector<int>* boundary_count = nullptr) {
  std::map<std::pair<int, int>, int> count;
  for (const auto& t : mesh.faces)
    for (int k = 0; k < 3; ++k) {
      int a = t[static_cast<size_t>(k)], b = t[static_cast<size_t>((k + 1) % 3)];
      if (a > b) std::swap(a, b);
      ++count[{a, b}];
    }
  std::vector<std::array<int, 2>> edges;
  edges.reserve(count.size());
  if (boundary_count) boundary_count->assign(static_cast<size_t>(mesh.num_vertices()), 0);
  for (const auto& [e, n] : count) {
    edges.push_back({e.first, e.second});
    if (boundary_count && n == 1) {
      ++(*boundary_count)[static_cast<size_t>(e.first)];
      ++(*boundary_count)[static_cast<size_t>(e.second)];
    }
  }
  return edges;
}

// Connected sets of the vertices with inside[v] (joined by edges with both
// ends inside): component root per vertex (-1 outside), sizes by root.
std::vector<int> vertex_sets(int n, const std::vector<std::array<int, 2>>& edges, const std::vector<char>& inside,
                             std::map<int, int>& size) {
  UnionFind uf(static_cast<size_t>(n));
  for (const auto& e : edges)
    if (inside[static_cast<size_t>(e[0])] && inside[static_cast<size_t>(e[1])]) uf.unite(e[0], e[1]);
  std::vector<int> root(static_cast<size_t>(n), -1);
  size.clear();
  for (int v = 0; v < n; ++v)
    if (inside[static_cast<size_t>(v)]) ++size[root[static_cast<size_t>(v)] = uf.find(v)];
  return root;
}

}  // namespace

std::vector<double> body_part_field(const BodyModel& model, BodyPart part) {
  const auto p = static_cast<size_t>(part);
  if (!model.part_fields.empty()) return model.part_fields[p];
  if (model.vertex_parts.empty())
    throw InvalidInput(fmt::format("body model '{}' has no part labels to cut a region by{}", model.name,
                                   model.labels_note.empty() ? "" : ": " + model.labels_note));
  const TriMesh mesh = model.template_mesh();
  std::vector<double> f(static_cast<size_t>(model.num_vertices()));
  for (size_t i = 0; i < f.size(); ++i) f[i] = model.vertex_parts[i] == part ? 1.0 : -1.0;
  const auto edges = unique_edges(mesh);
  for (int pass = 0; pass < 8; ++pass) {
    std::vector<double> sum(f), cnt(f.size(), 1.0);
    for (const auto& e : edges) {
      sum[static_cast<size_t>(e[0])] += f[static_cast<size_t>(e[1])];
      sum[static_cast<size_t>(e[1])] += f[static_cast<size_t>(e[0])];
      cnt[static_cast<size_t>(e[0])] += 1.0;
      cnt[static_cast<size_t>(e[1])] += 1.0;
    }
    for (size_t i = 0; i < f.size(); ++i) f[i] = sum[i] / cnt[i];
  }
  return f;
}

std::vector<double> scan_part_field(const BodyModel& model, const TriMesh& fitted, const TriMesh& scan,
                                    BodyPart part) {
  if (fitted.num_vertices() != model.num_vertices() || fitted.faces != model.faces)
    throw InvalidInput(fmt::format("the fitted body ({} vertices, {} faces) is not a body of the model '{}' ({} "
                                   "vertices, {} faces)",
                                   fitted.num_vertices(), fitted.num_faces(), model.name, model.num_vertices(),
                                   model.num_faces()));
  const std::vector<double> g = body_part_field(model, part);
  const SurfaceBvh bvh(fitted);
  std::vector<double> f(scan.vertices.size());
  for (size_t i = 0; i < scan.vertices.size(); ++i) {
    const ClosestPoint cp = bvh.closest_point(scan.vertices[i]);
    const auto& t = fitted.faces[static_cast<size_t>(cp.face)];
    const TrianglePoint tp =
        closest_triangle_point(scan.vertices[i], fitted.vertices[static_cast<size_t>(t[0])],
                               fitted.vertices[static_cast<size_t>(t[1])], fitted.vertices[static_cast<size_t>(t[2])]);
    f[i] = 0.0;
    for (int k = 0; k < 3; ++k) f[i] += tp.bary[k] * g[static_cast<size_t>(t[static_cast<size_t>(k)])];
  }
  return f;
}

BodyRegion cut_body_region(const TriMesh& surface, const std::vector<double>& field, const BodyRegionOptions& options) {
  const int V = surface.num_vertices();
  if (static_cast<int>(field.size()) != V)
    throw InvalidInput(fmt::format("body region: {} field values for a surface of {} vertices", field.size(), V));
  if (!(options.edge_length_mm >= 0.0) || !std::isfinite(options.edge_length_mm))
    throw InvalidInput(fmt::format("body region: edge length {} mm must be >= 0", options.edge_length_mm));
  if (options.remesh_iterations < 0)
    throw InvalidInput(fmt::format("body region: remesh iterations {} must be >= 0", options.remesh_iterations));
  BodyRegion out;

  // 1. Islands and holes, on the vertex sets.
  std::vector<double> f = field;
  std::vector<int> on_boundary;
  const auto edges = unique_edges(surface, &on_boundary);
  std::vector<char> used(static_cast<size_t>(V), 0);
  for (const auto& t : surface.faces)
    for (int v : t) used[static_cast<size_t>(v)] = 1;
  std::vector<char> pos(static_cast<size_t>(V)), neg(static_cast<size_t>(V));
  for (int v = 0; v < V; ++v) {
    pos[static_cast<size_t>(v)] = used[static_cast<size_t>(v)] && f[static_cast<size_t>(v)] > 0.0;
    neg[static_cast<size_t>(v)] = used[static_cast<size_t>(v)] && !pos[static_cast<size_t>(v)];
  }
  std::map<int, int> size;
  const std::vector<int> proot = vertex_sets(V, edges, pos, size);
  if (size.empty()) throw InvalidInput("body region: the part has no vertex on this surface");
  int keep = -1;
  for (const auto& [r, n] : size)
    if (keep < 0 || n > size[keep]) keep = r;
  out.islands_removed = static_cast<int>(size.size()) - 1;
  for (int v = 0; v < V; ++v) {
    const int r = proot[static_cast<size_t>(v)];
    if (r >= 0 && r != keep) f[static_cast<size_t>(v)] = -std::max(std::abs(f[static_cast<size_t>(v)]), 1e-6);
  }
  for (int v = 0; v < V; ++v) neg[static_cast<size_t>(v)] = used[static_cast<size_t>(v)] && !(f[static_cast<size_t>(v)] > 0.0);
  const std::vector<int> nroot = vertex_sets(V, edges, neg, size);
  std::map<int, bool> outside;  // keep as the outside: the largest set and sets on the surface's boundary
  int largest = -1;
  for (const auto& [r, n] : size)
    if (largest < 0 || n > size[largest]) largest = r;
  for (int v = 0; v < V; ++v) {
    const int r = nroot[static_cast<size_t>(v)];
    if (r >= 0 && (r == largest || on_boundary[static_cast<size_t>(v)] > 0)) outside[r] = true;
  }
  for (const auto& [r, n] : size)
    if (!outside.count(r)) ++out.holes_filled;
  for (int v = 0; v < V; ++v) {
    const int r = nroot[static_cast<size_t>(v)];
    if (r >= 0 && !outside.count(r)) f[static_cast<size_t>(v)] = std::max(std::abs(f[static_cast<size_t>(v)]), 1e-6);
  }

  // 2.-3. The cut, one component. Snapping can in rare cases pinch the
  // region at a vertex; then the cut is made again without it.
  ClippedMesh cut = clip_mesh_by_field(surface, f);
  TriMesh panel = largest_component(cut.mesh);
  if (!validate_surface(panel).ok()) {
    ClipFieldOptions no_snap;
    no_snap.snap_fraction = 0.0;
    cut = clip_mesh_by_field(surface, f, no_snap);
    panel = largest_component(cut.mesh);
  }
  out.snapped_vertices = cut.snapped_vertices;
  const SurfaceReport before = validate_surface(panel);
  if (!before.ok()) throw TopologyError("body region: the cut region is not a valid surface: " + before.summary());
  if (!before.is_disk)
    throw TopologyError(fmt::format("body region: the region is not a disk after removing islands and filling holes "
                                    "({} boundary loops, genus {}); a region that wraps around a limb needs a cut",
                                    before.num_boundary_loops, before.genus));

  // 4. Remeshing.
  out.edge_length_mm = options.edge_length_mm > 0.0 ? options.edge_length_mm : edge_length_stats(panel).mean;
  if (options.remesh_iterations > 0) {
    RemeshOptions ro;
    ro.target_edge_length = out.edge_length_mm;
    ro.iterations = options.remesh_iterations;
    panel = isotropic_remesh(panel, ro);
  }
  // 5. The result.
  const SurfaceReport after = validate_surface(panel);
  if (!after.is_disk) throw TopologyError("body region: the remeshed region is not a disk: " + after.summary());
  out.area_mm2 = total_area(panel);
  const Halfedges he = build_halfedges(panel.num_vertices(), panel.faces);
  for (const auto& loop : he.boundary_loops())
    for (size_t k = 0; k < loop.size(); ++k)
      out.boundary_length_mm += (panel.vertices[static_cast<size_t>(loop[k])] -
                                 panel.vertices[static_cast<size_t>(loop[(k + 1) % loop.size()])])
                                    .norm();
  out.mesh = std::move(panel);
  return out;
}

}  // namespace knitforge
