#include "knitforge/geometry/isocurves.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numeric>
#include <utility>

#include <fmt/core.h>

#include "knitforge/geometry/halfedges.h"
#include "knitforge/geometry/mesh_measures.h"
#include "knitforge/util/errors.h"

namespace knitforge {

namespace {

// One isocurve segment between two isocurve nodes. Node ids: a vertex v is
// v, a crossing point on edge e is num_vertices + e.
struct Segment {
  int a = -1;
  int b = -1;
  int face_ab = -1;  // face reported when walking a -> b (the right side)
  int face_ba = -1;  // face reported when walking b -> a
  int pref = 0;      // +1: a -> b is the n x grad F direction, -1: b -> a, 0: none
};

struct Context {
  const TriMesh& mesh;
  const std::vector<double>& field;
  Halfedges he;
  std::vector<int> edge_lo, edge_hi;  // canonical edge endpoints (lo < hi)
  double tol = 0.0;
};

int sign_of(double value, double level, double tol) {
  const double d = value - level;
  if (std::abs(d) <= tol) return 0;
  return d > 0.0 ? 1 : -1;
}

void check_field(const TriMesh& mesh, const std::vector<double>& field, const char* who) {
  if (static_cast<int>(field.size()) != mesh.num_vertices()) {
    throw InvalidInput(fmt::format("{}: the field has {} values but the mesh has {} vertices; give "
                                   "one value per vertex",
                                   who, field.size(), mesh.num_vertices()));
  }
  for (size_t v = 0; v < field.size(); ++v) {
    if (!std::isfinite(field[v])) {
      throw InvalidInput(
          fmt::format("{}: the field value of vertex {} is not finite ({})", who, v, field[v]));
    }
  }
}

Context make_context(const TriMesh& mesh, const std::vector<double>& field,
                     const IsocurveOptions& options, const char* who) {
  check_field(mesh, field, who);
  if (!std::isfinite(options.tolerance) || options.tolerance < 0.0 ||
      !std::isfinite(options.relative_tolerance) || options.relative_tolerance < 0.0) {
    throw InvalidInput(fmt::format("{}: tolerances must be finite and >= 0 (tolerance {}, "
                                   "relative_tolerance {})",
                                   who, options.tolerance, options.relative_tolerance));
  }
  Context ctx{mesh, field, build_halfedges(mesh.num_vertices(), mesh.faces), {}, {}, 0.0};
  ctx.edge_lo.assign(ctx.he.num_edges(), -1);
  ctx.edge_hi.assign(ctx.he.num_edges(), -1);
  for (int h = 0; h < ctx.he.num_halfedges(); ++h) {
    const int e = ctx.he.edge(h);
    if (ctx.edge_lo[e] < 0) {
      ctx.edge_lo[e] = std::min(ctx.he.from(h), ctx.he.to(h));
      ctx.edge_hi[e] = std::max(ctx.he.from(h), ctx.he.to(h));
    }
  }
  double range = 0.0;
  if (!field.empty()) {
    const auto [mn, mx] = std::minmax_element(field.begin(), field.end());
    range = *mx - *mn;
  }
  ctx.tol = std::max(options.tolerance, options.relative_tolerance * range);
  return ctx;
}

// Appends the isocurve segments of face f at `level` (face round of §3.A.2).
void face_segments(const Context& ctx, int f, double level, std::vector<Segment>& out) {
  const Halfedges& he = ctx.he;
  const int nv = ctx.mesh.num_vertices();
  int s[3];
  int zeros = 0;
  for (int k = 0; k < 3; ++k) {
    s[k] = sign_of(ctx.field[ctx.mesh.faces[f][k]], level, ctx.tol);
    if (s[k] == 0) ++zeros;
  }
  if (zeros >= 2) {
    // On-level edges; each is emitted by exactly one of its faces (the one
    // holding the smaller half-edge), whichever of them is flat.
    for (int k = 0; k < 3; ++k) {
      if (s[k] != 0 || s[(k + 1) % 3] != 0) continue;
      const int h = he.halfedge(f, k);
      const int o = he.opposite(h);
      if (o >= 0 && o < h) continue;
      const int sl = s[(k + 2) % 3];
      const int sr =
          o >= 0 ? sign_of(ctx.field[he.to(he.next(o))], level, ctx.tol) : 0;
      if (sl == 0 && sr == 0) continue;  // inside a flat region or flat on the boundary
      Segment seg;
      seg.a = he.from(h);
      seg.b = he.to(h);
      // face(h) lies to the left of a -> b.
      const int left = f, right = o >= 0 ? he.face(o) : -1;
      seg.face_ab = right >= 0 ? right : left;
      seg.face_ba = left;
      seg.pref = sl < sr ? 1 : (sl > sr ? -1 : 0);
      out.push_back(seg);
    }
    return;
  }
  // zeros <= 1: walk the face counter-clockwise and record where the sign
  // changes from - to + (mp) and from + to - (pm). With the larger values to
  // the right, the segment runs from mp to pm.
  int mp = -1, pm = -1;
  for (int k = 0; k < 3; ++k) {
    const int k1 = (k + 1) % 3;
    if (s[k] * s[k1] < 0) {
      const int node = nv + he.edge(he.halfedge(f, k));
      (s[k] < 0 ? mp : pm) = node;
    }
    if (s[k] == 0) {
      const int sp = s[(k + 2) % 3], sn = s[k1];
      if (sp * sn < 0) (sp < 0 ? mp : pm) = ctx.mesh.faces[f][k];
    }
  }
  if (mp >= 0 && pm >= 0) out.push_back(Segment{mp, pm, f, f, 1});
}

// Joins the segments of one level into maximal manifold chains.
std::vector<Isocurve> assemble(const Context& ctx, double level, const std::vector<Segment>& segs) {
  std::vector<Isocurve> curves;
  if (segs.empty()) return curves;
  const int nv = ctx.mesh.num_vertices();
  std::vector<int> nodes;
  nodes.reserve(2 * segs.size());
  for (const Segment& s : segs) {
    nodes.push_back(s.a);
    nodes.push_back(s.b);
  }
  std::sort(nodes.begin(), nodes.end());
  nodes.erase(std::unique(nodes.begin(), nodes.end()), nodes.end());
  const int nn = static_cast<int>(nodes.size());
  auto local = [&](int node) {
    return static_cast<int>(std::lower_bound(nodes.begin(), nodes.end(), node) - nodes.begin());
  };
  const int ns = static_cast<int>(segs.size());
  std::vector<int> la(ns), lb(ns);
  std::vector<int> start(nn + 1, 0);
  for (int i = 0; i < ns; ++i) {
    la[i] = local(segs[i].a);
    lb[i] = local(segs[i].b);
    ++start[la[i] + 1];
    ++start[lb[i] + 1];
  }
  for (int n = 0; n < nn; ++n) start[n + 1] += start[n];
  std::vector<int> adj(start[nn]);
  {
    std::vector<int> fill(start.begin(), start.end() - 1);
    for (int i = 0; i < ns; ++i) {
      adj[fill[la[i]]++] = i;
      adj[fill[lb[i]]++] = i;
    }
  }
  auto degree = [&](int n) { return start[n + 1] - start[n]; };
  std::vector<char> used(ns, 0);

  auto emit = [&](std::vector<int> chain_nodes, std::vector<int> chain_segs, bool closed) {
    // chain_nodes are local node ids; chain_segs[i] joins nodes i and i+1.
    int votes = 0;
    for (size_t i = 0; i < chain_segs.size(); ++i) {
      const Segment& s = segs[chain_segs[i]];
      const bool forward = la[chain_segs[i]] == chain_nodes[i];
      votes += forward ? s.pref : -s.pref;
    }
    if (votes < 0) {
      if (closed) {
        // Keep the first node, reverse the cycle.
        std::reverse(chain_nodes.begin() + 1, chain_nodes.end());
        std::reverse(chain_segs.begin(), chain_segs.end());
      } else {
        std::reverse(chain_nodes.begin(), chain_nodes.end());
        std::reverse(chain_segs.begin(), chain_segs.end());
      }
    }
    Isocurve c;
    c.value = level;
    c.closed = closed;
    const int np = static_cast<int>(chain_nodes.size());
    c.points.reserve(np);
    c.positions.reserve(np);
    for (int ln : chain_nodes) {
      const int node = nodes[ln];
      if (node < nv) {
        c.points.push_back(MeshPoint::at_vertex(node));
        c.positions.push_back(ctx.mesh.vertices[node]);
      } else {
        const int e = node - nv;
        const int lo = ctx.edge_lo[e], hi = ctx.edge_hi[e];
        const double f0 = ctx.field[lo], f1 = ctx.field[hi];
        double t = (level - f0) / (f1 - f0);
        t = std::clamp(t, 0.0, 1.0);
        c.points.push_back(MeshPoint::on_edge(lo, hi, t));
        c.positions.push_back((1.0 - t) * ctx.mesh.vertices[lo] + t * ctx.mesh.vertices[hi]);
      }
    }
    c.faces.reserve(chain_segs.size());
    for (size_t i = 0; i < chain_segs.size(); ++i) {
      const int si = chain_segs[i];
      const bool forward = la[si] == chain_nodes[i];
      c.faces.push_back(forward ? segs[si].face_ab : segs[si].face_ba);
    }
    if (!closed) {
      c.starts_at_junction = degree(chain_nodes.front()) > 2;
      c.ends_at_junction = degree(chain_nodes.back()) > 2;
    }
    curves.push_back(std::move(c));
  };

  auto other_end = [&](int seg, int n) { return la[seg] == n ? lb[seg] : la[seg]; };
  auto next_unused = [&](int n) {
    for (int k = start[n]; k < start[n + 1]; ++k)
      if (!used[adj[k]]) return adj[k];
    return -1;
  };

  // Open chains: from every node that is not of degree 2.
  for (int n = 0; n < nn; ++n) {
    if (degree(n) == 2) continue;
    for (int seg = next_unused(n); seg >= 0; seg = next_unused(n)) {
      std::vector<int> cn{n}, cs;
      int cur = n;
      while (seg >= 0) {
        used[seg] = 1;
        cs.push_back(seg);
        cur = other_end(seg, cur);
        cn.push_back(cur);
        if (degree(cur) != 2) break;
        seg = next_unused(cur);
      }
      emit(std::move(cn), std::move(cs), false);
    }
  }
  // Closed chains: what is left has degree 2 everywhere.
  for (int s0 = 0; s0 < ns; ++s0) {
    if (used[s0]) continue;
    const int n0 = la[s0];
    std::vector<int> cn{n0}, cs;
    int cur = n0, seg = s0;
    while (seg >= 0) {
      used[seg] = 1;
      cs.push_back(seg);
      cur = other_end(seg, cur);
      if (cur == n0) break;
      cn.push_back(cur);
      seg = next_unused(cur);
    }
    emit(std::move(cn), std::move(cs), true);
  }
  return curves;
}

}  // namespace

double Isocurve::length() const {
  double len = 0.0;
  for (size_t i = 1; i < positions.size(); ++i) len += (positions[i] - positions[i - 1]).norm();
  if (closed && positions.size() > 1) len += (positions.front() - positions.back()).norm();
  return len;
}

std::vector<Isocurve> extract_isocurve(const TriMesh& mesh, const std::vector<double>& field,
                                       double value, const IsocurveOptions& options) {
  auto all = extract_isocurves(mesh, field, std::vector<double>{value}, options);
  return std::move(all.front());
}

std::vector<std::vector<Isocurve>> extract_isocurves(const TriMesh& mesh,
                                                     const std::vector<double>& field,
                                                     const std::vector<double>& values,
                                                     const IsocurveOptions& options) {
  for (size_t i = 0; i < values.size(); ++i) {
    if (!std::isfinite(values[i])) {
      throw InvalidInput(fmt::format("extract_isocurves: level {} is not finite ({})", i, values[i]));
    }
  }
  const Context ctx = make_context(mesh, field, options, "extract_isocurves");
  const int nl = static_cast<int>(values.size());
  std::vector<std::pair<double, int>> sorted(nl);
  for (int i = 0; i < nl; ++i) sorted[i] = {values[i], i};
  std::sort(sorted.begin(), sorted.end());
  std::vector<std::vector<Segment>> buckets(nl);
  for (int f = 0; f < mesh.num_faces(); ++f) {
    const auto& t = mesh.faces[f];
    const double a = field[t[0]], b = field[t[1]], c = field[t[2]];
    const double lo = std::min({a, b, c}) - ctx.tol, hi = std::max({a, b, c}) + ctx.tol;
    auto it = std::lower_bound(sorted.begin(), sorted.end(), std::pair<double, int>{lo, -1});
    for (; it != sorted.end() && it->first <= hi; ++it) face_segments(ctx, f, it->first, buckets[it->second]);
  }
  std::vector<std::vector<Isocurve>> result(nl);
  for (int i = 0; i < nl; ++i) result[i] = assemble(ctx, values[i], buckets[i]);
  return result;
}

std::vector<double> isocurve_levels(double first, double last, double spacing) {
  if (!std::isfinite(first) || !std::isfinite(last) || !std::isfinite(spacing) || spacing <= 0.0) {
    throw InvalidInput(fmt::format("isocurve_levels: need finite first/last and a positive spacing "
                                   "(got first {}, last {}, spacing {})",
                                   first, last, spacing));
  }
  std::vector<double> levels;
  const double count = std::floor((last - first) / spacing + 1e-9);
  if (count < 0.0) return levels;
  if (count > 1e8) {
    throw InvalidInput(fmt::format("isocurve_levels: {} levels requested; use a larger spacing", count));
  }
  const int n = static_cast<int>(count);
  levels.reserve(n + 1);
  for (int k = 0; k <= n; ++k) levels.push_back(first + k * spacing);
  return levels;
}

std::vector<Vec3> field_face_gradients(const TriMesh& mesh, const std::vector<double>& field) {
  if (static_cast<int>(field.size()) != mesh.num_vertices()) {
    throw InvalidInput(fmt::format("field_face_gradients: the field has {} values but the mesh has "
                                   "{} vertices",
                                   field.size(), mesh.num_vertices()));
  }
  std::vector<Vec3> grads(mesh.num_faces(), Vec3::Zero());
  for (int f = 0; f < mesh.num_faces(); ++f) {
    const auto& t = mesh.faces[f];
    const Vec3& p0 = mesh.vertices[t[0]];
    const Vec3& p1 = mesh.vertices[t[1]];
    const Vec3& p2 = mesh.vertices[t[2]];
    const Vec3 area_vec = (p1 - p0).cross(p2 - p0);
    const double a2 = area_vec.squaredNorm();
    if (!(a2 > 0.0)) continue;
    // grad = sum_i f_i (N x e_i) / (2A), e_i the edge opposite vertex i; with
    // area_vec = 2A N this is sum_i f_i (area_vec x e_i) / |area_vec|^2.
    const Vec3 g = field[t[0]] * area_vec.cross(p2 - p1) + field[t[1]] * area_vec.cross(p0 - p2) +
                   field[t[2]] * area_vec.cross(p1 - p0);
    grads[f] = g / a2;
  }
  return grads;
}

std::vector<Vec3> wale_directions(const TriMesh& mesh, const std::vector<double>& field) {
  std::vector<Vec3> dirs = field_face_gradients(mesh, field);
  for (int f = 0; f < mesh.num_faces(); ++f) {
    const Vec3 n = face_normal(mesh, f);
    const Vec3 d = n.cross(dirs[f]);
    const double len = d.norm();
    dirs[f] = len > 0.0 ? Vec3(d / len) : Vec3(Vec3::Zero());
  }
  return dirs;
}

}  // namespace knitforge
