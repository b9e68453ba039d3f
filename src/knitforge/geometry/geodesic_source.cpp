#include "knitforge/geometry/geodesic_source.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <map>
#include <queue>
#include <string>
#include <unordered_map>
#include <utility>

#include <fmt/format.h>

#include "knitforge/geometry/chain_edges.h"
#include "knitforge/geometry/geodesic_path.h"
#include "knitforge/geometry/halfedges.h"
#include "knitforge/geometry/mesh_measures.h"
#include "knitforge/util/errors.h"

namespace knitforge {
namespace {

// A node of a source curve: a vertex (a == b) or a point inside edge (a, b), a < b.
struct NodeKey {
  int a = -1;
  int b = -1;
  bool operator<(const NodeKey& o) const { return a != o.a ? a < o.a : b < o.b; }
  bool operator==(const NodeKey& o) const { return a == o.a && b == o.b; }
};

int corner_of(const TriMesh& mesh, int f, int v) {
  for (int k = 0; k < 3; ++k)
    if (mesh.faces[f][k] == v) return k;
  return -1;
}

// The point (1 - t) va + t vb of face f, with exact zero barycentric coordinates.
SurfacePoint point_in_face(const TriMesh& mesh, int f, int va, int vb, double t) {
  SurfacePoint p;
  p.face = f;
  p.bary = Vec3::Zero();
  const int ka = corner_of(mesh, f, va);
  const int kb = corner_of(mesh, f, vb);
  if (va == vb || t <= 0.0) {
    p.bary[ka] = 1.0;
  } else if (t >= 1.0) {
    p.bary[kb] = 1.0;
  } else {
    p.bary[ka] = 1.0 - t;
    p.bary[kb] = t;
  }
  return p;
}

void check_face_indices(const TriMesh& mesh) {
  const int n = mesh.num_vertices();
  for (int f = 0; f < mesh.num_faces(); ++f)
    for (int k = 0; k < 3; ++k)
      if (mesh.faces[f][k] < 0 || mesh.faces[f][k] >= n)
        throw InvalidInput(fmt::format("geodesic source: face {} uses vertex index {} outside [0, {})", f,
                                       mesh.faces[f][k], n));
}

double mesh_scale(const TriMesh& mesh) {
  const double d = bounding_box(mesh).diagonal();
  return d > 0.0 ? d : 1.0;
}

// The segments between nodes chained into polylines (chain_edges.h): open
// chains first, then cycles; nodes without a segment become point sources.
std::vector<std::vector<SurfacePoint>> chain_segments(const std::vector<SurfacePoint>& node_point,
                                                      const std::vector<std::pair<int, int>>& segments) {
  std::vector<std::vector<SurfacePoint>> out;
  for (const std::vector<int>& path : chain_edges(static_cast<int>(node_point.size()), segments, true)) {
    out.emplace_back();
    for (int n : path) out.back().push_back(node_point[n]);
  }
  return out;
}

// Ericson's closest point on a triangle, returning barycentric coordinates
// with exact zeros on edges and vertices.
Vec3 closest_bary(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c) {
  const Vec3 ab = b - a, ac = c - a, ap = p - a;
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0.0 && d2 <= 0.0) return {1, 0, 0};
  const Vec3 bp = p - b;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0.0 && d4 <= d3) return {0, 1, 0};
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0 && d1 - d3 > 0.0) {
    const double v = d1 / (d1 - d3);
    return {1 - v, v, 0};
  }
  const Vec3 cp = p - c;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0.0 && d5 <= d6) return {0, 0, 1};
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0 && d2 - d6 > 0.0) {
    const double w = d2 / (d2 - d6);
    return {1 - w, 0, w};
  }
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0.0 && (d4 - d3) >= 0.0 && (d5 - d6) >= 0.0 && (d4 - d3) + (d5 - d6) > 0.0) {
    const double w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
    return {0, 1 - w, w};
  }
  const double denom = va + vb + vc;
  if (!(denom > 0.0)) {  // degenerate triangle: best of the three edges
    Vec3 best(1, 0, 0);
    double bd = (p - a).squaredNorm();
    const Vec3 pts[3] = {a, b, c};
    for (int k = 0; k < 3; ++k) {
      const Vec3& u = pts[k];
      const Vec3& w = pts[(k + 1) % 3];
      const double len2 = (w - u).squaredNorm();
      const double t = len2 > 0.0 ? std::clamp((p - u).dot(w - u) / len2, 0.0, 1.0) : 0.0;
      const double d = (p - (u + t * (w - u))).squaredNorm();
      if (d < bd) {
        bd = d;
        best = Vec3::Zero();
        best[k] = 1 - t;
        best[(k + 1) % 3] = t;
      }
    }
    return best;
  }
  const double v = vb / denom, w = vc / denom;
  return {1 - v - w, v, w};
}

}  // namespace

