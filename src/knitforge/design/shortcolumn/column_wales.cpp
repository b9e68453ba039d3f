#include "knitforge/design/shortcolumn/column_wales.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <queue>
#include <set>
#include <tuple>
#include <utility>

#include <fmt/format.h>

#include "knitforge/geometry/geodesic_distance.h"
#include "knitforge/geometry/geodesic_source.h"
#include "knitforge/geometry/halfedges.h"
#include "knitforge/geometry/isocurves.h"
#include "knitforge/geometry/mesh_measures.h"
#include "knitforge/geometry/resample_polyline.h"
#include "knitforge/geometry/split_mesh_along_path.h"
#include "knitforge/geometry/split_nonmanifold_vertices.h"
#include "knitforge/util/errors.h"

namespace knitforge {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

using Edge = std::pair<int, int>;
Edge key(int a, int b) { return a < b ? Edge{a, b} : Edge{b, a}; }

/// The remaining region R with its front.
struct Region {
  TriMesh mesh;
  std::vector<double> f;
  std::set<Edge> front;      ///< undirected front edges
  int point = -1;            ///< the front is this single vertex (a point start), else -1
  std::vector<int> samples;  ///< global sample ids along the front, bottom to top
  double tau = -kInf;        ///< reference value (max f of the previous whole wale)
  bool force_whole = false;  ///< the last partial advance produced no isocurve
};

/// The front as a chain of region vertices in wale order (bottom to top).
std::vector<int> front_chain(const Region& r, const Halfedges& he) {
  if (r.point >= 0) return {r.point};
  std::vector<int> best;
  for (const std::vector<int>& loop : he.boundary_loops()) {
    const int n = static_cast<int>(loop.size());
    std::vector<char> is_front(static_cast<size_t>(n), 0);  // edge loop[i] -> loop[i+1]
    int count = 0;
    for (int i = 0; i < n; ++i) {
      is_front[static_cast<size_t>(i)] = r.front.count(key(loop[i], loop[(i + 1) % n])) ? 1 : 0;
      count += is_front[static_cast<size_t>(i)];
    }
    if (count == 0 || count == n) continue;  // no front, or a closed front (an island)
    // Start after a non-front edge so that no run wraps.
    int start = 0;
    while (is_front[static_cast<size_t>((start + n - 1) % n)]) start = (start + 1) % n;
    for (int k = 0; k < n;) {
      const int i = (start + k) % n;
      if (!is_front[static_cast<size_t>(i)]) {
        ++k;
        continue;
      }
      std::vector<int> run{loop[i]};
      while (k < n && is_front[static_cast<size_t>((start + k) % n)]) {
        run.push_back(loop[(start + k + 1) % n]);
        ++k;
      }
      if (run.size() > best.size()) best = run;
    }
  }
  // The loop runs with R on its left; wales run with larger f (R) on their right.
  std::reverse(best.begin(), best.end());
  return best;
}

/// Distance field from `sources` (chains of region vertices) on a band of
/// the region that holds the level `level`.
struct BandField {
  TriMesh band;
  std::vector<int> to_region;    ///< band vertex -> region vertex
  std::vector<int> from_region;  ///< region vertex -> band vertex or -1
  std::vector<double> d;         ///< per band vertex
};

BandField band_distance(const TriMesh& R, const Halfedges& he, const std::vector<std::vector<int>>& sources,
                        double level, double radius0, double tolerance, int& growths) {
  const int n = R.num_vertices();
  const int nf = R.num_faces();
  double radius = radius0;
  for (int attempt = 0;; ++attempt) {
    // Dijkstra along edges from the sources, up to the radius.
    std::vector<double> dist(static_cast<size_t>(n), kInf);
    using Item = std::pair<double, int>;
    std::priority_queue<Item, std::vector<Item>, std::greater<Item>> pq;
    for (const auto& s : sources)
      for (int v : s) {
        dist[static_cast<size_t>(v)] = 0.0;
        pq.push({0.0, v});
      }
    while (!pq.empty()) {
      const auto [dv, v] = pq.top();
      pq.pop();
      if (dv > dist[static_cast<size_t>(v)] || dv > radius) continue;
      for (int w : he.vertex_neighbors(v)) {
        const double nd = dv + (R.vertices[v] - R.vertices[w]).norm();
        if (nd < dist[static_cast<size_t>(w)]) {
          dist[static_cast<size_t>(w)] = nd;
          pq.push({nd, w});
        }
      }
    }
    const bool whole = attempt >= 4;
    std::vector<char> in(static_cast<size_t>(nf), 0);
    for (int f = 0; f < nf; ++f) {
      bool any = whole;
      for (int v : R.faces[f]) any = any || dist[static_cast<size_t>(v)] <= radius;
      in[static_cast<size_t>(f)] = any ? 1 : 0;
    }
    // A vertex whose band faces form several fans would make the band
    // non-manifold: take all its faces.
    for (bool changed = true; changed;) {
      changed = false;
      for (int v = 0; v < n; ++v) {
        if (he.is_isolated_vertex(v)) continue;
        const std::vector<int> fan = he.vertex_faces(v);
        int groups = 0, total = 0;
        for (size_t k = 0; k < fan.size(); ++k) {
          const bool cur = in[static_cast<size_t>(fan[k])];
          total += cur;
          const bool prev = k > 0 ? in[static_cast<size_t>(fan[k - 1])] : (he.is_boundary_vertex(v) ? false : in[static_cast<size_t>(fan.back())]);
          if (cur && !prev) ++groups;
        }
        if (total > 0 && total < static_cast<int>(fan.size()) && groups == 0) groups = 1;
        if (groups > 1) {
          for (int f : fan) in[static_cast<size_t>(f)] = 1;
          changed = true;
        }
      }
    }
    BandField b;
    b.from_region.assign(static_cast<size_t>(n), -1);
    for (int f = 0; f < nf; ++f) {
      if (!in[static_cast<size_t>(f)]) continue;
      std::array<int, 3> t{};
      for (int k = 0; k < 3; ++k) {
        const int v = R.faces[f][k];
        int& id = b.from_region[static_cast<size_t>(v)];
        if (id < 0) {
          id = b.band.num_vertices();
          b.band.vertices.push_back(R.vertices[v]);
          b.to_region.push_back(v);
        }
        t[static_cast<size_t>(k)] = id;
      }
      b.band.faces.push_back(t);
    }
    // Artificial border: band edges whose other face exists but is not in the band.
    std::vector<char> artificial(static_cast<size_t>(b.band.num_vertices()), 0);
    bool any_artificial = false;
    for (int f = 0; f < nf; ++f) {
      if (!in[static_cast<size_t>(f)]) continue;
      for (int k = 0; k < 3; ++k) {
        const int o = he.neighbor(f, k);
        if (o >= 0 && !in[static_cast<size_t>(o)]) {
          artificial[static_cast<size_t>(b.from_region[static_cast<size_t>(R.faces[f][k])])] = 1;
          artificial[static_cast<size_t>(b.from_region[static_cast<size_t>(R.faces[f][(k + 1) % 3])])] = 1;
          any_artificial = true;
        }
      }
    }
    GeodesicSource src;
    for (const auto& s : sources) {
      std::vector<SurfacePoint> pl;
      for (int v : s) pl.push_back(surface_point_at_vertex(b.band, b.from_region[static_cast<size_t>(v)]));
      src.polylines.push_back(std::move(pl));
    }
    src.description = "active curve";
    GeodesicOptions go;
    go.tolerance = tolerance;
    go.signed_field = false;
    b.d = geodesic_distance(b.band, src, go).distance;
    bool ok = true;
    if (any_artificial)
      for (int v = 0; v < b.band.num_vertices() && ok; ++v)
        if (artificial[static_cast<size_t>(v)] && b.d[static_cast<size_t>(v)] <= level * (1.0 + 1e-6)) ok = false;
    if (ok || whole) return b;
    radius *= 2.0;
    ++growths;
  }
}

/// Max of the piecewise-linear `f` over {d <= level} on the band.
double max_over_disk(const BandField& b, const std::vector<double>& fR, double level) {
  double m = -kInf;
  auto fv = [&](int v) { return fR[static_cast<size_t>(b.to_region[static_cast<size_t>(v)])]; };
  for (int v = 0; v < b.band.num_vertices(); ++v)
    if (b.d[static_cast<size_t>(v)] <= level) m = std::max(m, fv(v));
  for (const auto& t : b.band.faces) {
    for (int k = 0; k < 3; ++k) {
      const int u = t[k], w = t[(k + 1) % 3];
      const double du = b.d[static_cast<size_t>(u)], dw = b.d[static_cast<size_t>(w)];
      if ((du <= level) != (dw <= level) && std::isfinite(du) && std::isfinite(dw)) {
        const double s = (level - du) / (dw - du);
        m = std::max(m, (1 - s) * fv(u) + s * fv(w));
      }
    }
  }
  return m;
}

/// Arc-length parameters of a chain.
std::vector<double> chain_params(const TriMesh& R, const std::vector<int>& chain) {
  std::vector<double> s(chain.size(), 0.0);
  for (size_t k = 1; k < chain.size(); ++k)
    s[k] = s[k - 1] + (R.vertices[chain[k]] - R.vertices[chain[k - 1]]).norm();
  return s;
}

/// Parameter along the chain of the nearest point to p.
double project_on_chain(const TriMesh& R, const std::vector<int>& chain, const std::vector<double>& s, const Vec3& p,
                        double* distance = nullptr) {
  if (chain.size() == 1) {
    if (distance) *distance = (p - R.vertices[chain[0]]).norm();
    return 0.0;
  }
  double best = kInf, param = 0.0;
  for (size_t k = 0; k + 1 < chain.size(); ++k) {
    const Vec3& a = R.vertices[chain[k]];
    const Vec3& b = R.vertices[chain[k + 1]];
    const Vec3 ab = b - a;
    const double len2 = ab.squaredNorm();
    const double t = len2 > 0 ? std::clamp((p - a).dot(ab) / len2, 0.0, 1.0) : 0.0;
    const double d = (a + t * ab - p).norm();
    if (d < best) {
      best = d;
      param = s[k] + t * (s[k + 1] - s[k]);
    }
  }
  if (distance) *distance = best;
  return param;
}

/// One piece of the isocurve d = sw: a new wale; or several pieces joined
/// along the surface boundary (join_arcs_along_boundary()).
struct Arc {
  /// The isocurve pieces, in region ids (one unless joined), in wale order;
  /// the region is cut along each.
  std::vector<std::vector<MeshPoint>> paths;
  std::vector<Vec3> pos;  ///< the wale: the pieces and the boundary between them
  /// Index ranges [first, last] of `pos` that run along the surface boundary
  /// between two joined pieces (no front there afterwards).
  std::vector<std::pair<int, int>> rim_gaps;
  bool start_front = false, end_front = false;
  double s_start = 0.0, s_end = 0.0;  ///< chain parameters of the ends on the front
  int p = -1, q = -1;                 ///< sample range on the old front (even indices), -1 = none
  std::vector<int> samples;           ///< the new wale's global samples
  std::vector<char> on_rim;           ///< per sample: in a rim gap (not front afterwards)
};

/// Joins arcs that are consecutive along the boundary of the region R with
/// the stretch of boundary between them, when that stretch is surface
/// boundary (no front edge) inside the removed part (every vertex of it
/// nearer than `level` to the active curve, d from `bf`): the front there
/// lies along the rim, and the isocurve d = level leaves the surface and
/// comes back. Without the join each piece would get its own strip, and the
/// old front samples facing the stretch would go to one of them (strips
/// whose old side is much longer than the new, stacked short-row ends) or
/// to none (stitches the knitting order never reaches); joined, the front
/// gets one wale across the stretch it removes, along the rim. The loop
/// runs with R on its left, so from where an arc ends (its right side is
/// kept, d > level) the loop walks into the removed part, towards the start
/// of the next arc. Chains of joins are followed (a front along the rim in
/// several places); a cycle is left as it is. Returns the number of joins.
int join_arcs_along_boundary(const Region& R, const Halfedges& he, const BandField& bf, double level,
                             std::vector<Arc>& arcs) {
  if (arcs.size() < 2) return 0;
  // Boundary positions: loop, edge index (loop[i] -> loop[i + 1]), ratio along it.
  struct LoopPos {
    int loop = -1, edge = -1;
    double t = 0.0;
  };
  const std::vector<std::vector<int>> loops = he.boundary_loops();
  std::map<Edge, std::pair<int, int>> edge_at;  // -> (loop, edge index)
  std::map<int, std::pair<int, int>> vertex_at; // -> (loop, edge index of the edge it starts)
  for (size_t l = 0; l < loops.size(); ++l) {
    const std::vector<int>& lp = loops[l];
    for (size_t i = 0; i < lp.size(); ++i) {
      edge_at[key(lp[i], lp[(i + 1) % lp.size()])] = {static_cast<int>(l), static_cast<int>(i)};
      vertex_at[lp[i]] = {static_cast<int>(l), static_cast<int>(i)};
    }
  }
  auto locate = [&](const MeshPoint& p) {
    LoopPos r;
    if (p.is_vertex()) {
      const auto it = vertex_at.find(p.v0);
      if (it == vertex_at.end()) return r;
      r.loop = it->second.first, r.edge = it->second.second;
    } else if (p.is_edge()) {
      const auto it = edge_at.find(key(p.v0, p.v1));
      if (it == edge_at.end()) return r;
      r.loop = it->second.first, r.edge = it->second.second;
      r.t = loops[static_cast<size_t>(r.loop)][static_cast<size_t>(r.edge)] == p.v0 ? p.ratio : 1.0 - p.ratio;
    } else {
      return r;
    }
    const std::vector<int>& lp = loops[static_cast<size_t>(r.loop)];
    if (R.front.count(key(lp[static_cast<size_t>(r.edge)], lp[(static_cast<size_t>(r.edge) + 1) % lp.size()])))
      r.loop = -1;  // on the front, not on the surface boundary
    return r;
  };
  auto d_at = [&](int v) {
    const int b = bf.from_region[static_cast<size_t>(v)];
    return b < 0 ? kInf : bf.d[static_cast<size_t>(b)];
  };
  const size_t na = arcs.size();
  std::vector<LoopPos> start(na), end(na);
  for (size_t j = 0; j < na; ++j) {
    start[j] = locate(arcs[j].paths.front().front());
    end[j] = locate(arcs[j].paths.back().back());
  }
  // next[j]: the arc whose start follows the end of arc j along the loop
  // across removed surface boundary only; the loop vertices in between.
  std::vector<int> next(na, -1), prev(na, -1);
  std::vector<std::vector<int>> between(na);
  for (size_t j = 0; j < na; ++j) {
    const LoopPos& e = end[j];
    if (e.loop < 0) continue;
    const std::vector<int>& lp = loops[static_cast<size_t>(e.loop)];
    const int n = static_cast<int>(lp.size());
    int best = -1;
    double best_steps = kInf;
    for (size_t k = 0; k < na; ++k) {
      if (k == j || start[k].loop != e.loop) continue;
      double steps = (start[k].edge - e.edge + n) % n + (start[k].t - e.t);
      if (steps <= 0.0) steps += n;
      if (steps < best_steps) best_steps = steps, best = static_cast<int>(k);
    }
    if (best < 0) continue;
    std::vector<int> verts;
    bool ok = true;
    for (int i = e.edge; ok && i != start[static_cast<size_t>(best)].edge; i = (i + 1) % n) {
      const int v = lp[static_cast<size_t>((i + 1) % n)];
      const int w = lp[static_cast<size_t>((i + 2) % n)];
      ok = d_at(v) < level && !R.front.count(key(v, w));
      verts.push_back(v);
    }
    if (!ok || prev[static_cast<size_t>(best)] >= 0) continue;
    next[j] = best;
    prev[static_cast<size_t>(best)] = static_cast<int>(j);
    between[j] = std::move(verts);
  }
  int joins = 0;
  std::vector<Arc> joined;
  std::vector<char> used(na, 0);
  for (size_t j0 = 0; j0 < na; ++j0) {
    if (prev[j0] >= 0 || used[j0]) continue;  // not the first of a chain
    Arc a = std::move(arcs[j0]);
    used[j0] = 1;
    for (size_t j = j0; next[j] >= 0;) {
      const size_t k = static_cast<size_t>(next[j]);
      Arc& b = arcs[k];
      const int g0 = static_cast<int>(a.pos.size()) - 1;  // P, where arc j ends
      for (int v : between[j]) a.pos.push_back(R.mesh.vertices[v]);
      if (!((b.pos.front() - a.pos.back()).norm() < 1e-9)) a.pos.push_back(b.pos.front());
      const int g1 = static_cast<int>(a.pos.size()) - 1;  // Q, where arc k starts
      a.pos.insert(a.pos.end(), b.pos.begin() + 1, b.pos.end());
      a.rim_gaps.push_back({g0, g1});
      for (const auto& [x, y] : b.rim_gaps) a.rim_gaps.push_back({x + g1, y + g1});
      a.paths.insert(a.paths.end(), b.paths.begin(), b.paths.end());
      a.end_front = b.end_front;
      a.s_end = b.s_end;
      used[k] = 1;
      ++joins;
      j = k;
    }
    joined.push_back(std::move(a));
  }
  for (size_t j = 0; j < na; ++j)
    if (!used[j]) joined.push_back(std::move(arcs[j]));  // cycles stay apart
  arcs = std::move(joined);
  return joins;
}

double polyline_distance(const std::vector<Vec3>& pl, const Vec3& p) {
  double best = kInf;
  for (size_t k = 0; k + 1 < pl.size(); ++k)
    best = std::min(best, (closest_point_on_segment(p, pl[k], pl[k + 1]) - p).norm());
  if (pl.size() == 1) best = (pl[0] - p).norm();
  return best;
}

/// Segments of a new wale of length len: the even count nearest to len / sh,
/// at least 2; a short wale with both ends at forks takes 2 (q - p) at most
/// (tessellate_strip() covers B up to twice as long as A without stacking
/// four short-row ends) and more than half of q - p, at least 4 (the old
/// front twice as long as B needs two A-advances at one apex somewhere:
/// four stacked short-row ends), or 2 opposite a 2-segment front part.
int segment_count(double len, double sh, const Arc& a) {
  int n = 2 * std::max(1, static_cast<int>(std::lround(len / (2.0 * sh))));
  if (a.start_front && a.end_front && a.p >= 0) {
    const int na = a.q - a.p;
    const int at_least = std::max(4, 2 * (na / 4 + 1));
    n = na == 2 ? 2 : std::clamp(n, std::min(at_least, 2 * na), 2 * na);
  }
  return n;
}

double polyline_length(const std::vector<Vec3>& pl) {
  double l = 0.0;
  for (size_t k = 1; k < pl.size(); ++k) l += (pl[k] - pl[k - 1]).norm();
  return l;
}

/// The samples of the new wale `pl` (the arc's positions, its ends moved to
/// the fork samples) of length `len`: equal segments, segment_count() of
/// them. An arc joined along the rim is resampled piece by piece (the
/// isocurve pieces and the rim stretches between them, an even number of
/// segments each, at least 2), so that where it leaves and rejoins the rim
/// are samples of even label, the ends of the front pieces it leaves; when
/// that gives more than twice the segments of the old front it faces
/// (`na`; tessellate_strip() covers no more), it is resampled evenly. Every
/// wale that faces an old front gets at most 2 na segments (e.g. the first
/// wale around a short start interval). Arc::on_rim marks the samples
/// strictly inside a rim stretch.
std::vector<Vec3> resample_wale(const std::vector<Vec3>& pl, double len, double sh, int na, Arc& a) {
  a.on_rim.clear();
  if (!a.rim_gaps.empty()) {
    std::vector<Vec3> pts{pl.front()};
    std::vector<char> rim_flags{0};
    auto part = [&](int i0, int i1, bool rim) {
      const std::vector<Vec3> piece(pl.begin() + i0, pl.begin() + i1 + 1);
      const double l = polyline_length(piece);
      if (piece.size() < 2 || !(l > 0.0)) return;
      const int n = 2 * std::max(1, static_cast<int>(std::lround(l / (2.0 * sh))));
      const ResampledPolyline rs = resample_polyline(piece, l / n, ResampleOptions{false});
      for (size_t k = 1; k < rs.points.size(); ++k) {
        pts.push_back(rs.points[k]);
        rim_flags.push_back(rim && k + 1 < rs.points.size() ? 1 : 0);
      }
    };
    int from = 0;
    for (const auto& [g0, g1] : a.rim_gaps) {
      part(from, g0, false);
      part(g0, g1, true);
      from = g1;
    }
    part(from, static_cast<int>(pl.size()) - 1, false);
    if (na < 0 || static_cast<int>(pts.size()) - 1 <= 2 * na) {
      a.on_rim = std::move(rim_flags);
      return pts;
    }
  }
  int n = segment_count(len, sh, a);
  if (na >= 1) n = std::min(n, 2 * na);
  const ResampledPolyline rs = resample_polyline(pl, len / n, ResampleOptions{false});
  for (size_t k = 0; k < rs.points.size(); ++k) {
    const int seg = rs.segment[k];
    bool rim = false;
    for (const auto& [g0, g1] : a.rim_gaps) rim = rim || (seg >= g0 && seg < g1);
    a.on_rim.push_back(rim ? 1 : 0);
  }
  return rs.points;
}

/// The last strip of a region narrower than a stitch width: between the
/// front's samples and the surface boundary that closes the region, a new
/// wale on the boundary from the front's first to its last even-labelled
/// sample (both ends are forks; their apexes lie on the fabric boundary and
/// become edge stitches in the post-processing). False when there is too
/// little front or boundary for one.
bool last_strip(const Region& R, const Halfedges& he, const std::vector<int>& chain, ColumnWales& out,
                std::vector<char>& increase_apex, std::vector<char>& decrease_apex, std::vector<char>& inside,
                double sh) {
  const std::vector<int>& S = R.samples;
  const int ns = static_cast<int>(S.size());
  if (ns < 3 || chain.size() < 2) return false;
  int fe = 0, le = ns - 1;
  while (fe < ns && out.parity[static_cast<size_t>(S[fe])] != 0) ++fe;
  while (le >= 0 && out.parity[static_cast<size_t>(S[le])] != 0) --le;
  if (!(le - fe >= 4)) return false;
  // The boundary from the front's start X to its end Y: the loop runs with R
  // on its left, so from X it follows the surface boundary to Y.
  const int x = chain.front(), y = chain.back();
  std::vector<int> path;
  for (const std::vector<int>& loop : he.boundary_loops()) {
    const auto it = std::find(loop.begin(), loop.end(), x);
    if (it == loop.end()) continue;
    const size_t n = loop.size();
    size_t k = static_cast<size_t>(it - loop.begin());
    for (size_t step = 0; step <= n; ++step, k = (k + 1) % n) {
      path.push_back(loop[k]);
      if (loop[k] == y && step > 0) break;
    }
    break;
  }
  if (path.size() < 2 || path.back() != y) return false;
  std::vector<Vec3> pl;
  for (int v : path) pl.push_back(R.mesh.vertices[v]);
  pl.front() = out.samples[static_cast<size_t>(S[fe])];
  pl.back() = out.samples[static_cast<size_t>(S[le])];
  const double len = polyline_length(pl);
  if (!(len >= 2.0 * sh)) return false;
  const int na = le - fe;
  const int n = std::clamp(2 * std::max(1, static_cast<int>(std::lround(len / (2.0 * sh)))), 4, 2 * na);
  const ResampledPolyline rs = resample_polyline(pl, len / n, ResampleOptions{false});
  ColumnStrip st;
  st.a.assign(S.begin() + fe, S.begin() + le + 1);
  for (int k = 0; k <= rs.num_segments; ++k) {
    if (k == 0) {
      st.b.push_back(S[fe]);
    } else if (k == rs.num_segments) {
      st.b.push_back(S[le]);
    } else {
      st.b.push_back(static_cast<int>(out.samples.size()));
      out.samples.push_back(rs.points[static_cast<size_t>(k)]);
      out.parity.push_back(k % 2);
    }
  }
  increase_apex.resize(out.samples.size(), 0);
  decrease_apex.resize(out.samples.size(), 0);
  inside.resize(out.samples.size(), 0);
  st.start_increase = st.end_decrease = true;
  st.column = out.steps++;
  st.short_wale = false;
  std::vector<Vec3> wale;
  for (int id : st.b) wale.push_back(out.samples[static_cast<size_t>(id)]);
  out.wales.push_back(std::move(wale));
  out.strips.push_back(std::move(st));
  ++out.last_strips;
  out.last_strip_area += total_area(R.mesh);
  return true;
}

}  // namespace

