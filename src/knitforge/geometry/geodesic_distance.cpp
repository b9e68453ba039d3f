#include "knitforge/geometry/geodesic_distance.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <fmt/format.h>

#include "knitforge/geometry/geodesic_propagation.h"
#include "knitforge/util/errors.h"
#include "knitforge/util/parallel_ranges.h"
#include "knitforge/util/union_find.h"

namespace knitforge {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// A source point seen from one face that contains it.
struct FacePoint {
  int line, index;  // polyline and position in it
  Vec3 bary;        // in the face's corner order
};

// Barycentric coordinates of p in face f (exact zeros kept), or false when
// f does not contain p.
bool bary_in_face(const TriMesh& mesh, const SurfacePoint& p, int f, Vec3& out) {
  out = Vec3::Zero();
  const auto& src = mesh.faces[p.face];
  const auto& dst = mesh.faces[f];
  for (int k = 0; k < 3; ++k) {
    if (p.bary[k] == 0.0) continue;
    int j = 0;
    while (j < 3 && dst[j] != src[k]) ++j;
    if (j == 3) return false;
    out[j] += p.bary[k];
  }
  return true;
}

// Position of a point on the boundary of its face as a perimeter parameter
// (edge k, from corner k to corner k + 1, covers [k, k + 1]), or -1 inside.
double perimeter_param(const Vec3& b) {
  int zeros = 0, m = -1;
  for (int k = 0; k < 3; ++k)
    if (b[k] == 0.0) {
      ++zeros;
      m = k;
    }
  if (zeros == 0) return -1.0;
  if (zeros >= 2) {  // at a corner
    for (int k = 0; k < 3; ++k)
      if (b[k] != 0.0) return k;
    return -1.0;
  }
  const int k = (m + 1) % 3;  // the edge opposite corner m
  return k + b[(k + 1) % 3];
}

// True when the vertex sides are certified consistent with the source curve
// (see geodesic_distance.h, "Two sides"): the side is constant on every
// connected part of (surface minus source), so that the shortest path from a
// vertex of side s never meets an edge whose ends both have side -s outside
// the faces the source touches. Sufficient conditions checked (the proof is
// in docs/geometry.md):
//  (a) every vertex of side 0 is a source point;
//  (b) a face without source points has three corners of one non-zero side;
//  (c) in a face with source points, two corners off the source with
//      different sides are separated inside the face by one connected piece
//      of the source (it meets both boundary arcs between them);
//  (d) on every edge, two consecutive source points are joined by a source
//      segment along the edge (no piece of the edge between two crossings).
// Conservative: anything not proven gives false. `source_face` gets 1 for the
// faces that contain a source point.
bool sides_certified(const detail::GeodesicGeometry& g, const GeodesicSource& src,
                     std::vector<char>& source_face) {
  const TriMesh& mesh = *g.mesh;
  const int nf = mesh.num_faces();
  const std::vector<signed char>& side = src.vertex_side;
  std::vector<char> on_source(mesh.num_vertices(), 0);
  std::vector<std::vector<FacePoint>> in_face(nf);
  source_face.assign(nf, 0);
  for (int li = 0; li < static_cast<int>(src.polylines.size()); ++li) {
    const auto& line = src.polylines[li];
    for (int i = 0; i < static_cast<int>(line.size()); ++i) {
      const SurfacePoint& p = line[i];
      const auto& t = mesh.faces[p.face];
      int support[3] = {-1, -1, -1}, ns = 0;
      for (int k = 0; k < 3; ++k)
        if (p.bary[k] != 0.0) support[ns++] = t[k];
      if (ns == 0) continue;  // (not a valid point: rejected before)
      if (ns == 1) on_source[support[0]] = 1;
      // Every face containing p: around its first support vertex.
      const int v0 = support[0];
      for (int j = g.out_start[v0]; j < g.out_start[v0 + 1]; ++j) {
        const int f = g.he.face(g.out_he[j]);
        Vec3 b;
        if (!bary_in_face(mesh, p, f, b)) continue;
        in_face[f].push_back({li, i, b});
        source_face[f] = 1;
      }
    }
  }
  auto face_ok_clean = [&](int f) {
    const auto& t = mesh.faces[f];
    return side[t[0]] != 0 && side[t[0]] == side[t[1]] && side[t[1]] == side[t[2]];
  };
  for (int f = 0; f < nf; ++f) {
    if (!source_face[f]) {
      if (!face_ok_clean(f)) return false;  // (b), and (a) for its corners
      continue;
    }
    const auto& t = mesh.faces[f];
    const std::vector<FacePoint>& pts = in_face[f];
    const int n = static_cast<int>(pts.size());
    // Connected pieces of the source inside f: consecutive points of a
    // polyline (the segment between them lies in f) and equal points.
    UnionFind uf(n);
    for (int a = 0; a < n; ++a)
      for (int b = a + 1; b < n; ++b) {
        const bool consecutive = pts[a].line == pts[b].line && std::abs(pts[a].index - pts[b].index) == 1;
        if (consecutive || pts[a].bary == pts[b].bary) uf.unite(a, b);
      }
    for (int k = 0; k < 3; ++k)
      if (side[t[k]] == 0 && !on_source[t[k]]) return false;  // (a)
    // (c)
    for (int u = 0; u < 3; ++u)
      for (int w = u + 1; w < 3; ++w) {
        if (on_source[t[u]] || on_source[t[w]] || side[t[u]] == side[t[w]]) continue;
        // Arcs of the perimeter: (u, w) and (w, u + 3).
        std::vector<char> arc1(n, 0), arc2(n, 0);
        for (int a = 0; a < n; ++a) {
          const double x = perimeter_param(pts[a].bary);
          if (x < 0.0) continue;
          const int r = uf.find(a);
          if (x > u && x < w)
            arc1[r] = 1;
          else if (x != u && x != w)
            arc2[r] = 1;
        }
        bool separated = false;
        for (int r = 0; r < n; ++r) separated = separated || (arc1[r] && arc2[r]);
        if (!separated) return false;
      }
    // (d): points on edge k (corner k -> k + 1) at t = bary[k + 1], and the
    // source segments along it.
    for (int k = 0; k < 3; ++k) {
      const int k1 = (k + 1) % 3, k2 = (k + 2) % 3;
      std::vector<double> ts;
      std::vector<std::pair<double, double>> along;
      for (int a = 0; a < n; ++a) {
        if (pts[a].bary[k2] != 0.0) continue;
        ts.push_back(pts[a].bary[k1]);
        for (int b = 0; b < n; ++b)
          if (pts[b].bary[k2] == 0.0 && pts[b].line == pts[a].line && pts[b].index == pts[a].index + 1)
            along.emplace_back(std::min(pts[a].bary[k1], pts[b].bary[k1]),
                               std::max(pts[a].bary[k1], pts[b].bary[k1]));
      }
      std::sort(ts.begin(), ts.end());
      ts.erase(std::unique(ts.begin(), ts.end()), ts.end());
      for (size_t i = 0; i + 1 < ts.size(); ++i) {
        bool covered = false;
        for (const auto& [lo, hi] : along) covered = covered || (lo <= ts[i] && hi >= ts[i + 1]);
        if (!covered) return false;
      }
    }
  }
  return true;
}

// The field of one propagation (or of the two side propagations) before
// signing.
struct RawField {
  std::vector<double> distance;
  size_t num_windows = 0;
  bool split = false;
};

RawField single_run(const detail::GeodesicGeometry& g, const GeodesicSource& source, double tolerance) {
  detail::GeodesicPropagation prop(g, false, tolerance);
  prop.add_source(source);
  prop.run();
  return {prop.distance(), prop.num_windows(), false};
}

// The two side propagations (run concurrently when the machine has more than
// one hardware thread). False when the sides are not certified, one side has
// no vertex, or a vertex stays unreached on its own side.
bool split_run(const detail::GeodesicGeometry& g, const GeodesicSource& source, double tolerance,
               RawField& out) {
  const TriMesh& mesh = *g.mesh;
  const std::vector<signed char>& side = source.vertex_side;
  bool has_pos = false, has_neg = false;
  for (int v = 0; v < mesh.num_vertices(); ++v) {
    if (g.he.is_isolated_vertex(v)) continue;
    has_pos = has_pos || side[v] > 0;
    has_neg = has_neg || side[v] < 0;
  }
  if (!has_pos || !has_neg) return false;
  std::vector<char> source_face;
  if (!sides_certified(g, source, source_face)) return false;
  // Side s drops the edges whose two ends are on side -s, outside the faces
  // the source touches.
  const int nh = g.he.num_halfedges();
  std::vector<char> blocked_pos(nh, 0), blocked_neg(nh, 0);
  for (int h = 0; h < nh; ++h) {
    const int o = g.he.opposite(h);
    if (source_face[g.he.face(h)] || (o >= 0 && source_face[g.he.face(o)])) continue;
    const int a = side[g.he.from(h)], b = side[g.he.to(h)];
    if (a < 0 && b < 0) blocked_pos[h] = 1;
    if (a > 0 && b > 0) blocked_neg[h] = 1;
  }
  detail::GeodesicPropagation pos(g, false, tolerance), neg(g, false, tolerance);
  pos.set_blocked(&blocked_pos);
  neg.set_blocked(&blocked_neg);
  pos.add_source(source);  // (throws for a bad source before any thread starts)
  neg.add_source(source);
  // Concurrently when the machine has more than one hardware thread.
  parallel_ranges(2, 2, [&](std::size_t begin, std::size_t end) {
    for (std::size_t k = begin; k < end; ++k) (k == 0 ? pos : neg).run();
  });
  const std::vector<double>& dp = pos.distance();
  const std::vector<double>& dn = neg.distance();
  out.distance.assign(mesh.num_vertices(), kInf);
  for (int v = 0; v < mesh.num_vertices(); ++v) {
    if (g.he.is_isolated_vertex(v)) continue;
    const double d = side[v] > 0 ? dp[v] : side[v] < 0 ? dn[v] : std::min(dp[v], dn[v]);
    if (!std::isfinite(d)) return false;  // cannot happen when certified; stay safe
    out.distance[v] = d;
  }
  out.num_windows = pos.num_windows() + neg.num_windows();
  out.split = true;
  return true;
}

}  // namespace