std::vector<signed char> source_sides(const TriMesh& mesh, const GeodesicSource& src) {
  const int nv = mesh.num_vertices();
  std::vector<char> on_source(nv, 0);
  std::map<std::pair<int, int>, char> crossed;
  for (const auto& line : src.polylines) {
    for (const SurfacePoint& p : line) {
      int nz = 0;
      int ks[3];
      for (int k = 0; k < 3; ++k)
        if (p.bary[k] != 0.0) ks[nz++] = k;
      const auto& f = mesh.faces[p.face];
      if (nz == 1) on_source[f[ks[0]]] = 1;
      if (nz == 2) crossed[{std::min(f[ks[0]], f[ks[1]]), std::max(f[ks[0]], f[ks[1]])}] = 1;
      // A point inside a face separates nothing by itself: the segments to
      // its neighbours cross the face's edges, which are recorded there.
    }
  }
  std::vector<std::vector<int>> adj(nv);
  for (const auto& f : mesh.faces) {
    for (int k = 0; k < 3; ++k) {
      const int a = f[k], b = f[(k + 1) % 3];
      if (on_source[a] || on_source[b] || crossed.count({std::min(a, b), std::max(a, b)})) continue;
      adj[a].push_back(b);
      adj[b].push_back(a);
    }
  }
  std::vector<int> comp(nv, -1);
  int ncomp = 0;
  std::vector<int> stack;
  std::vector<char> used(nv, 0);
  for (const auto& f : mesh.faces)
    for (int v : f) used[v] = 1;
  for (int v = 0; v < nv; ++v) {
    if (comp[v] >= 0 || on_source[v] || !used[v]) continue;
    comp[v] = ncomp;
    stack.push_back(v);
    while (!stack.empty()) {
      const int u = stack.back();
      stack.pop_back();
      for (int w : adj[u])
        if (comp[w] < 0) {
          comp[w] = ncomp;
          stack.push_back(w);
        }
    }
    ++ncomp;
  }
  std::vector<int> ids;
  for (int c : comp)
    if (c >= 0) ids.push_back(c);
  std::sort(ids.begin(), ids.end());
  ids.erase(std::unique(ids.begin(), ids.end()), ids.end());
  if (ids.size() != 2) return {};
  // Orientation from the first segment of positive length.
  for (const auto& line : src.polylines) {
    for (size_t i = 0; i + 1 < line.size(); ++i) {
      const Vec3 p = surface_point_position(mesh, line[i]);
      const Vec3 q = surface_point_position(mesh, line[i + 1]);
      if ((q - p).norm() <= 0.0) continue;
      // A face containing both points: the face of one of them contains the other's support.
      for (const SurfacePoint* sp : {&line[i], &line[i + 1]}) {
        const int f = sp->face;
        const Vec3 n = face_normal(mesh, f);
        for (int v : mesh.faces[f]) {
          if (comp[v] < 0) continue;
          const double s = n.dot((q - p).cross(mesh.vertices[v] - p));
          if (s == 0.0) continue;
          const int left = s > 0.0 ? comp[v] : (comp[v] == ids[0] ? ids[1] : ids[0]);
          std::vector<signed char> side(nv, 0);
          for (int u = 0; u < nv; ++u)
            if (comp[u] >= 0) side[u] = comp[u] == left ? 1 : -1;
          return side;
        }
      }
    }
  }
  return {};
}

int GeodesicSource::num_segments() const {
  int n = 0;
  for (const auto& l : polylines) n += l.empty() ? 0 : static_cast<int>(l.size()) - 1;
  return n;
}

double GeodesicSource::length(const TriMesh& mesh) const {
  double len = 0.0;
  for (const auto& l : polylines)
    for (size_t i = 0; i + 1 < l.size(); ++i)
      len += (surface_point_position(mesh, l[i + 1]) - surface_point_position(mesh, l[i])).norm();
  return len;
}