ColumnWales extract_column_wales(const TriMesh& mesh, const std::vector<double>& field, const KnitParams& params,
                                 const ColumnWaleOptions& o) {
  const double sw = params.stitch_width, sh = params.stitch_height;
  if (!(sw > 0.0) || !(sh > 0.0) || !std::isfinite(sw) || !std::isfinite(sh))
    throw InvalidInput(fmt::format("short-column wales: stitch size {} x {} mm must be positive", sw, sh));
  if (static_cast<int>(field.size()) != mesh.num_vertices())
    throw InvalidInput(fmt::format("short-column wales: the field has {} values for {} vertices", field.size(),
                                   mesh.num_vertices()));
  for (size_t v = 0; v < field.size(); ++v)
    if (!std::isfinite(field[v]))
      throw InvalidInput(fmt::format("short-column wales: field value of vertex {} is not finite", v));
  if (!(o.min_segment_factor >= 0.0) || !(o.band_factor > 0.0) || !(o.distance_tolerance >= 0.0) ||
      !(o.min_region_stitches >= 0.0))
    throw InvalidInput("short-column wales: min_segment_factor, band_factor, distance_tolerance and "
                       "min_region_stitches must be >= 0 (band > 0)");

  ColumnWales out;
  out.surface_area = total_area(mesh);
  const int max_steps = o.max_steps > 0 ? o.max_steps : static_cast<int>(4.0 * out.surface_area / (sw * sh)) + 100;
  const double tolerance = o.distance_tolerance * sw;

  // The start: the boundary vertices where f is minimal, one run of the loop.
  const Halfedges he0 = build_halfedges(mesh.num_vertices(), mesh.faces);
  const auto loops = he0.boundary_loops();
  if (loops.size() != 1)
    throw TopologyError(fmt::format("short-column wales: the surface has {} boundary loops; it must be a disk", loops.size()));
  double fmin = kInf, fmax = -kInf;
  int argmin = -1;
  for (int v = 0; v < mesh.num_vertices(); ++v) {
    if (he0.is_isolated_vertex(v)) continue;
    if (field[v] < fmin) fmin = field[v], argmin = v;
    fmax = std::max(fmax, field[v]);
  }
  if (!(fmax > fmin)) throw InvalidInput("short-column wales: the field is constant");
  const double ftol = 1e-9 * (fmax - fmin);
  const std::vector<int>& loop = loops.front();
  const int nl = static_cast<int>(loop.size());
  std::vector<char> low(static_cast<size_t>(nl), 0);
  int nlow = 0;
  for (int i = 0; i < nl; ++i) {
    low[static_cast<size_t>(i)] = field[loop[i]] <= fmin + ftol ? 1 : 0;
    nlow += low[static_cast<size_t>(i)];
  }
  if (nlow == 0)
    throw InvalidInput(fmt::format(
        "short-column wales: the field's minimum ({:.6g}) is at interior vertex {}, not on the boundary; wales start "
        "on the boundary (use a harmonic field, or a field whose minimum lies on the boundary)",
        fmin, argmin));
  if (nlow == nl) throw InvalidInput("short-column wales: the field is minimal on the whole boundary");
  int first = 0;
  while (!(low[static_cast<size_t>(first)] && !low[static_cast<size_t>((first + nl - 1) % nl)])) first = (first + 1) % nl;
  std::vector<int> start{loop[first]};
  for (int k = 1; k < nl && low[static_cast<size_t>((first + k) % nl)]; ++k) start.push_back(loop[(first + k) % nl]);
  if (static_cast<int>(start.size()) != nlow)
    throw InvalidInput("short-column wales: the field is minimal on several separate parts of the boundary; the "
                       "start (f = min) must be one interval");

  Region r0;
  r0.mesh = mesh;
  r0.f = field;
  if (start.size() == 1) {
    r0.point = start[0];
  } else {
    for (size_t k = 0; k + 1 < start.size(); ++k) r0.front.insert(key(start[k], start[k + 1]));
  }
  // The first wale: the start interval in wale order (against the loop),
  // when it holds at least one stitch height.
  {
    std::vector<Vec3> pl;
    for (auto it = start.rbegin(); it != start.rend(); ++it) pl.push_back(mesh.vertices[*it]);
    if (pl.size() >= 2 && polyline_length(pl) >= sh) {
      const ResampledPolyline rs = resample_polyline(pl, sh, ResampleOptions{false});
      for (size_t k = 0; k < rs.points.size(); ++k) {
        r0.samples.push_back(static_cast<int>(out.samples.size()));
        out.samples.push_back(rs.points[k]);
        out.parity.push_back(static_cast<int>(k % 2));
      }
      out.wales.push_back(rs.points);
    }
  }

  // Per global sample: already the apex of an Increase / a Decrease; inside
  // the fabric (an interior sample of a strip's new wale, so stitches lie on
  // its left along both its segments: only there may a short column fork off,
  // else the apex would sit on the fabric's edge).
  std::vector<char> increase_apex, decrease_apex, inside;
  auto apex_flags = [&]() {
    increase_apex.resize(out.samples.size(), 0);
    decrease_apex.resize(out.samples.size(), 0);
    inside.resize(out.samples.size(), 0);
  };

  std::vector<Region> stack;
  stack.push_back(std::move(r0));
  while (!stack.empty()) {
    Region R = std::move(stack.back());
    stack.pop_back();
    for (;;) {
      const Halfedges he = build_halfedges(R.mesh.num_vertices(), R.mesh.faces);
      const std::vector<int> chain = front_chain(R, he);
      if (chain.empty()) {
        out.uncovered_area += total_area(R.mesh);
        break;
      }
      if (out.steps > 0 && R.samples.size() < 3) {
        // A front without stitch samples (its piece was dropped): wales
        // advanced from it would have nothing on their left, strips of
        // their own that no course of the fabric reaches. Left uncovered.
        out.uncovered_area += total_area(R.mesh);
        ++out.sampleless_regions;
        break;
      }
      if (out.steps >= max_steps)
        throw SolverError(fmt::format("short-column wales: more than {} advances; the field or the stitch size is "
                                      "unsuitable (the fronts do not leave the surface)",
                                      max_steps));
      const std::vector<double> cs = chain_params(R.mesh, chain);
      double chain_max = -kInf, chain_min = kInf;
      int xstar = chain[0];
      for (int v : chain) {
        chain_max = std::max(chain_max, R.f[static_cast<size_t>(v)]);
        if (R.f[static_cast<size_t>(v)] < chain_min) chain_min = R.f[static_cast<size_t>(v)], xstar = v;
      }
      const double mean_edge = std::max(1e-9, edge_length_stats(R.mesh).mean);
      const double radius = o.band_factor * sw + 2.0 * mean_edge;

      // UpdateReference (Alg. 3.3) and UpdateActiveCurve (Alg. 3.2).
      std::vector<std::vector<int>> runs;
      bool refined = false;
      if (!R.force_whole && R.point < 0 && R.tau > chain_min) {
        double tau = R.tau;
        if (o.refine_reference) {
          const BandField disk = band_distance(R.mesh, he, {{xstar}}, sw, radius, tolerance, out.band_growths);
          const double m = max_over_disk(disk, R.f, sw);
          if (m < tau) {
            tau = m;
            refined = true;
          }
        }
        for (size_t k = 0; k < chain.size();) {
          if (!(R.f[static_cast<size_t>(chain[k])] < tau)) {
            ++k;
            continue;
          }
          size_t e = k;
          while (e < chain.size() && R.f[static_cast<size_t>(chain[e])] < tau) ++e;
          if (cs[e - 1] - cs[k] > o.min_segment_factor * sh)
            runs.emplace_back(chain.begin() + static_cast<long>(k), chain.begin() + static_cast<long>(e));
          k = e;
        }
        if (runs.size() == 1 && runs[0].size() == chain.size()) runs.clear();  // the whole front lags: a whole step
      }
      const bool whole = runs.empty();
      if (whole) runs = {chain};
      R.force_whole = false;

      // Advance: d from C_a, the isocurve d = sw.
      const BandField bf = band_distance(R.mesh, he, runs, sw, radius, tolerance, out.band_growths);
      std::vector<Isocurve> iso = extract_isocurve(bf.band, bf.d, sw);
      bool junction = false;
      for (const Isocurve& c : iso) junction = junction || c.starts_at_junction || c.ends_at_junction;
      double level = sw;
      if (junction) {
        level = sw * (1.0 + 1e-6);
        iso = extract_isocurve(bf.band, bf.d, level);
      }
      std::vector<int> chain_index(static_cast<size_t>(R.mesh.num_vertices()), -1);
      for (size_t k = 0; k < chain.size(); ++k) chain_index[static_cast<size_t>(chain[k])] = static_cast<int>(k);
      std::vector<Arc> arcs;
      for (const Isocurve& c : iso) {
        if (c.closed || c.num_points() < 2 || c.starts_at_junction || c.ends_at_junction) continue;
        Arc a;
        a.paths.emplace_back();
        for (const MeshPoint& p : c.points) {
          MeshPoint q = p;
          q.v0 = bf.to_region[static_cast<size_t>(p.v0)];
          q.v1 = bf.to_region[static_cast<size_t>(p.v1)];
          a.paths.back().push_back(q);
        }
        a.pos = c.positions;
        auto on_front = [&](const MeshPoint& p, double& s) {
          if (p.is_vertex()) {
            const int k = chain_index[static_cast<size_t>(p.v0)];
            if (k < 0) return false;
            s = cs[static_cast<size_t>(k)];
            return true;
          }
          const int k0 = chain_index[static_cast<size_t>(p.v0)], k1 = chain_index[static_cast<size_t>(p.v1)];
          if (k0 < 0 || k1 < 0 || std::abs(k0 - k1) != 1) return false;
          s = (1 - p.ratio) * cs[static_cast<size_t>(k0)] + p.ratio * cs[static_cast<size_t>(k1)];
          return true;
        };
        a.start_front = on_front(a.paths.front().front(), a.s_start);
        a.end_front = on_front(a.paths.back().back(), a.s_end);
        if (a.start_front && a.end_front && a.s_start > a.s_end) {
          std::reverse(a.paths.front().begin(), a.paths.front().end());
          std::reverse(a.pos.begin(), a.pos.end());
          std::swap(a.s_start, a.s_end);
        }
        arcs.push_back(std::move(a));
      }
      if (o.join_along_boundary) out.joined_arcs += join_arcs_along_boundary(R, he, bf, level, arcs);
      if (arcs.empty()) {
        if (whole) {
          // The region is narrower than a stitch width: the last wale is its
          // boundary, and one strip covers it.
          if (!last_strip(R, he, chain, out, increase_apex, decrease_apex, inside, sh)) {
            out.uncovered_area += total_area(R.mesh);
          }
          break;
        }
        R.force_whole = true;
        continue;
      }
      const int column = out.steps++;
      (whole ? out.whole_steps : out.fill_steps) += 1;
      if (refined) ++out.refined_steps;
      if (whole) R.tau = chain_max;

      // Sample ranges on the old front.
      const std::vector<int>& S = R.samples;
      const int ns = static_cast<int>(S.size());
      std::vector<double> sp(static_cast<size_t>(ns));
      for (int k = 0; k < ns; ++k) {
        sp[static_cast<size_t>(k)] = project_on_chain(R.mesh, chain, cs, out.samples[static_cast<size_t>(S[k])]);
        if (k > 0) sp[static_cast<size_t>(k)] = std::max(sp[static_cast<size_t>(k)], sp[static_cast<size_t>(k - 1)]);
      }
      apex_flags();
      // Strips start and end at samples of even label (course parity 0), so
      // that every strip's first course runs left to right as the operators
      // of tessellate_strip() assume.
      auto even = [&](int k) { return out.parity[static_cast<size_t>(S[k])] == 0; };
      // An isocurve piece shorter than half a stitch height (the level d = sw
      // passing around a single vertex of the front that sticks out, or
      // clipping a corner) holds no wale: it cuts the region, owns no front
      // sample (it would break the run of samples facing the real wale
      // there) and makes neither a strip nor a front piece.
      std::vector<char> tiny(arcs.size(), 0);
      for (size_t j = 0; j < arcs.size(); ++j) {
        tiny[j] = polyline_length(arcs[j].pos) < 0.5 * sh ? 1 : 0;
        if (tiny[j]) ++out.tiny_arcs;
      }
      // Each even sample of the old front belongs to its nearest arc, and an
      // arc's strip takes its longest run of samples. An arc that gets no
      // strip (too few samples, no fork possible) owns none either: its
      // samples go to the arcs beside it, and the ranges are found again.
      std::vector<char> no_strip = tiny;
      std::vector<std::pair<bool, bool>> ends(arcs.size());
      for (size_t j = 0; j < arcs.size(); ++j) ends[j] = {arcs[j].start_front, arcs[j].end_front};
      const int moved_before = out.moved_forks;
      const std::vector<char> no_apex(out.samples.size(), 0);
      int first_even = 0, last_even = ns - 1;
      while (first_even < ns && !even(first_even)) ++first_even;
      while (last_even >= 0 && !even(last_even)) --last_even;
      for (bool again = true; again;) {
        again = false;
        out.moved_forks = moved_before;
        for (size_t j = 0; j < arcs.size(); ++j) {
          std::tie(arcs[j].start_front, arcs[j].end_front) = ends[j];
          arcs[j].p = arcs[j].q = -1;
        }
        std::vector<int> owner(static_cast<size_t>(ns), -1);  // even samples: nearest arc
        for (int k = 0; k < ns; ++k) {
          if (!even(k)) continue;
          double best = kInf;
          for (size_t j = 0; j < arcs.size(); ++j) {
            if (no_strip[j]) continue;
            const double dd = polyline_distance(arcs[j].pos, out.samples[static_cast<size_t>(S[k])]);
            if (dd < best) best = dd, owner[static_cast<size_t>(k)] = static_cast<int>(j);
          }
        }
        auto snap = [&](double s, const std::vector<char>& taken) {
          int best = -1;
          double bd = kInf;
          for (int k = 1; k + 1 < ns; ++k) {
            if (!even(k) || taken[static_cast<size_t>(S[k])] || !inside[static_cast<size_t>(S[k])]) continue;
            const double dd = std::abs(sp[static_cast<size_t>(k)] - s);
            if (dd < bd) bd = dd, best = k;
          }
          return best;
        };
        // A fork at arc parameter s goes to the nearest free sample (not
        // already an apex of its type); none: the arc does not fork there.
        auto snap_fork = [&](double s, const std::vector<char>& apex, bool& forks, int& sample) {
          const int k = snap(s, apex);
          if (k >= 0 && k != snap(s, no_apex)) ++out.moved_forks;
          if (k < 0) forks = false;
          else sample = k;
        };
        for (size_t j = 0; j < arcs.size(); ++j) {
          Arc& a = arcs[j];
          if (ns < 3 || tiny[j]) {  // nothing on the left to fork from, or no wale
            a.start_front = a.end_front = false;
            continue;
          }
          int lo = -1, hi = -1, run_lo = -1, best_len = 0;  // longest run of owned even samples
          for (int k = 0; k < ns; ++k) {
            if (!even(k)) continue;
            if (owner[static_cast<size_t>(k)] == static_cast<int>(j)) {
              if (run_lo < 0) run_lo = k;
              if (k - run_lo + 1 > best_len) best_len = k - run_lo + 1, lo = run_lo, hi = k;
            } else {
              run_lo = -1;
            }
          }
          if (a.start_front) snap_fork(a.s_start, increase_apex, a.start_front, lo);
          if (a.end_front) snap_fork(a.s_end, decrease_apex, a.end_front, hi);
          if (!a.start_front && a.end_front && lo < 0) lo = first_even;
          if (a.start_front && !a.end_front && hi < 0) hi = last_even;
          // A short column with both ends at forks needs 4 segments on the old
          // front (2 when it is a single stitch pair): the fork operators of
          // tessellate_strip() start and end with a quad each.
          if (a.start_front && a.end_front && lo >= 0 && hi >= 0 && hi - lo == 2) {
            auto joinable = [&](int k) {
              return k >= 1 && k + 1 < ns && inside[static_cast<size_t>(S[k])] && !decrease_apex[static_cast<size_t>(S[k])];
            };
            auto forkable = [&](int k) {
              return k >= 1 && k + 1 < ns && inside[static_cast<size_t>(S[k])] && !increase_apex[static_cast<size_t>(S[k])];
            };
            if (joinable(hi + 2)) hi += 2;
            else if (forkable(lo - 2)) lo -= 2;
          }
          if (lo >= 0 && hi >= 0 && hi - lo >= 2) {
            a.p = lo;
            a.q = hi;
          } else {
            a.start_front = a.end_front = false;
            if (!no_strip[j] && std::count(owner.begin(), owner.end(), static_cast<int>(j)) > 0) {
              no_strip[j] = 1;
              again = true;
            }
          }
        }
      }
      // Ranges of different arcs must not overlap (disjoint isocurve pieces
      // face disjoint parts of the front; snapping can make them touch).
      std::vector<size_t> order(arcs.size());
      for (size_t j = 0; j < arcs.size(); ++j) order[j] = j;
      std::stable_sort(order.begin(), order.end(), [&](size_t x, size_t y) {
        const double px = arcs[x].p >= 0 ? arcs[x].p : 1e18, py = arcs[y].p >= 0 ? arcs[y].p : 1e18;
        return px < py;
      });
      int last_q = -1;
      for (size_t j : order) {
        Arc& a = arcs[j];
        if (a.p < 0) continue;
        if (a.p < last_q && a.start_front && a.q - last_q >= 2) a.p = last_q;  // touch instead of overlap
        if (a.p < last_q) {  // overlap: this arc gets no strip
          a.p = a.q = -1;
          a.start_front = a.end_front = false;
          continue;
        }
        last_q = a.q;
      }

      // Resample the arcs into the new wales and make the strips.
      for (size_t j : order) {
        Arc& a = arcs[j];
        std::vector<Vec3> pl = a.pos;
        if (a.start_front) pl.front() = out.samples[static_cast<size_t>(S[a.p])];
        if (a.end_front) pl.back() = out.samples[static_cast<size_t>(S[a.q])];
        const double len = polyline_length(pl);
        if (!(len > 0.0) || tiny[j]) {
          a.p = a.q = -1;
          continue;
        }
        const std::vector<Vec3> pts = resample_wale(pl, len, sh, a.p >= 0 ? a.q - a.p : -1, a);
        const int m = static_cast<int>(pts.size()) - 1;
        const int base_parity = a.p >= 0 ? out.parity[static_cast<size_t>(S[a.p])] : 0;
        for (int k = 0; k <= m; ++k) {
          if (k == 0 && a.start_front) {
            a.samples.push_back(S[a.p]);
          } else if (k == m && a.end_front) {
            a.samples.push_back(S[a.q]);
          } else {
            a.samples.push_back(static_cast<int>(out.samples.size()));
            out.samples.push_back(pts[static_cast<size_t>(k)]);
            out.parity.push_back((base_parity + k) % 2);
          }
        }
        apex_flags();
        std::vector<Vec3> wale;
        for (int id : a.samples) wale.push_back(out.samples[static_cast<size_t>(id)]);
        out.wales.push_back(std::move(wale));
        if (a.p >= 0) {
          ColumnStrip st;
          st.a.assign(S.begin() + a.p, S.begin() + a.q + 1);
          st.b = a.samples;
          st.start_increase = a.start_front;
          st.end_decrease = a.end_front;
          st.column = column;
          st.short_wale = !whole;
          for (size_t k = 1; k + 1 < st.b.size(); ++k) inside[static_cast<size_t>(st.b[k])] = 1;
          if (st.start_increase) increase_apex[static_cast<size_t>(S[a.p])] = 1;
          if (st.end_decrease) decrease_apex[static_cast<size_t>(S[a.q])] = 1;
          out.strips.push_back(std::move(st));
        }
      }

      // The new front pieces (see the file comment).
      std::vector<std::vector<int>> pieces;
      {
        std::vector<int> cur;
        int cursor = 0;
        bool open = true;  // the old front before the first arc continues
        // The samples of a wale; one that runs along the rim (joined arcs)
        // is front only off the rim: each stretch on it ends a piece.
        auto append = [&](const Arc& a) {
          // Two arcs that touch share the sample where one rejoins and the next leaves.
          const bool shared = !cur.empty() && cur.back() == a.samples.front();
          for (size_t k = shared ? 1 : 0; k < a.samples.size(); ++k) {
            if (!a.on_rim[k]) {
              cur.push_back(a.samples[k]);
            } else if (!cur.empty()) {
              pieces.push_back(cur);
              cur.clear();
            }
          }
        };
        for (size_t j : order) {
          const Arc& a = arcs[j];
          if (a.samples.empty()) continue;
          if (a.p < 0) {  // a wale with nothing on its left: its own piece(s)
            std::vector<int> before = std::move(cur);
            cur.clear();
            append(a);
            if (!cur.empty()) pieces.push_back(cur);
            cur = std::move(before);
            continue;
          }
          if (a.start_front && open) {
            for (int k = cursor; k < a.p; ++k) cur.push_back(S[k]);
          } else if (!cur.empty()) {
            pieces.push_back(cur);
            cur.clear();
          }
          append(a);
          if (a.end_front) {
            cursor = a.q + 1;
            open = true;
          } else {
            pieces.push_back(cur);
            cur.clear();
            cursor = a.q + 1;
            open = false;
          }
        }
        if (open)
          for (int k = cursor; k < ns; ++k) cur.push_back(S[k]);
        if (!cur.empty()) pieces.push_back(cur);
      }

      // Cut R along the arcs and remove d < sw.
      TriMesh cur = R.mesh;
      std::vector<double> d(static_cast<size_t>(cur.num_vertices()), kInf);
      for (int v = 0; v < bf.band.num_vertices(); ++v) d[static_cast<size_t>(bf.to_region[static_cast<size_t>(v)])] = bf.d[static_cast<size_t>(v)];
      std::vector<double> fcur = R.f;
      std::set<Edge> front = R.front;
      for (const Arc& a : arcs) {
        for (const std::vector<MeshPoint>& path : a.paths) {
          const SplitMeshResult split = split_mesh_along_path(cur, path);
          d = carry_vertex_scalar(cur, split, d);
          fcur = carry_vertex_scalar(cur, split, fcur);
          std::map<Edge, std::vector<std::pair<double, int>>> on_front;
          for (int v = split.original_num_vertices; v < split.mesh.num_vertices(); ++v) {
            const MeshPoint& p = split.new_vertex_origin[static_cast<size_t>(v - split.original_num_vertices)];
            if (!p.is_edge()) continue;
            const Edge e = key(p.v0, p.v1);
            if (!front.count(e)) continue;
            on_front[e].push_back({p.v0 == e.first ? p.ratio : 1.0 - p.ratio, v});
          }
          for (auto& [e, list] : on_front) {
            front.erase(e);
            std::sort(list.begin(), list.end());
            int prev = e.first;
            for (const auto& [t, v] : list) front.insert(key(prev, v)), prev = v;
            front.insert(key(prev, e.second));
          }
          for (size_t k = 0; k + 1 < split.path.size(); ++k) front.insert(key(split.path[k], split.path[k + 1]));
          cur = split.mesh;
        }
      }
      TriMesh kept;
      std::vector<int> remap(static_cast<size_t>(cur.num_vertices()), -1);
      std::vector<double> fk;
      for (const auto& t : cur.faces) {
        const double dc = (d[static_cast<size_t>(t[0])] + d[static_cast<size_t>(t[1])] + d[static_cast<size_t>(t[2])]) / 3.0;
        if (dc < level * (1.0 - 1e-9)) continue;
        std::array<int, 3> nt{};
        for (int k = 0; k < 3; ++k) {
          int& id = remap[static_cast<size_t>(t[k])];
          if (id < 0) {
            id = kept.num_vertices();
            kept.vertices.push_back(cur.vertices[t[k]]);
            fk.push_back(fcur[static_cast<size_t>(t[k])]);
          }
          nt[static_cast<size_t>(k)] = id;
        }
        kept.faces.push_back(nt);
      }
      if (kept.faces.empty()) {
        // Nothing left ahead: the pieces end here.
        break;
      }
      // Removing d < sw can leave parts of R touching at single vertices.
      std::vector<int> kept_to_cur(static_cast<size_t>(kept.num_vertices()), -1);
      for (int v = 0; v < cur.num_vertices(); ++v)
        if (remap[static_cast<size_t>(v)] >= 0) kept_to_cur[static_cast<size_t>(remap[static_cast<size_t>(v)])] = v;
      {
        std::vector<int> start{0}, corners;
        for (const auto& t : kept.faces) {
          corners.insert(corners.end(), t.begin(), t.end());
          start.push_back(static_cast<int>(corners.size()));
        }
        const VertexFanSplit split = split_nonmanifold_vertices(kept.num_vertices(), start, corners);
        for (size_t v = kept.vertices.size(); v < split.vertex_origin.size(); ++v) {
          const size_t o = static_cast<size_t>(split.vertex_origin[v]);
          kept.vertices.push_back(kept.vertices[o]);
          fk.push_back(fk[o]);
          kept_to_cur.push_back(kept_to_cur[o]);
        }
        for (size_t f = 0; f < kept.faces.size(); ++f)
          for (size_t k = 0; k < 3; ++k) kept.faces[f][k] = split.face_vertices[3 * f + k];
        out.pinched_vertices += split.num_split;
      }
      const Halfedges hk = build_halfedges(kept.num_vertices(), kept.faces);
      std::set<Edge> kept_front;
      for (int h = 0; h < hk.num_halfedges(); ++h) {
        if (!hk.is_boundary_halfedge(h)) continue;
        const int a = hk.from(h), b = hk.to(h);
        if (front.count(key(kept_to_cur[static_cast<size_t>(a)], kept_to_cur[static_cast<size_t>(b)])))
          kept_front.insert(key(a, b));
      }
      int ncomp = 0;
      const std::vector<int> comp = hk.face_components(&ncomp);
      std::vector<Region> next(static_cast<size_t>(ncomp));
      {
        std::vector<int> local(static_cast<size_t>(kept.num_vertices()), -1), owner_comp(static_cast<size_t>(kept.num_vertices()), -1);
        for (int f = 0; f < kept.num_faces(); ++f) {
          Region& n = next[static_cast<size_t>(comp[static_cast<size_t>(f)])];
          std::array<int, 3> nt{};
          for (int k = 0; k < 3; ++k) {
            const int v = kept.faces[f][k];
            if (local[static_cast<size_t>(v)] < 0) {
              local[static_cast<size_t>(v)] = n.mesh.num_vertices();
              owner_comp[static_cast<size_t>(v)] = comp[static_cast<size_t>(f)];
              n.mesh.vertices.push_back(kept.vertices[v]);
              n.f.push_back(fk[static_cast<size_t>(v)]);
            }
            nt[static_cast<size_t>(k)] = local[static_cast<size_t>(v)];
          }
          n.mesh.faces.push_back(nt);
        }
        for (const Edge& e : kept_front) {
          const int c = owner_comp[static_cast<size_t>(e.first)];
          next[static_cast<size_t>(c)].front.insert(key(local[static_cast<size_t>(e.first)], local[static_cast<size_t>(e.second)]));
        }
      }
      if (ncomp > 1) ++out.region_splits;
      // Each piece goes to the region whose front it lies on.
      std::vector<std::vector<int>> chains(next.size());
      std::vector<std::vector<double>> chain_s(next.size());
      for (size_t c = 0; c < next.size(); ++c) {
        next[c].tau = R.tau;
        const Halfedges hc = build_halfedges(next[c].mesh.num_vertices(), next[c].mesh.faces);
        chains[c] = front_chain(next[c], hc);
        chain_s[c] = chain_params(next[c].mesh, chains[c]);
      }
      // A piece goes to the region whose front chain its samples lie on:
      // the median distance (a few samples off the chain, e.g. the old front
      // next to a fork inside the removed disk, must not lose the piece; its
      // region would be left without samples).
      for (const std::vector<int>& piece : pieces) {
        int best = -1;
        double bd = kInf;
        for (size_t c = 0; c < next.size(); ++c) {
          if (chains[c].empty()) continue;
          std::vector<double> dist(piece.size(), 0.0);
          for (size_t k = 0; k < piece.size(); ++k)
            project_on_chain(next[c].mesh, chains[c], chain_s[c], out.samples[static_cast<size_t>(piece[k])], &dist[k]);
          std::nth_element(dist.begin(), dist.begin() + static_cast<long>(dist.size() / 2), dist.end());
          if (dist[dist.size() / 2] < bd) bd = dist[dist.size() / 2], best = static_cast<int>(c);
        }
        if (best < 0 || bd > 0.5 * sw || piece.size() < 3) {
          ++out.dropped_pieces;
          continue;
        }
        std::vector<int>& dst = next[static_cast<size_t>(best)].samples;
        if (dst.size() < piece.size()) {
          if (!dst.empty()) ++out.dropped_pieces;
          dst = piece;
        } else {
          ++out.dropped_pieces;
        }
      }
      for (size_t c = 0; c < next.size(); ++c) {
        if (chains[c].empty()) {
          out.uncovered_area += total_area(next[c].mesh);
          continue;
        }
        // A remnant smaller than two stitches ahead of the front would get
        // a strip of its own (at least four segments long) whose stitches
        // touch the rest of the fabric at a corner only, or not at all: the
        // knitting order cannot reach them and the map degenerates there.
        // It is left uncovered (a notch of less than two stitches).
        const double area = total_area(next[c].mesh);
        if (area < o.min_region_stitches * sw * sh) {
          out.uncovered_area += area;
          ++out.dropped_remnants;
          continue;
        }
        stack.push_back(std::move(next[c]));
      }
      break;  // continue with the regions on the stack (the current one is among them)
    }
  }
  return out;
}

}  // namespace knitforge