GeodesicSolver::GeodesicSolver(const TriMesh& mesh)
    : geometry_(std::make_unique<detail::GeodesicGeometry>(detail::build_geodesic_geometry(mesh))) {}

GeodesicSolver::~GeodesicSolver() = default;
GeodesicSolver::GeodesicSolver(GeodesicSolver&&) noexcept = default;
GeodesicSolver& GeodesicSolver::operator=(GeodesicSolver&&) noexcept = default;

const TriMesh& GeodesicSolver::mesh() const { return *geometry_->mesh; }

GeodesicField GeodesicSolver::distance(const GeodesicSource& source, const GeodesicOptions& options) const {
  const TriMesh& mesh = *geometry_->mesh;
  bool any = false;
  for (const auto& line : source.polylines) any = any || !line.empty();
  if (!any) throw InvalidInput("geodesic distance: the source has no points");
  const bool sided = options.signed_field && !source.vertex_side.empty();
  if (!source.vertex_side.empty() && static_cast<int>(source.vertex_side.size()) != mesh.num_vertices())
    throw InvalidInput(
        fmt::format("geodesic distance: the source has {} vertex sides but the mesh has {} vertices",
                    source.vertex_side.size(), mesh.num_vertices()));
  if (!std::isfinite(options.tolerance) || options.tolerance < 0.0)
    throw InvalidInput(fmt::format(
        "geodesic distance: the tolerance must be a finite number >= 0 mm (0 = exact), got {}",
        options.tolerance));
  // Validate every source point before any side analysis reads them.
  for (const auto& line : source.polylines)
    for (const SurfacePoint& p : line) detail::check_surface_point(mesh, p);
  const double tolerance =
      options.tolerance > 0.0 && geometry_->saddle_fraction <= options.max_saddle_fraction ? options.tolerance : 0.0;
  RawField raw;
  if (!(options.split_sides && !source.vertex_side.empty() && split_run(*geometry_, source, tolerance, raw)))
    raw = single_run(*geometry_, source, tolerance);
  GeodesicField field;
  field.approximate = tolerance > 0.0;
  field.distance = std::move(raw.distance);
  field.num_windows = raw.num_windows;
  field.split_sides = raw.split;
  field.is_signed = sided;
  const auto& he = geometry_->he;
  for (int v = 0; v < mesh.num_vertices(); ++v) {
    if (he.is_isolated_vertex(v)) continue;
    double& d = field.distance[v];
    if (!std::isfinite(d))
      throw TopologyError(fmt::format(
          "geodesic distance: vertex {} cannot be reached from the source ({}); the surface has a "
          "component without a source point (check it with `knitforge check`, or remove that part)",
          v, source.description.empty() ? "given source" : source.description));
    if (sided && source.vertex_side[v] < 0) d = -d;
    field.max_abs_distance = std::max(field.max_abs_distance, std::abs(d));
  }
  return field;
}

GeodesicField geodesic_distance(const TriMesh& mesh, const GeodesicSource& source,
                                const GeodesicOptions& options) {
  return GeodesicSolver(mesh).distance(source, options);
}

}  // namespace knitforge