Vec3 surface_point_position(const TriMesh& mesh, const SurfacePoint& p) {
  const auto& f = mesh.faces[p.face];
  return p.bary[0] * mesh.vertices[f[0]] + p.bary[1] * mesh.vertices[f[1]] + p.bary[2] * mesh.vertices[f[2]];
}

SurfacePoint surface_point_at_vertex(const TriMesh& mesh, int v) {
  if (v < 0 || v >= mesh.num_vertices())
    throw InvalidInput(fmt::format("vertex id {} is out of range: the mesh has {} vertices (ids 0 to {})", v,
                                   mesh.num_vertices(), mesh.num_vertices() - 1));
  for (int f = 0; f < mesh.num_faces(); ++f)
    if (corner_of(mesh, f, v) >= 0) return point_in_face(mesh, f, v, v, 0.0);
  throw InvalidInput(fmt::format("vertex {} is used by no face, so it is not on the surface", v));
}

SurfacePoint surface_point_on_edge(const TriMesh& mesh, int v0, int v1, double t) {
  if (!(t >= 0.0 && t <= 1.0)) throw InvalidInput(fmt::format("edge ratio {} is outside [0, 1]", t));
  for (int f = 0; f < mesh.num_faces(); ++f)
    if (corner_of(mesh, f, v0) >= 0 && corner_of(mesh, f, v1) >= 0 && v0 != v1)
      return point_in_face(mesh, f, v0, v1, t);
  throw InvalidInput(fmt::format("vertices {} and {} are not joined by an edge of the mesh", v0, v1));
}

SurfacePoint closest_surface_point(const TriMesh& mesh, const Vec3& p) {
  if (mesh.faces.empty()) throw InvalidInput("closest surface point: the mesh has no faces");
  if (!p.allFinite()) throw InvalidInput("closest surface point: the query point is not finite");
  SurfacePoint best;
  double bd = std::numeric_limits<double>::infinity();
  for (int f = 0; f < mesh.num_faces(); ++f) {
    const auto& t = mesh.faces[f];
    const Vec3 b = closest_bary(p, mesh.vertices[t[0]], mesh.vertices[t[1]], mesh.vertices[t[2]]);
    const Vec3 q = b[0] * mesh.vertices[t[0]] + b[1] * mesh.vertices[t[1]] + b[2] * mesh.vertices[t[2]];
    const double d = (q - p).squaredNorm();
    if (d < bd) {
      bd = d;
      best.face = f;
      best.bary = b;
    }
  }
  return best;
}

GeodesicSource source_from_plane(const TriMesh& mesh, const Vec3& normal, double offset) {
  if (!normal.allFinite() || !(normal.norm() > 0.0))
    throw InvalidInput("plane source: the plane normal must be finite and non-zero");
  if (!std::isfinite(offset)) throw InvalidInput("plane source: the plane offset must be finite");
  if (mesh.faces.empty()) throw InvalidInput("plane source: the mesh has no faces");
  check_face_indices(mesh);
  const Vec3 n = normal.normalized();
  const double tol = 1e-9 * mesh_scale(mesh);
  const int nv = mesh.num_vertices();
  std::vector<double> phi(nv);
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  for (int v = 0; v < nv; ++v) {
    phi[v] = n.dot(mesh.vertices[v]) - offset;
    if (std::abs(phi[v]) <= tol) phi[v] = 0.0;
  }
  for (const auto& f : mesh.faces)
    for (int v : f) {
      lo = std::min(lo, phi[v] == 0.0 ? offset : n.dot(mesh.vertices[v]));
      hi = std::max(hi, phi[v] == 0.0 ? offset : n.dot(mesh.vertices[v]));
    }
  if (lo > offset || hi < offset)
    throw InvalidInput(fmt::format(
        "plane source: the plane n·x = {} with n = ({}, {}, {}) misses the surface; n·x ranges over "
        "[{}, {}] mm on the mesh, choose an offset in that range",
        offset, n.x(), n.y(), n.z(), lo, hi));

  std::map<NodeKey, int> node_id;
  std::vector<SurfacePoint> node_point;
  std::map<std::pair<int, int>, char> seg_seen;
  std::vector<std::pair<int, int>> segments;
  auto node = [&](int f, int a, int b) {
    NodeKey key{std::min(a, b), std::max(a, b)};
    auto it = node_id.find(key);
    if (it != node_id.end()) return it->second;
    const double t = key.a == key.b ? 0.0 : phi[key.a] / (phi[key.a] - phi[key.b]);
    node_point.push_back(point_in_face(mesh, f, key.a, key.b, t));
    node_id.emplace(key, static_cast<int>(node_point.size()) - 1);
    return static_cast<int>(node_point.size()) - 1;
  };
  auto add_segment = [&](int p, int q) {
    if (p == q) return;
    if (seg_seen.emplace(std::make_pair(std::min(p, q), std::max(p, q)), 1).second)
      segments.emplace_back(p, q);
  };
  for (int f = 0; f < mesh.num_faces(); ++f) {
    const auto& t = mesh.faces[f];
    std::vector<int> pts;
    int zeros = 0;
    for (int k = 0; k < 3; ++k) zeros += phi[t[k]] == 0.0;
    if (zeros == 3) {
      for (int k = 0; k < 3; ++k) add_segment(node(f, t[k], t[k]), node(f, t[(k + 1) % 3], t[(k + 1) % 3]));
      continue;
    }
    for (int k = 0; k < 3; ++k) {
      const int a = t[k], b = t[(k + 1) % 3];
      if (phi[a] == 0.0) pts.push_back(node(f, a, a));
      if ((phi[a] < 0.0 && phi[b] > 0.0) || (phi[a] > 0.0 && phi[b] < 0.0)) pts.push_back(node(f, a, b));
    }
    if (pts.size() == 2) add_segment(pts[0], pts[1]);
  }
  GeodesicSource src;
  src.polylines = chain_segments(node_point, segments);
  src.vertex_side.assign(nv, 0);
  for (int v = 0; v < nv; ++v) src.vertex_side[v] = phi[v] > 0.0 ? 1 : (phi[v] < 0.0 ? -1 : 0);
  src.description = fmt::format("plane ({}, {}, {})·x = {}", n.x(), n.y(), n.z(), offset);
  return src;
}

namespace {

struct BoundaryLoopData {
  std::vector<int> loop;      // vertices
  std::vector<int> halfedge;  // boundary half-edge loop[i] -> loop[i+1]
  std::vector<double> arc;    // arc length at loop[i]; arc[n] = total
};

std::vector<BoundaryLoopData> boundary_loop_data(const TriMesh& mesh, const Halfedges& he) {
  std::vector<int> out_he(mesh.num_vertices(), -1);
  for (int h = 0; h < he.num_halfedges(); ++h)
    if (he.is_boundary_halfedge(h)) out_he[he.from(h)] = h;
  std::vector<BoundaryLoopData> res;
  for (auto& loop : he.boundary_loops()) {
    BoundaryLoopData d;
    d.loop = loop;
    d.arc.push_back(0.0);
    for (size_t i = 0; i < loop.size(); ++i) {
      const int h = out_he[loop[i]];
      d.halfedge.push_back(h);
      d.arc.push_back(d.arc.back() + (mesh.vertices[he.to(h)] - mesh.vertices[he.from(h)]).norm());
    }
    res.push_back(std::move(d));
  }
  return res;
}

}  // namespace

GeodesicSource source_from_boundary(const TriMesh& mesh, double begin_fraction, double end_fraction,
                                    int loop) {
  for (double fr : {begin_fraction, end_fraction})
    if (!(fr >= 0.0 && fr <= 1.0))
      throw InvalidInput(fmt::format(
          "boundary source: arc-length fraction {} is outside [0, 1] (0 and 1 are the loop's first vertex)",
          fr));
  if (mesh.faces.empty()) throw InvalidInput("boundary source: the mesh has no faces");
  check_face_indices(mesh);
  const Halfedges he = build_halfedges(mesh.num_vertices(), mesh.faces);
  const auto loops = boundary_loop_data(mesh, he);
  if (loop < 0 || loop >= static_cast<int>(loops.size()))
    throw InvalidInput(
        fmt::format("boundary source: loop index {} is out of range: the mesh has {} boundary loop(s)", loop,
                    loops.size()));
  const BoundaryLoopData& d = loops[loop];
  const int n = static_cast<int>(d.loop.size());
  const double total = d.arc[n];
  if (!(total > 0.0)) throw InvalidInput("boundary source: the boundary loop has zero length");
  auto point_at = [&](double s) {
    s = std::clamp(s, 0.0, total);
    int i = static_cast<int>(std::upper_bound(d.arc.begin(), d.arc.end(), s) - d.arc.begin()) - 1;
    i = std::clamp(i, 0, n - 1);
    const int h = d.halfedge[i];
    const double len = d.arc[i + 1] - d.arc[i];
    const double t = len > 0.0 ? (s - d.arc[i]) / len : 0.0;
    return point_in_face(mesh, he.face(h), he.from(h), he.to(h), t);
  };
  GeodesicSource src;
  src.description = fmt::format("boundary loop {} from {} to {}", loop, begin_fraction, end_fraction);
  std::vector<SurfacePoint> line;
  auto vertex_point = [&](int i) {
    const int h = d.halfedge[i % n];
    return point_in_face(mesh, he.face(h), he.from(h), he.from(h), 0.0);
  };
  if (begin_fraction == end_fraction) {
    src.polylines.push_back({point_at(begin_fraction * total)});
    return src;
  }
  if (begin_fraction == 0.0 && end_fraction == 1.0) {
    for (int i = 0; i <= n; ++i) line.push_back(vertex_point(i));
    src.polylines.push_back(std::move(line));
    return src;
  }
  const double sb = begin_fraction * total, se = end_fraction * total;
  line.push_back(point_at(sb));
  // Vertices strictly after sb, up to se (wrapping when begin > end).
  auto add_range = [&](double from, double to) {
    for (int i = 0; i < n; ++i)
      if (d.arc[i] > from && d.arc[i] < to) line.push_back(vertex_point(i));
  };
  if (sb < se) {
    add_range(sb, se);
  } else {
    add_range(sb, total + 1.0);
    line.push_back(vertex_point(0));
    add_range(0.0, se);
  }
  const SurfacePoint last = point_at(se);
  line.push_back(last);
  // Drop repeated points (a fraction exactly at a vertex).
  std::vector<SurfacePoint> clean;
  for (const SurfacePoint& p : line)
    if (clean.empty() ||
        (surface_point_position(mesh, p) - surface_point_position(mesh, clean.back())).norm() > 0.0)
      clean.push_back(p);
  src.polylines.push_back(std::move(clean));
  return src;
}

GeodesicSource source_from_boundary_vertices(const TriMesh& mesh, const std::vector<int>& ids) {
  if (ids.empty()) throw InvalidInput("boundary vertex source: no vertex ids given");
  if (mesh.faces.empty()) throw InvalidInput("boundary vertex source: the mesh has no faces");
  check_face_indices(mesh);
  const Halfedges he = build_halfedges(mesh.num_vertices(), mesh.faces);
  std::vector<char> in(mesh.num_vertices(), 0);
  for (int v : ids) {
    if (v < 0 || v >= mesh.num_vertices())
      throw InvalidInput(
          fmt::format("boundary vertex source: vertex id {} is out of range (the mesh has {} vertices)", v,
                      mesh.num_vertices()));
    if (he.is_isolated_vertex(v) || !he.is_boundary_vertex(v))
      throw InvalidInput(
          fmt::format("boundary vertex source: vertex {} is not on the boundary of the surface", v));
    in[v] = 1;
  }
  GeodesicSource src;
  src.description = fmt::format("{} boundary vertices", ids.size());
  for (const BoundaryLoopData& d : boundary_loop_data(mesh, he)) {
    const int n = static_cast<int>(d.loop.size());
    auto vp = [&](int i) {
      const int h = d.halfedge[((i % n) + n) % n];
      return point_in_face(mesh, he.face(h), he.from(h), he.from(h), 0.0);
    };
    int count = 0;
    for (int v : d.loop) count += in[v];
    if (count == 0) continue;
    if (count == n) {
      std::vector<SurfacePoint> line;
      for (int i = 0; i <= n; ++i) line.push_back(vp(i));
      src.polylines.push_back(std::move(line));
      continue;
    }
    for (int i = 0; i < n; ++i) {
      if (!in[d.loop[i]] || in[d.loop[(i + n - 1) % n]]) continue;  // not a run start
      std::vector<SurfacePoint> line{vp(i)};
      for (int j = i + 1; in[d.loop[j % n]]; ++j) line.push_back(vp(j));
      src.polylines.push_back(std::move(line));
    }
  }
  return src;
}

GeodesicSource source_from_vertex_paths(const TriMesh& mesh, const std::vector<std::vector<int>>& paths,
                                       const std::string& description) {
  if (mesh.faces.empty()) throw InvalidInput("vertex path source: the mesh has no faces");
  check_face_indices(mesh);
  const Halfedges he = build_halfedges(mesh.num_vertices(), mesh.faces);
  GeodesicSource src;
  src.description = description;
  for (size_t i = 0; i < paths.size(); ++i) {
    const std::vector<int>& path = paths[i];
    if (path.empty()) continue;
    for (int v : path) {
      if (v < 0 || v >= mesh.num_vertices() || he.is_isolated_vertex(v))
        throw InvalidInput(
            fmt::format("vertex path source: path {} uses vertex {}, which is not a vertex of the surface", i, v));
    }
    std::vector<SurfacePoint> line;
    if (path.size() == 1) {
      line.push_back(surface_point_at_vertex(mesh, path[0]));
    }
    for (size_t k = 0; k + 1 < path.size(); ++k) {
      const int a = path[k], b = path[k + 1];
      // A face holding the edge a-b expresses both ends.
      int face = -1;
      for (int f : he.vertex_faces(a))
        if (corner_of(mesh, f, b) >= 0) face = f;
      if (face < 0 || a == b)
        throw InvalidInput(fmt::format(
            "vertex path source: vertices {} and {} (positions {} and {} of path {}) are not joined by an edge", a,
            b, k, k + 1, i));
      if (k == 0) line.push_back(point_in_face(mesh, face, a, a, 0.0));
      line.push_back(point_in_face(mesh, face, b, b, 0.0));
    }
    src.polylines.push_back(std::move(line));
  }
  if (src.polylines.empty()) throw InvalidInput("vertex path source: no path has a vertex");
  src.vertex_side = source_sides(mesh, src);
  return src;
}

GeodesicSource source_from_vertex(const TriMesh& mesh, int v) {
  GeodesicSource src;
  src.polylines.push_back({surface_point_at_vertex(mesh, v)});
  src.description = fmt::format("vertex {}", v);
  return src;
}

namespace {

// The vertices with a non-zero barycentric coordinate of p.
std::vector<int> support_of(const TriMesh& mesh, const SurfacePoint& p) {
  std::vector<int> vs;
  for (int k = 0; k < 3; ++k)
    if (p.bary[k] != 0.0) vs.push_back(mesh.faces[p.face][k]);
  return vs;
}

// The faces that contain p (around its support).
std::vector<int> faces_containing(const TriMesh& mesh, const Halfedges& he, const SurfacePoint& p) {
  const std::vector<int> vs = support_of(mesh, p);
  if (vs.size() == 3) return {p.face};
  std::vector<int> out;
  for (int f : he.vertex_faces(vs[0])) {
    bool all = true;
    for (int v : vs) all = all && corner_of(mesh, f, v) >= 0;
    if (all) out.push_back(f);
  }
  return out;
}

// p expressed in face f (which contains it), with its exact zeros.
SurfacePoint in_face(const TriMesh& mesh, const SurfacePoint& p, int f) {
  SurfacePoint q;
  q.face = f;
  q.bary = Vec3::Zero();
  for (int k = 0; k < 3; ++k)
    if (p.bary[k] != 0.0) q.bary[corner_of(mesh, f, mesh.faces[p.face][k])] = p.bary[k];
  return q;
}

// Joins p to q along the normal section (see source_from_polyline): the
// intersection of the surface with the plane through both points that
// contains their mean normal, searched as a graph (the plane's crossings of
// the edges and vertices of the faces it cuts, near the two points) for the
// shortest way along it from p to q. Appends the points after p (ending
// with q) to `line`; false when the section does not join them nearby.
bool join_along_section(const TriMesh& mesh, const Halfedges& he, const std::vector<Vec3>& fn, double mean_edge,
                        const SurfacePoint& p, const SurfacePoint& q, std::vector<SurfacePoint>& line) {
  const Vec3 P = surface_point_position(mesh, p), Q = surface_point_position(mesh, q);
  const Vec3 dir = Q - P;
  const double len = dir.norm();
  const std::vector<int> pf = faces_containing(mesh, he, p), qf = faces_containing(mesh, he, q);
  // The surface normal at a point: the mean over the faces that contain it
  // (so that a point on an edge or at a vertex sees both sides alike).
  auto normal_at = [&](const std::vector<int>& faces) {
    Vec3 n = Vec3::Zero();
    for (int f : faces) n += fn[f];
    return n.norm() > 0.0 ? Vec3(n.normalized()) : n;
  };
  Vec3 nav = normal_at(pf) + normal_at(qf);
  Vec3 m = dir.cross(nav);
  if (m.norm() <= 1e-9 * len * std::max(nav.norm(), 1e-300)) return false;  // no plane: the normals are along PQ
  m.normalize();
  auto phi = [&](int v) {
    const double x = m.dot(mesh.vertices[v] - P);
    return std::abs(x) <= 1e-12 * len ? 0.0 : x;
  };
  const Vec3 mid = 0.5 * (P + Q);
  const double reach = 0.75 * len + 3.0 * mean_edge;  // faces farther from the midpoint are not searched
  // Nodes: a vertex on the plane (a == b) or an edge crossing (a < b); then p and q.
  std::map<NodeKey, int> id;
  std::vector<SurfacePoint> point;
  std::vector<Vec3> pos;
  auto node = [&](int f, int a, int b) {
    NodeKey k{std::min(a, b), std::max(a, b)};
    if (const auto it = id.find(k); it != id.end()) return it->second;
    const double t = k.a == k.b ? 0.0 : phi(k.a) / (phi(k.a) - phi(k.b));
    point.push_back(point_in_face(mesh, f, k.a, k.b, t));
    pos.push_back(surface_point_position(mesh, point.back()));
    id.emplace(k, static_cast<int>(point.size()) - 1);
    return static_cast<int>(point.size()) - 1;
  };
  std::vector<std::vector<std::pair<int, double>>> adj;
  auto link = [&](int i, int j) {
    if (adj.size() < point.size()) adj.resize(point.size());
    const double w = (pos[i] - pos[j]).norm();
    adj[i].push_back({j, w});
    adj[j].push_back({i, w});
  };
  // Flood the faces the plane cuts, from p's faces.
  std::vector<char> seen(mesh.num_faces(), 0);
  std::vector<int> stack = pf;
  for (int f : pf) seen[f] = 1;
  std::map<int, std::vector<int>> face_nodes;
  while (!stack.empty()) {
    const int f = stack.back();
    stack.pop_back();
    const auto& t = mesh.faces[f];
    std::vector<int> nodes;
    int zeros = 0;
    for (int k = 0; k < 3; ++k) zeros += phi(t[k]) == 0.0 ? 1 : 0;
    for (int k = 0; k < 3; ++k) {
      const int a = t[k], b = t[(k + 1) % 3];
      const double pa = phi(a), pb = phi(b);
      if (pa == 0.0) nodes.push_back(node(f, a, a));
      if ((pa < 0.0 && pb > 0.0) || (pa > 0.0 && pb < 0.0)) nodes.push_back(node(f, a, b));
    }
    if (nodes.size() < 2 && zeros < 3) continue;  // the plane only touches the face (or misses it)
    face_nodes[f] = nodes;
    for (size_t i = 0; i < nodes.size(); ++i)
      for (size_t j = i + 1; j < nodes.size(); ++j) link(nodes[i], nodes[j]);
    for (int k = 0; k < 3; ++k) {
      const int g = he.neighbor(f, k);
      if (g < 0 || seen[g]) continue;
      const auto& u = mesh.faces[g];
      const Vec3 c = (mesh.vertices[u[0]] + mesh.vertices[u[1]] + mesh.vertices[u[2]]) / 3.0;
      if ((c - mid).norm() > reach) continue;
      seen[g] = 1;
      stack.push_back(g);
    }
    // Faces that share only a vertex on the plane with f.
    for (int k = 0; k < 3; ++k) {
      if (phi(t[k]) != 0.0) continue;
      for (int g : he.vertex_faces(t[k])) {
        if (seen[g]) continue;
        seen[g] = 1;
        stack.push_back(g);
      }
    }
  }
  // p and q join the section in the faces that contain them.
  const int ip = static_cast<int>(point.size());
  point.push_back(p);
  pos.push_back(P);
  const int iq = static_cast<int>(point.size());
  point.push_back(q);
  pos.push_back(Q);
  adj.resize(point.size());
  for (int f : pf)
    if (const auto it = face_nodes.find(f); it != face_nodes.end())
      for (int n : it->second) link(ip, n);
  for (int f : qf)
    if (const auto it = face_nodes.find(f); it != face_nodes.end())
      for (int n : it->second) link(iq, n);
  // Dijkstra from p to q.
  std::vector<double> dist(point.size(), std::numeric_limits<double>::infinity());
  std::vector<int> prev(point.size(), -1);
  using Item = std::pair<double, int>;
  std::priority_queue<Item, std::vector<Item>, std::greater<Item>> queue;
  dist[ip] = 0.0;
  queue.push({0.0, ip});
  while (!queue.empty()) {
    const auto [d, i] = queue.top();
    queue.pop();
    if (d > dist[i]) continue;
    if (i == iq) break;
    for (const auto& [j, w] : adj[i]) {
      if (d + w < dist[j]) {
        dist[j] = d + w;
        prev[j] = i;
        queue.push({d + w, j});
      }
    }
  }
  if (!std::isfinite(dist[iq]) || dist[iq] > 3.0 * len + 1e-9) return false;
  std::vector<int> chain;
  for (int i = iq; i != ip; i = prev[i]) chain.push_back(i);
  for (auto it = chain.rbegin(); it != chain.rend(); ++it) line.push_back(point[*it]);
  return true;
}

// Joins p to q on the surface: directly when they share a face, else along
// the normal section, else (the section leaves the surface or folds back)
// along the shortest path between them. False when no path joins them.
bool join_on_surface(const TriMesh& mesh, const Halfedges& he, const std::vector<Vec3>& fn, double mean_edge,
                     const SurfacePoint& p, const SurfacePoint& q, std::vector<SurfacePoint>& line) {
  if ((surface_point_position(mesh, q) - surface_point_position(mesh, p)).norm() == 0.0) return true;
  const std::vector<int> pf = faces_containing(mesh, he, p);
  for (int f : faces_containing(mesh, he, q)) {
    if (std::find(pf.begin(), pf.end(), f) != pf.end()) {
      line.push_back(in_face(mesh, q, f));
      return true;
    }
  }
  if (join_along_section(mesh, he, fn, mean_edge, p, q, line)) return true;
  try {
    const GeodesicPath path = geodesic_path(mesh, p, q);
    for (size_t i = 1; i < path.points.size(); ++i) line.push_back(path.points[i].point);
    return true;
  } catch (const TopologyError&) {
    return false;
  }
}

// Near-degenerate projections: a barycentric coordinate below 1e-9 is a
// point on the opposite edge (or at a vertex), exactly.
SurfacePoint snap_to_edges(SurfacePoint p) {
  double sum = 0.0;
  for (int k = 0; k < 3; ++k) {
    if (p.bary[k] < 1e-9) p.bary[k] = 0.0;
    sum += p.bary[k];
  }
  p.bary /= sum;
  return p;
}

}  // namespace

GeodesicSource source_from_polyline(const TriMesh& mesh, const std::vector<Vec3>& points) {
  if (points.empty()) throw InvalidInput("polyline source: the polyline has no points");
  if (mesh.faces.empty()) throw InvalidInput("polyline source: the mesh has no faces");
  check_face_indices(mesh);
  for (size_t i = 0; i < points.size(); ++i)
    if (!points[i].allFinite()) throw InvalidInput(fmt::format("polyline source: point {} is not finite", i));
  const Halfedges he = build_halfedges(mesh.num_vertices(), mesh.faces);
  const std::vector<Vec3> fn = face_normals(mesh);
  const double mean_edge = edge_length_stats(mesh).mean;
  std::vector<SurfacePoint> proj;
  for (const Vec3& p : points) proj.push_back(snap_to_edges(closest_surface_point(mesh, p)));
  std::vector<SurfacePoint> line{proj[0]};
  for (size_t i = 0; i + 1 < proj.size(); ++i) {
    if (!join_on_surface(mesh, he, fn, mean_edge, line.back(), proj[i + 1], line))
      throw InvalidInput(fmt::format(
          "polyline source: points {} and {} lie on different parts of the surface (no path on it joins them); "
          "move them onto one part",
          i, i + 1));
  }
  // Drop repeated points (a polyline point that falls on the previous one).
  std::vector<SurfacePoint> clean;
  for (const SurfacePoint& p : line)
    if (clean.empty() ||
        (surface_point_position(mesh, p) - surface_point_position(mesh, clean.back())).norm() > 0.0)
      clean.push_back(p);
  GeodesicSource src;
  src.polylines.push_back(std::move(clean));
  src.description = fmt::format("polyline of {} points", points.size());
  src.vertex_side = source_sides(mesh, src);
  return src;
}

}  // namespace knitforge
