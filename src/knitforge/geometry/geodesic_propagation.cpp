#include "knitforge/geometry/geodesic_propagation.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <numbers>

#include <fmt/format.h>
#include <Eigen/Geometry>

#include "knitforge/util/errors.h"

namespace knitforge::detail {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// Approximate mode: the deviation one merge may introduce, as a fraction of
// the requested tolerance. The deviations of successive merges add up along
// the wavefront (measured: the field's largest error is 1.4 to 7.3 times the
// per-merge deviation on the hemisphere, mannequin_front and triple_peak
// plane-x = 0 fields; see geodesic_distance.h), hence the factor 1/10.
constexpr double kMergeSlackPerTolerance = 0.1;

inline double entry_dist(const Vec2& s, double sigma, bool line, double x) {
  return line ? s.x() * x + sigma : std::sqrt((x - s.x()) * (x - s.x()) + s.y() * s.y()) + sigma;
}

// The one point of the edge line where dist_o - dist_w can have a zero
// derivative (both rays have the same direction there), or infinity.
template <class Entry>
double critical_x(const Entry& o, const Entry& w) {
  if (!o.line && !w.line) {
    const double dy = w.s.y() - o.s.y();
    return dy != 0.0 ? o.s.x() + (w.s.x() - o.s.x()) * (-o.s.y()) / dy : kInf;
  }
  if (o.line && !w.line) return w.s.x() + o.s.x() * (-w.s.y()) / o.s.y();
  if (!o.line && w.line) return o.s.x() + w.s.x() * (-o.s.y()) / w.s.y();
  return kInf;
}

// The smallest and largest value of dist_o - dist_w over [lo, hi] (attained
// at an end or at the critical point).
template <class Entry>
std::pair<double, double> deviation_range(const Entry& o, const Entry& w, double lo, double hi) {
  auto f = [&](double x) { return entry_dist(o.s, o.sigma, o.line, x) - entry_dist(w.s, w.sigma, w.line, x); };
  const double f0 = f(lo), f1 = f(hi);
  double mn = std::min(f0, f1), mx = std::max(f0, f1);
  const double xc = critical_x(o, w);
  if (xc > lo && xc < hi) {
    const double fc = f(xc);
    mn = std::min(mn, fc);
    mx = std::max(mx, fc);
  }
  return {mn, mx};
}

inline double cross2(const Vec2& a, const Vec2& b) { return a.x() * b.y() - a.y() * b.x(); }

// Rigid map into the frame of a child edge: x' = R (x - o), R rows (u, perp u).
struct Frame {
  Vec2 o;
  Vec2 u;
  Vec2 point(const Vec2& x) const {
    const Vec2 d = x - o;
    return {u.dot(d), cross2(u, d)};
  }
  Vec2 dir(const Vec2& n) const { return {u.dot(n), cross2(u, n)}; }
};

}  // namespace

GeodesicGeometry build_geodesic_geometry(const TriMesh& mesh) {
  if (mesh.faces.empty()) throw InvalidInput("geodesic distance: the mesh has no faces");
  for (int v = 0; v < mesh.num_vertices(); ++v)
    if (!mesh.vertices[v].allFinite())
      throw InvalidInput(fmt::format("geodesic distance: vertex {} has a non-finite coordinate", v));
  GeodesicGeometry g;
  g.mesh = &mesh;
  g.he = build_halfedges(mesh.num_vertices(), mesh.faces);
  const int nh = g.he.num_halfedges();
  const int nv = mesh.num_vertices();
  g.len.resize(nh);
  g.apex.resize(nh);
  Vec3 lo = mesh.vertices.empty() ? Vec3::Zero() : mesh.vertices[0], hi = lo;
  for (const Vec3& p : mesh.vertices) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  g.scale = std::max((hi - lo).norm(), 1e-300);
  g.eps = 1e-11 * g.scale;
  const double tiny_len = 1e-12 * g.scale;
  std::vector<double> angle(nv, 0.0);
  std::vector<char>& degenerate = g.degenerate;
  degenerate.assign(nv, 0);
  g.corner_angle.assign(nh, 0.0);
  for (int h = 0; h < nh; ++h) {
    const Vec3& a = mesh.vertices[g.he.from(h)];
    const Vec3& b = mesh.vertices[g.he.to(h)];
    const Vec3& c = mesh.vertices[g.he.to(g.he.next(h))];
    const Vec3 ab = b - a, ac = c - a;
    const double l = ab.norm();
    g.len[h] = l;
    if (l > 0.0) {
      const double cx = ac.dot(ab) / l;
      const double cy = ab.cross(ac).norm() / l;
      g.apex[h] = Vec2(cx, cy);
    } else {
      g.apex[h] = Vec2(0.0, 0.0);
    }
    g.corner_angle[h] = std::atan2(ab.cross(ac).norm(), ab.dot(ac));
    angle[g.he.from(h)] += g.corner_angle[h];
    const double twice_area = ab.cross(ac).norm();
    if (l <= tiny_len || twice_area <= 1e-12 * l * l || twice_area <= tiny_len * tiny_len) {
      degenerate[g.he.from(h)] = degenerate[g.he.to(h)] = degenerate[g.he.to(g.he.next(h))] = 1;
    }
  }
  g.out_start.assign(nv + 1, 0);
  for (int h = 0; h < nh; ++h) ++g.out_start[g.he.from(h) + 1];
  for (int v = 0; v < nv; ++v) g.out_start[v + 1] += g.out_start[v];
  g.out_he.resize(nh);
  std::vector<int> fill(g.out_start.begin(), g.out_start.end() - 1);
  for (int h = 0; h < nh; ++h) g.out_he[fill[g.he.from(h)]++] = h;
  // Angular coordinate of every out-going half-edge around its vertex:
  // counter-clockwise from the boundary half-edge (boundary vertices) or from
  // the first out-going half-edge.
  g.theta.assign(nh, 0.0);
  g.total_angle = angle;
  for (int v = 0; v < nv; ++v) {
    if (g.out_start[v] == g.out_start[v + 1]) continue;
    int start = g.out_he[g.out_start[v]];
    for (int i = g.out_start[v]; i < g.out_start[v + 1]; ++i)
      if (g.he.opposite(g.out_he[i]) < 0) start = g.out_he[i];
    double th = 0.0;
    int h = start;
    for (int guard = 0; guard < g.out_start[v + 1] - g.out_start[v]; ++guard) {
      g.theta[h] = th;
      th += g.corner_angle[h];
      h = g.he.opposite(g.he.prev(h));
      if (h < 0 || h == start) break;
    }
  }
  g.emits.assign(nv, 0);
  g.is_boundary.assign(nv, 0);
  const double tol = 1e-12;
  for (int v = 0; v < nv; ++v) {
    if (g.he.is_isolated_vertex(v)) continue;
    const bool boundary = g.he.is_boundary_vertex(v);
    g.is_boundary[v] = boundary;
    const double need = boundary ? std::numbers::pi : 2.0 * std::numbers::pi;
    g.emits[v] = degenerate[v] || angle[v] > need + tol;
  }
  int interior = 0, interior_emitting = 0;
  for (int v = 0; v < nv; ++v) {
    if (g.he.is_isolated_vertex(v) || g.is_boundary[v]) continue;
    ++interior;
    interior_emitting += g.emits[v] ? 1 : 0;
  }
  g.saddle_fraction = interior > 0 ? static_cast<double>(interior_emitting) / interior : 0.0;
  std::vector<char> flat(nv, 0);
  for (int v = 0; v < nv; ++v)
    flat[v] = !g.he.is_isolated_vertex(v) && !g.is_boundary[v] &&
              std::abs(angle[v] - 2.0 * std::numbers::pi) <= 1e-9;
  g.mergeable.assign(nh, 0);
  auto face_has_flat = [&](int h) {
    return flat[g.he.from(h)] || flat[g.he.to(h)] || flat[g.he.to(g.he.next(h))];
  };
  for (int h = 0; h < nh; ++h) {
    const int o = g.he.opposite(h);
    g.mergeable[h] = face_has_flat(h) || (o >= 0 && face_has_flat(o));
  }
  return g;
}

GeodesicPropagation::GeodesicPropagation(const GeodesicGeometry& g, bool track_boundary, double tolerance)
    : g_(g),
      dist_(g.mesh->num_vertices(), kInf),
      vorigin_(g.mesh->num_vertices(), Origin::None),
      vorigin_id_(g.mesh->num_vertices(), -1),
      pending_(g.he.num_halfedges()),
      track_boundary_(track_boundary) {
  if (!std::isfinite(tolerance) || tolerance < 0.0)
    throw InvalidInput(fmt::format(
        "geodesic distance: the tolerance must be a finite number >= 0 mm (0 = exact), got {}", tolerance));
  if (tolerance > 0.0) {
    approx_ = true;
    merge_slack_ = tolerance * kMergeSlackPerTolerance;
    index_.resize(g.he.num_halfedges());
  }
}

Vec2 GeodesicPropagation::corner(int h, int k) const {
  switch (k % 3) {
    case 0:
      return Vec2(0.0, 0.0);
    case 1:
      return Vec2(g_.len[h], 0.0);
    default:
      return g_.apex[h];
  }
}

double GeodesicPropagation::window_distance(const Window& w, const Vec2& x) const {
  return w.line ? w.s.dot(x) + w.sigma : (x - w.s).norm() + w.sigma;
}

// Where the ray of w through x (a point on the far side of the edge)
// crosses the window's edge line y = 0.
double GeodesicPropagation::window_xint(const Window& w, const Vec2& x) const {
  if (w.line) return x.x() - x.y() * w.s.x() / w.s.y();
  const double den = x.y() - w.s.y();
  if (!(den > 0.0)) return w.s.x();
  return w.s.x() + (x.x() - w.s.x()) * (-w.s.y()) / den;
}

void GeodesicPropagation::update_vertex(int v, double d, Origin origin, int id) {
  if (!(d < dist_[v])) return;
  dist_[v] = d;
  vorigin_[v] = origin;
  vorigin_id_[v] = id;
  if (track_boundary_ && g_.is_boundary[v]) boundary_candidate(d, -1, 0.0, Origin::Vertex, v);
  queue_.push({d, -(v + 1), Window{}});
}

uint64_t GeodesicPropagation::RadixQueue::bits(double key) {
  uint64_t u;
  std::memcpy(&u, &key, sizeof u);
  // Order-preserving map of IEEE doubles to unsigned integers.
  return (u >> 63) ? ~u : (u | (uint64_t{1} << 63));
}

int GeodesicPropagation::RadixQueue::bucket(uint64_t k) const {
  return k <= last_ ? 0 : 64 - std::countl_zero(k ^ last_);
}

void GeodesicPropagation::RadixQueue::push(const QueueItem& item) {
  buckets_[bucket(bits(item.key))].push_back(item);
  ++size_;
}

GeodesicPropagation::QueueItem GeodesicPropagation::RadixQueue::pop() {
  if (buckets_[0].empty()) {
    int i = 1;
    while (buckets_[i].empty()) ++i;
    std::vector<QueueItem>& b = buckets_[i];
    uint64_t lo = bits(b[0].key);
    for (const QueueItem& it : b) lo = std::min(lo, bits(it.key));
    last_ = lo;
    for (const QueueItem& it : b) buckets_[bucket(bits(it.key))].push_back(it);
    b.clear();
  }
  const QueueItem item = buckets_[0].back();
  buckets_[0].pop_back();
  --size_;
  return item;
}

uint32_t GeodesicPropagation::root_code(const Window& w) {
  return (static_cast<uint32_t>(w.origin_id) << 3) | (w.origin == Origin::Vertex ? 4u : 0u) |
         (static_cast<uint32_t>(w.aux & 1) << 1) | static_cast<uint32_t>(w.line);
}

void GeodesicPropagation::boundary_candidate(double d, int halfedge, double t, Origin origin, int id) {
  if (!track_boundary_ || !(d < boundary_.dist)) return;
  boundary_ = {d, halfedge, std::clamp(t, 0.0, 1.0), origin, id};
}

// True when a vertex of the faces on both sides of the window's edge gives a
// shorter path to every point of the window (see the header).
bool GeodesicPropagation::dominated(Window& w, const Vec2* extra, int extra_vertex) const {
  const int h = w.h;
  const double L = g_.len[h];
  const double eps = g_.eps;
  const int a = g_.he.from(h), b = g_.he.to(h);
  const double da = dist_[a], db = dist_[b];
  const double sx = w.s.x(), sy = w.s.y();
  // f(x) = d(x) - x is non-increasing and d(x) + x non-decreasing along the
  // edge (|d'| <= 1): the points dominated by a (d(x) > da + x + eps) form
  // an interval at the start, those dominated by b one at the end.
  auto dist_at = [&](double x) {
    return w.line ? sx * x + w.sigma : std::sqrt((x - sx) * (x - sx) + sy * sy) + w.sigma;
  };
  const double d0 = dist_at(w.b0), d1 = dist_at(w.b1);
  if (d1 > da + w.b1 + eps) return true;
  if (d0 > db + (L - w.b0) + eps) return true;
  bool trimmed = false;
  if (d0 > da + w.b0 + eps) {  // solve d(x) - x = da + eps
    double x;
    const double k = da + eps - w.sigma;
    if (w.line) {
      x = sx < 1.0 ? k / (sx - 1.0) : w.b0;
    } else {
      const double den = 2.0 * (sx + k);
      x = den > 0.0 ? (sx * sx + sy * sy - k * k) / den : w.b0;
    }
    if (x > w.b0 && x < w.b1) {
      w.b0 = x;
      trimmed = true;
    }
  }
  if (d1 > db + (L - w.b1) + eps) {  // solve d(x) + x = db + L + eps
    double x;
    const double k = db + L + eps - w.sigma;
    if (w.line) {
      x = sx > -1.0 ? k / (sx + 1.0) : w.b1;
    } else {
      const double den = 2.0 * (k - sx);
      x = den > 0.0 ? (k * k - sx * sx - sy * sy) / den : w.b1;
    }
    if (x > w.b0 && x < w.b1) {
      w.b1 = x;
      trimmed = true;
    }
  }
  if (trimmed && !prepare(w)) return true;
  const Vec2 p0(w.b0, 0.0), p1(w.b1, 0.0);
  const double dmin = w.key;
  auto check = [&](const Vec2& pos, int v) {
    const double dv = dist_[v];
    if (dv == kInf) return false;
    return dv + std::sqrt(std::max((pos - p0).squaredNorm(), (pos - p1).squaredNorm())) < dmin - eps;
  };
  if (check(g_.apex[h], g_.he.to(g_.he.next(h)))) return true;
  if (extra && check(*extra, extra_vertex)) return true;
  return false;
}

bool GeodesicPropagation::prepare(Window& w) const {
  const double L = g_.len[w.h];
  w.b0 = std::clamp(w.b0, 0.0, L);
  w.b1 = std::clamp(w.b1, 0.0, L);
  if (!(w.b1 - w.b0 > 1e-12 * L)) return false;
  if (w.line) {
    w.key = std::min(w.s.x() * w.b0, w.s.x() * w.b1) + w.sigma;
  } else {
    const double x = std::clamp(w.s.x(), w.b0, w.b1);
    w.key = std::sqrt((x - w.s.x()) * (x - w.s.x()) + w.s.y() * w.s.y()) + w.sigma;
  }
  return true;
}

// Appends a window, or merges it into a pending window on the same edge with
// the same distance function whose interval it touches. Without merging, the
// pieces a window is split into at every vertex would stay separate forever
// and their number per edge would grow with the distance from the source.
void GeodesicPropagation::push_window(const Window& w0) {
  if (blocked_ && (*blocked_)[w0.h]) return;
  Window w = w0;
  if (approx_) {
    if (!trim_against_index(w) || merge_adjacent(w)) return;
    const int id = static_cast<int>(windows_.size());
    windows_.push_back(w);
    index_[w.h].push_back({w.b0, w.b1, w.s, w.sigma, id, w.line});
    queue_.push({w.key, id, w});
    return;
  }
  if (!g_.mergeable[w.h]) {
    const int id = static_cast<int>(windows_.size());
    windows_.push_back(w);
    queue_.push({w.key, id, w});
    return;
  }
  const double L = g_.len[w.h];
  const double ftol = 1e-9 * g_.scale;
  std::vector<PendingRef>& pend = pending_[w.h];
  const uint32_t root = root_code(w);
  const double stol = w.line ? 1e-12 : ftol;
  for (size_t i = pend.size(); i-- > 0;) {  // the most recent first
    const PendingRef& r = pend[i];
    if (r.root != root || std::abs(r.sigma - w.sigma) > ftol || std::abs(r.sx - w.s.x()) > stol) continue;
    const int j = r.id;
    Window& o = windows_[j];
    if (o.line != w.line || o.origin != w.origin || o.origin_id != w.origin_id || o.aux != w.aux) continue;
    if (std::abs(o.sigma - w.sigma) > ftol) continue;
    if (w.line ? (o.s - w.s).norm() > 1e-12 : (o.s - w.s).norm() > ftol) continue;
    if (w.b0 > o.b1 + 1e-9 * L || w.b1 < o.b0 - 1e-9 * L) continue;
    o.b0 = std::min(o.b0, w.b0);
    o.b1 = std::max(o.b1, w.b1);
    // (o.s and o.sigma are unchanged: the copies in pend stay valid)
    if (w.key < o.key) {
      o.key = w.key;
      queue_.push({o.key, j, o});
    }
    return;
  }
  const int id = static_cast<int>(windows_.size());
  windows_.push_back(w);
  pend.push_back({root, id, w.s.x(), w.sigma});
  queue_.push({w.key, id, w});
}

// Approximate mode. f(x) = dist_o(x) - dist_w(x) along the edge has at most
// one critical point (two point sources: where the line through them crosses
// the edge; a point and a parallel family: where the ray from the point in
// the family's direction crosses it; two families: f is linear), so it is
// monotone on the pieces between lo, that point and hi, and the run of
// dominated points (f <= 0) from an end is found piece by piece, the
// crossing piece by bisection (keeping the dominated side, so the returned
// limit is always dominated).
double GeodesicPropagation::dominated_run(const IndexEntry& o, const IndexEntry& w, double lo, double hi,
                                          bool from_lo) const {
  auto f = [&](double x) { return entry_dist(o.s, o.sigma, o.line, x) - entry_dist(w.s, w.sigma, w.line, x); };
  const double start = from_lo ? lo : hi, end = from_lo ? hi : lo;
  if (!(f(start) <= 0.0)) return start;
  const double xc = critical_x(o, w);
  double pts[2];
  int np = 0;
  if (std::isfinite(xc) && xc > lo && xc < hi) pts[np++] = xc;
  pts[np++] = end;
  double good = start;
  for (int i = 0; i < np; ++i) {
    double bad = pts[i];
    if (f(bad) <= 0.0) {
      good = bad;
      continue;
    }
    // The root of f between good (f <= 0) and bad (f > 0), f monotone there:
    // regula falsi with the Illinois rule (superlinear where bisection needs
    // ~30 steps for this tolerance), falling back to bisection when the
    // secant stalls; the bracket keeps f(good) <= 0 < f(bad).
    const double stop = 1e-9 * (hi - lo);
    double fg = f(good), fb = f(bad);
    int side = 0;
    for (int it = 0; it < 100 && std::abs(bad - good) > stop; ++it) {
      double x = fb - fg > 0.0 ? good - fg * (bad - good) / (fb - fg) : 0.5 * (good + bad);
      const double margin = 0.01 * std::abs(bad - good);
      if (!(std::abs(x - good) > margin && std::abs(bad - x) > margin)) x = 0.5 * (good + bad);
      const double fx = f(x);
      if (fx <= 0.0) {
        good = x;
        fg = fx;
        if (side == -1) fb *= 0.5;
        side = -1;
      } else {
        bad = x;
        fb = fx;
        if (side == 1) fg *= 0.5;
        side = 1;
      }
    }
    return good;
  }
  return good;
}

// Approximate mode: trims w (exactly, as MMP does) to the part where no
// window already on its half-edge is shorter, and trims (or kills) the
// pending windows there that w beats on a run from one of their ends.
bool GeodesicPropagation::trim_against_index(Window& w) {
  std::vector<IndexEntry>& list = index_[w.h];
  IndexEntry we{w.b0, w.b1, w.s, w.sigma, -1, w.line};
  for (size_t i = 0; i < list.size();) {
    IndexEntry& o = list[i];
    double lo = std::max(o.b0, we.b0), hi = std::min(o.b1, we.b1);
    if (!(hi > lo)) {
      ++i;
      continue;
    }
    // w against o: cut the dominated runs at w's ends that lie inside o.
    if (o.b0 <= we.b0) {
      const double x = dominated_run(o, we, lo, hi, true);
      if (x >= we.b1) return false;
      we.b0 = x;
    }
    lo = std::max(o.b0, we.b0);
    if (o.b1 >= we.b1 && hi > lo) {
      const double x = dominated_run(o, we, lo, hi, false);
      if (x <= we.b0) return false;
      we.b1 = x;
    }
    // o against (what is left of) w, when o is still pending.
    Window& ow = windows_[o.id];
    lo = std::max(o.b0, we.b0);
    hi = std::min(o.b1, we.b1);
    if (!ow.done && hi > lo) {
      bool changed = false, gone = false;
      if (we.b0 <= o.b0) {
        const double x = dominated_run(we, o, lo, hi, true);
        if (x >= o.b1) gone = true;
        if (x > o.b0) {
          o.b0 = x;
          changed = true;
        }
      }
      lo = std::max(o.b0, we.b0);
      if (!gone && we.b1 >= o.b1 && hi > lo) {
        const double x = dominated_run(we, o, lo, hi, false);
        if (x <= o.b0) gone = true;
        if (x < o.b1) {
          o.b1 = x;
          changed = true;
        }
      }
      if (changed && !gone) {
        ow.b0 = o.b0;
        ow.b1 = o.b1;
        gone = !prepare(ow);
      }
      if (gone) {
        ow.dead = true;
        list[i] = list.back();
        list.pop_back();
        continue;
      }
    }
    ++i;
  }
  w.b0 = we.b0;
  w.b1 = we.b1;
  return prepare(w);
}

// Approximate mode (the window merging of Surazhsky et al. 2005, "Fast
// exact and approximate geodesics on meshes", for parallel families): w and a
// pending window o of the same half-edge that touch are replaced by one
// family over the union whose distance matches theirs exactly at the two
// outer ends (the line through the two end values: slope k, direction
// (k, sqrt(1 - k²))), accepted when it deviates from each part by at most
// merge_slack_ on that part (the deviation is linear, so checking the ends
// suffices). Point windows are not merged: a fitted pseudo-source changes the
// incoming direction at saddle vertices, whose shadow cones then miss the
// real geodesics (tried: errors of 0.3-0.6 mm on the triple-peak and the
// mannequin). Returns true when w was merged (o then carries the union).
bool GeodesicPropagation::merge_adjacent(const Window& w) {
  std::vector<IndexEntry>& list = index_[w.h];
  const double L = g_.len[w.h];
  const double touch = 1e-9 * L;
  if (!w.line) return false;
  const IndexEntry we{w.b0, w.b1, w.s, w.sigma, -1, w.line};
  for (IndexEntry& o : list) {
    if (!o.line) continue;
    bool o_left;
    if (std::abs(o.b1 - we.b0) <= touch)
      o_left = true;
    else if (std::abs(we.b1 - o.b0) <= touch)
      o_left = false;
    else
      continue;
    Window& ow = windows_[o.id];
    if (ow.done) continue;
    const IndexEntry& A = o_left ? o : we;
    const IndexEntry& B = o_left ? we : o;
    const double a = A.b0, b = B.b1;
    if (!(b - a > 0.0)) continue;
    const double Da = entry_dist(A.s, A.sigma, A.line, a), Db = entry_dist(B.s, B.sigma, B.line, b);
    const double k = (Db - Da) / (b - a);
    if (!(std::abs(k) < 1.0 - 1e-9)) continue;
    const IndexEntry M{a, b, Vec2(k, std::sqrt(1.0 - k * k)), Da - k * a, o.id, true};
    const auto ra = deviation_range(M, A, A.b0, A.b1), rb = deviation_range(M, B, B.b0, B.b1);
    if (std::max({-ra.first, ra.second, -rb.first, rb.second}) > merge_slack_) continue;
    const double old_key = ow.key;
    const bool w_longer = (w.b1 - w.b0) > (o.b1 - o.b0);
    o = M;
    ow.b0 = a;
    ow.b1 = b;
    ow.s = M.s;
    ow.sigma = M.sigma;
    if (w_longer) {  // the root of the longer part
      ow.origin = w.origin;
      ow.origin_id = w.origin_id;
      ow.aux = w.aux;
    }
    prepare(ow);  // (the union is longer than either part: never empty)
    if (ow.key < old_key) queue_.push({ow.key, o.id, ow});
    return true;
  }
  return false;
}

// Child k (1: edge next(h) = B->C, 2: edge prev(h) = C->A) of window `parent`
// (index wi) covering the rays that cross the parent's edge in [x0, x1].
void GeodesicPropagation::make_child(const Window& parent, int wi, int k, double x0, double x1) {
  const int h = parent.h;
  const int gk = k == 1 ? g_.he.next(h) : g_.he.prev(h);
  const Vec2 ck = corner(h, k), ck1 = corner(h, k + 1);  // edge gk runs ck -> ck1
  const double le = g_.len[gk];
  if (!(le > 1e-12 * g_.scale)) return;
  // Intersections of the rays through (x0,0), (x1,0) with the edge line ck -> ck1.
  auto hit = [&](double x) {
    const Vec2 q(x, 0.0);
    const Vec2 d = parent.line ? parent.s : Vec2(q - parent.s);
    const Vec2 e = ck1 - ck;
    const double den = cross2(e, d);
    double t = den != 0.0 ? cross2(q - ck, d) / den : 0.0;
    return std::clamp(t, 0.0, 1.0);
  };
  const double t0 = hit(x0), t1 = hit(x1);
  // Child frame: origin ck1, axis towards ck; position along the child edge = (1 - t) le.
  Window c;
  c.h = g_.he.opposite(gk);
  if (c.h >= 0 && blocked_ && (*blocked_)[c.h]) return;
  c.line = parent.line;
  c.origin = parent.origin;  // the root (seed or pseudo-source vertex)
  c.origin_id = parent.origin_id;
  c.aux = parent.aux;
  const Frame fr{ck1, (ck - ck1) / le};
  double a = (1.0 - t0) * le, b = (1.0 - t1) * le;
  if (a > b) std::swap(a, b);
  if (parent.line) {
    c.s = fr.dir(parent.s);
    c.sigma = parent.sigma + parent.s.dot(fr.o);
    if (!(c.s.y() > 1e-15)) return;
  } else {
    c.s = fr.point(parent.s);
    c.sigma = parent.sigma;
    if (!(c.s.y() < 0.0)) return;
  }
  c.b0 = a;
  c.b1 = b;
  if (c.h < 0) {  // boundary edge: a candidate end for paths to the boundary
    if (!track_boundary_) return;
    double x;
    if (c.line) {
      x = c.s.x() >= 0.0 ? a : b;
    } else {
      x = std::clamp(c.s.x(), a, b);
    }
    const double d = c.line ? c.s.x() * x + c.sigma : std::hypot(x - c.s.x(), c.s.y()) + c.sigma;
    boundary_candidate(d, gk, 1.0 - x / le, Origin::Window, wi);
    return;
  }
  const Vec2 other = fr.point(corner(h, k + 2));  // third vertex of the parent face
  const int other_v = g_.he.to(g_.he.next(gk));
  if (!prepare(c) || dominated(c, &other, other_v)) return;
  push_window(c);
}

void GeodesicPropagation::propagate(const Window& w, int wi) {
  const int h = w.h;
  const Vec2 C = g_.apex[h];
  const double L = g_.len[h];
  const int vc = g_.he.to(g_.he.next(h));
  double xc = window_xint(w, C);
  if (w.line && !(w.s.y() > 0.0)) return;
  if (!std::isfinite(xc)) xc = C.x();
  if (xc >= w.b0 - 1e-12 * L && xc <= w.b1 + 1e-12 * L) {
    update_vertex(vc, window_distance(w, C), Origin::Window, wi);
  }
  if (xc > w.b0) make_child(w, wi, 2, w.b0, std::min(w.b1, xc));
  if (xc < w.b1) make_child(w, wi, 1, std::max(w.b0, xc), w.b1);
}

// Direction back to the source at vertex v, as an angle around v (see
// GeodesicGeometry::theta), or a negative value when unknown (emit all around).
double GeodesicPropagation::back_angle(int v) const {
  const int id = vorigin_id_[v];
  switch (vorigin_[v]) {
    case Origin::Window: {
      const Window& w = windows_[id];
      const Vec2 C = g_.apex[w.h];
      const Vec2 back = w.line ? Vec2(-w.s) : Vec2(w.s - C);
      const int g = g_.he.prev(w.h);  // C -> A, the half-edge of v in this face
      const Vec2 e = corner(w.h, 0) - C;
      if (back.norm() <= 0.0 || e.norm() <= 0.0) return -1.0;
      const double phi = std::atan2(std::abs(cross2(e, back)), e.dot(back));
      return g_.theta[g] + std::clamp(phi, 0.0, g_.corner_angle[g]);
    }
    case Origin::Seed: {
      const Seed& sd = seeds_[id];
      const int h0 = g_.he.face_start(sd.face);
      int k = 0;
      while (k < 3 && g_.he.from(h0 + k) != v) ++k;
      if (k == 3) return -1.0;
      const Vec2 P = corner(h0, k);
      const Vec2 d = sd.q2 - sd.p2;
      const double t =
          d.squaredNorm() > 0.0 ? std::clamp((P - sd.p2).dot(d) / d.squaredNorm(), 0.0, 1.0) : 0.0;
      const Vec2 back = sd.p2 + t * d - P;
      const Vec2 e = corner(h0, k + 1) - P;
      if (back.norm() <= 1e-12 * g_.scale || e.norm() <= 0.0) return -1.0;
      const double phi = std::atan2(std::abs(cross2(e, back)), e.dot(back));
      return g_.theta[h0 + k] + std::clamp(phi, 0.0, g_.corner_angle[h0 + k]);
    }
    default:
      return -1.0;
  }
}

void GeodesicPropagation::emit_vertex(int v) {
  const double dv = dist_[v];
  constexpr double kPi = std::numbers::pi;
  // Geodesics continue through v only in its shadow: the directions at an
  // angle of at least π from the incoming one on both sides (interior), or on
  // the one side that exists (boundary). Elsewhere the path through v can be
  // shortened, so windows there are useless.
  double ranges[2][2];
  int nranges = 0;
  const double total = g_.total_angle[v];
  if (g_.emits[v]) {
    const double back = g_.degenerate[v] ? -1.0 : back_angle(v);
    const double m = 1e-12;
    if (back < 0.0) {
      ranges[nranges][0] = -1.0;
      ranges[nranges++][1] = total + 1.0;
    } else if (g_.is_boundary[v]) {
      if (back - kPi > -m) {
        ranges[nranges][0] = -1.0;
        ranges[nranges++][1] = back - kPi + m;
      }
      if (back + kPi < total + m) {
        ranges[nranges][0] = back + kPi - m;
        ranges[nranges++][1] = total + 1.0;
      }
    } else {
      double lo = back + kPi - m, hi = back + total - kPi + m;
      if (hi > lo) {
        while (lo >= total) {
          lo -= total;
          hi -= total;
        }
        ranges[nranges][0] = lo;
        ranges[nranges++][1] = hi;
        if (hi > total) {
          ranges[nranges][0] = lo - total;
          ranges[nranges++][1] = hi - total;
        }
      }
    }
  }
  for (int i = g_.out_start[v]; i < g_.out_start[v + 1]; ++i) {
    const int h = g_.out_he[i];  // v = corner 0 of the frame of h
    // Edge relaxation to the two neighbours in this face.
    const int b = g_.he.to(h), c = g_.he.to(g_.he.next(h));
    if (!blocked_ || !(*blocked_)[h]) update_vertex(b, dv + g_.len[h], Origin::Edge, v);
    if (!blocked_ || !(*blocked_)[g_.he.prev(h)]) update_vertex(c, dv + g_.len[g_.he.prev(h)], Origin::Edge, v);
    // A point window from v on the opposite edge (B -> C, child k = 1),
    // restricted to the shadow directions.
    const int gk = g_.he.next(h);
    const double le = g_.len[gk];
    if (!(le > 1e-12 * g_.scale)) continue;
    const double f0 = g_.theta[h], fa = g_.corner_angle[h];
    const Vec2 B = corner(h, 1), C = corner(h, 2);
    const Frame fr{C, (B - C) / le};
    for (int r = 0; r < nranges; ++r) {
      const double p0 = std::max(ranges[r][0] - f0, 0.0), p1 = std::min(ranges[r][1] - f0, fa);
      if (!(p1 > p0)) continue;
      // Rays from v = (0,0) at angle phi from AB hit BC at t (B + t (C - B)).
      auto pos = [&](double phi) {
        if (phi <= 0.0) return le;
        if (phi >= fa) return 0.0;
        const Vec2 d(std::cos(phi), std::sin(phi));
        const double den = cross2(d, C - B);
        const double t = den != 0.0 ? std::clamp(cross2(B, d) / den, 0.0, 1.0) : 0.0;
        return (1.0 - t) * le;
      };
      Window w;
      w.h = g_.he.opposite(gk);
      if (w.h >= 0 && blocked_ && (*blocked_)[w.h]) continue;
      w.origin = Origin::Vertex;
      w.origin_id = v;
      w.s = fr.point(Vec2(0.0, 0.0));
      w.sigma = dv;
      w.b0 = pos(p1);
      w.b1 = pos(p0);
      if (!(w.s.y() < -1e-12 * le)) continue;
      if (w.h < 0) {
        if (track_boundary_) {
          const double x = std::clamp(w.s.x(), w.b0, w.b1);
          boundary_candidate(std::hypot(x - w.s.x(), w.s.y()) + dv, gk, 1.0 - x / le, Origin::Vertex, v);
        }
        continue;
      }
      if (!prepare(w) || dominated(w, nullptr, -1)) continue;
      push_window(w);
    }
  }
}

// Seeds one face with a source piece: the segment p-q (line windows only,
// `point` false) or the point p (point windows only, clipped to the
// directions d with d·u <= 0 for every u in `cons`, given in the face frame).
void GeodesicPropagation::seed_face(int f, const Vec3& bp, const Vec3& bq, bool point,
                                    const std::vector<Vec2>& cons) {
  const int h0 = g_.he.face_start(f);
  const Vec2 cs[3] = {corner(h0, 0), corner(h0, 1), corner(h0, 2)};
  const Vec2 p2 = bp[0] * cs[0] + bp[1] * cs[1] + bp[2] * cs[2];
  const Vec2 q2 = point ? p2 : Vec2(bq[0] * cs[0] + bq[1] * cs[1] + bq[2] * cs[2]);
  const int si = static_cast<int>(seeds_.size());
  seeds_.push_back({f, bp, point ? bp : bq, p2, q2});
  const double seg_len = (q2 - p2).norm();
  const bool segment = !point && seg_len > 1e-12 * g_.scale;
  if (!point && !segment) return;  // a zero-length segment: its points are seeded as points
  auto seg_dist = [&](const Vec2& x) {
    if (!segment) return (x - p2).norm();
    const Vec2 d = q2 - p2;
    const double t = std::clamp((x - p2).dot(d) / d.squaredNorm(), 0.0, 1.0);
    return (x - (p2 + t * d)).norm();
  };
  for (int k = 0; k < 3; ++k) update_vertex(g_.he.from(h0 + k), seg_dist(cs[k]), Origin::Seed, si);
  for (int k = 0; k < 3; ++k) {
    const int gk = h0 + k;  // edge cs[k] -> cs[k+1]
    const double le = g_.len[gk];
    if (!(le > 1e-12 * g_.scale)) continue;
    const Frame fr{cs[(k + 1) % 3], (cs[k] - cs[(k + 1) % 3]) / le};
    const int hc = g_.he.opposite(gk);
    const Vec2 P = fr.point(p2), Q = fr.point(q2);
    const Vec2 other = fr.point(cs[(k + 2) % 3]);
    const int other_v = g_.he.from(g_.he.prev(gk));
    const double tiny = 1e-12 * le;
    // Interval [lo, hi] of the edge (x along it, y = 0) where lower <= a x + b <= upper.
    double lo = 0.0, hi = le;
    auto clip = [&](double a, double b, double lower, double upper) {
      if (a == 0.0) {
        if (b < lower || b > upper) hi = lo - 1.0;
        return;
      }
      double x0 = (lower - b) / a, x1 = (upper - b) / a;
      if (x0 > x1) std::swap(x0, x1);
      lo = std::max(lo, x0);
      hi = std::min(hi, x1);
    };
    if (hc < 0) {
      if (!track_boundary_) continue;
      // Closest point of the edge [0, le] x {0} to the source piece.
      double best = kInf, bx = 0.0;
      auto consider = [&](double x) {
        x = std::clamp(x, 0.0, le);
        const double d = seg_dist(fr.o + x * fr.u);
        if (d < best) {
          best = d;
          bx = x;
        }
      };
      consider(P.x());
      consider(Q.x());
      if (segment && (P.y() > 0.0) != (Q.y() > 0.0) && P.y() != Q.y())
        consider(P.x() + (Q.x() - P.x()) * P.y() / (P.y() - Q.y()));
      boundary_candidate(best, gk, 1.0 - bx / le, Origin::Seed, si);
      continue;
    }
    if (point) {
      if (!(P.y() < -tiny)) continue;
      for (const Vec2& u : cons) {
        const Vec2 uc = fr.dir(u);
        clip(uc.x(), -P.x() * uc.x() - P.y() * uc.y(), -kInf, 0.0);
      }
      if (!(hi > lo)) continue;
      Window w;
      w.h = hc;
      w.origin = Origin::Seed;
      w.origin_id = si;
      w.s = P;
      w.b0 = lo;
      w.b1 = hi;
      if (prepare(w) && !dominated(w, &other, other_v)) push_window(w);
      continue;
    }
    const Vec2 dir = (Q - P) / (Q - P).norm();
    for (int sgn : {1, -1}) {
      const Vec2 n = sgn * Vec2(-dir.y(), dir.x());
      if (!(n.y() > 1e-15)) continue;
      lo = 0.0;
      hi = le;
      // Feet inside the segment and the points on this side of it.
      clip(dir.x(), -P.x() * dir.x() - P.y() * dir.y(), 0.0, seg_len);
      clip(n.x(), -P.x() * n.x() - P.y() * n.y(), 0.0, kInf);
      if (!(hi > lo)) continue;
      Window w;
      w.h = hc;
      w.line = true;
      w.origin = Origin::Seed;
      w.origin_id = si;
      w.s = n;
      w.sigma = -n.dot(P);
      w.b0 = lo;
      w.b1 = hi;
      if (prepare(w) && !dominated(w, &other, other_v)) push_window(w);
    }
  }
}

void GeodesicPropagation::unpend(int h, int id) {
  std::vector<PendingRef>& pend = pending_[h];
  for (size_t i = 0; i < pend.size(); ++i) {
    if (pend[i].id == id) {
      pend[i] = pend.back();
      pend.pop_back();
      return;
    }
  }
}

void GeodesicPropagation::check_point(const SurfacePoint& sp) const { check_surface_point(*g_.mesh, sp); }

void GeodesicPropagation::add_source(const GeodesicSource& source) {
  const TriMesh& mesh = *g_.mesh;
  for (const auto& line : source.polylines) {
    const size_t n = line.size();
    if (n == 0) continue;
    const bool closed =
        n > 2 &&
        (surface_point_position(mesh, line.front()) - surface_point_position(mesh, line.back())).norm() ==
            0.0;
    const size_t npts = closed ? n - 1 : n;
    for (size_t i = 0; i < npts; ++i) {
      std::vector<const SurfacePoint*> nb;
      if (i > 0)
        nb.push_back(&line[i - 1]);
      else if (closed)
        nb.push_back(&line[n - 2]);
      if (i + 1 < n) nb.push_back(&line[i + 1]);
      add_point(line[i], nb);
    }
    for (size_t i = 0; i + 1 < n; ++i) add_segment(line[i], line[i + 1]);
  }
}

void check_surface_point(const TriMesh& mesh, const SurfacePoint& sp) {
  if (sp.face < 0 || sp.face >= mesh.num_faces())
    throw InvalidInput(fmt::format("geodesic source: surface point in face {} but the mesh has {} faces",
                                   sp.face, mesh.num_faces()));
  const Vec3& b = sp.bary;
  if (!b.allFinite() || b.minCoeff() < 0.0 || std::abs(b.sum() - 1.0) > 1e-9)
    throw InvalidInput(fmt::format(
        "geodesic source: surface point in face {} has barycentric coordinates ({}, {}, {}); they must be "
        ">= 0 and sum to 1",
        sp.face, b[0], b[1], b[2]));
}

namespace {

// Support vertices (non-zero coordinates) with their weights.
std::vector<std::pair<int, double>> support_of(const TriMesh& mesh, const SurfacePoint& s) {
  std::vector<std::pair<int, double>> out;
  for (int k = 0; k < 3; ++k)
    if (s.bary[k] != 0.0) out.emplace_back(mesh.faces[s.face][k], s.bary[k]);
  return out;
}

// Barycentric coordinates of a support in face t, or false when t does not contain it.
bool bary_in(const std::array<int, 3>& t, const std::vector<std::pair<int, double>>& s, Vec3& b) {
  b = Vec3::Zero();
  for (const auto& [v, w] : s) {
    int k = 0;
    while (k < 3 && t[k] != v) ++k;
    if (k == 3) return false;
    b[k] = w;
  }
  return true;
}

}  // namespace

void GeodesicPropagation::add_segment(const SurfacePoint& p, const SurfacePoint& q) {
  const TriMesh& mesh = *g_.mesh;
  check_point(p);
  check_point(q);
  const auto sp = support_of(mesh, p), sq = support_of(mesh, q);
  const int v0 = sp[0].first;
  bool found = false;
  for (int i = g_.out_start[v0]; i < g_.out_start[v0 + 1]; ++i) {
    const int f = g_.he.face(g_.out_he[i]);
    Vec3 bp, bq;
    if (!bary_in(mesh.faces[f], sp, bp) || !bary_in(mesh.faces[f], sq, bq)) continue;
    found = true;
    seed_face(f, bp, bq, false, {});
  }
  if (!found)
    throw InvalidInput(fmt::format(
        "geodesic source: consecutive source points in faces {} and {} share no face; a source segment must "
        "lie inside one face (insert the edge crossings between them)",
        p.face, q.face));
}

void GeodesicPropagation::add_point(const SurfacePoint& p,
                                    const std::vector<const SurfacePoint*>& neighbours) {
  const TriMesh& mesh = *g_.mesh;
  check_point(p);
  for (const SurfacePoint* q : neighbours) check_point(*q);
  const auto sp = support_of(mesh, p);
  const int v0 = sp[0].first;
  const Vec3 P3 = surface_point_position(mesh, p);
  for (int i = g_.out_start[v0]; i < g_.out_start[v0 + 1]; ++i) {
    const int f = g_.he.face(g_.out_he[i]);
    Vec3 bp;
    if (!bary_in(mesh.faces[f], sp, bp)) continue;
    // Directions to the neighbours in this face's frame: the distance is
    // attained at p only for directions d with d·(neighbour - p) <= 0.
    // Restricting is exact where the surface is flat around p (p inside a
    // face or an edge); at a vertex the windows are not restricted.
    std::vector<Vec2> cons;
    if (sp.size() >= 2) {
      const int h0 = g_.he.face_start(f);
      const Vec2 cs[3] = {corner(h0, 0), corner(h0, 1), corner(h0, 2)};
      for (const SurfacePoint* q : neighbours) {
        const auto sq = support_of(mesh, *q);
        const Vec3 Q3 = surface_point_position(mesh, *q);
        if ((Q3 - P3).norm() <= 1e-12 * g_.scale) continue;
        Vec3 bq;
        if (bary_in(mesh.faces[f], sq, bq)) {
          const Vec2 p2 = bp[0] * cs[0] + bp[1] * cs[1] + bp[2] * cs[2];
          const Vec2 q2 = bq[0] * cs[0] + bq[1] * cs[1] + bq[2] * cs[2];
          cons.push_back((q2 - p2).normalized());
          continue;
        }
        if (sp.size() != 2) continue;  // inside f: q must be in f (checked by add_segment)
        // p on edge (a, b) of f, q in the face across it: unfold by the hinge.
        int ka = -1, kb = -1;
        for (int k = 0; k < 3; ++k) {
          if (mesh.faces[f][k] == sp[0].first) ka = k;
          if (mesh.faces[f][k] == sp[1].first) kb = k;
        }
        const Vec3 xa = mesh.vertices[sp[0].first], xb = mesh.vertices[sp[1].first];
        const Vec3 e3 = (xb - xa).normalized();
        const Vec3 d3 = Q3 - P3;
        const double along = d3.dot(e3);
        const double across = (d3 - along * e3).norm();
        const Vec2 e2 = (cs[kb] - cs[ka]).normalized();
        Vec2 n2(-e2.y(), e2.x());
        const int kc = 3 - ka - kb;
        if (n2.dot(cs[kc] - cs[ka]) < 0.0) n2 = -n2;  // into f
        cons.push_back((along * e2 - across * n2).normalized());
      }
    }
    seed_face(f, bp, bp, true, cons);
  }
}

void GeodesicPropagation::run() {
  if (windows_.capacity() < 8 * static_cast<size_t>(g_.he.num_halfedges()))
    windows_.reserve(8 * static_cast<size_t>(g_.he.num_halfedges()));
  while (!queue_.empty()) {
    const QueueItem item = queue_.pop();
    if (item.id < 0) {
      const int v = -item.id - 1;
      if (item.key != dist_[v]) continue;  // stale
      emit_vertex(v);
      continue;
    }
    // (No second filter here: the vertex distances rarely improve enough
    // between a window's creation and its turn to drop it.)
    if (approx_) {  // approximate mode: windows change after creation (trimmed, killed, merged)
      Window& w = windows_[item.id];
      if (w.done) continue;
      w.done = true;
      if (g_.mergeable[w.h]) unpend(w.h, item.id);
      if (!w.dead) propagate(Window(w), item.id);
      continue;
    }
    if (!g_.mergeable[item.w.h]) {  // never changed after its creation: use the copy
      propagate(item.w, item.id);
      continue;
    }
    Window& w = windows_[item.id];
    if (w.done) continue;  // a merge re-queued it with a smaller key
    w.done = true;
    unpend(w.h, item.id);
    propagate(Window(w), item.id);
  }
}

// ---------------------------------------------------------------- tracing --

GeodesicPathPoint GeodesicPropagation::edge_point(int h, double x) const {
  const TriMesh& mesh = *g_.mesh;
  GeodesicPathPoint pt;
  const double L = g_.len[h];
  double t = L > 0.0 ? x / L : 0.0;
  const int a = g_.he.from(h), b = g_.he.to(h);
  const int f = g_.he.face(h);
  const int ka = g_.he.corner(h), kb = (ka + 1) % 3;
  pt.point.face = f;
  pt.point.bary = Vec3::Zero();
  if (t <= 1e-12) {
    pt.v0 = pt.v1 = a;
    pt.point.bary[ka] = 1.0;
    pt.position = mesh.vertices[a];
  } else if (t >= 1.0 - 1e-12) {
    pt.v0 = pt.v1 = b;
    pt.point.bary[kb] = 1.0;
    pt.position = mesh.vertices[b];
  } else {
    pt.v0 = a;
    pt.v1 = b;
    pt.ratio = t;
    pt.point.bary[ka] = 1.0 - t;
    pt.point.bary[kb] = t;
    pt.position = (1.0 - t) * mesh.vertices[a] + t * mesh.vertices[b];
  }
  return pt;
}

namespace {

GeodesicPathPoint vertex_point(const TriMesh& mesh, const Halfedges& he, const std::vector<int>& out_start,
                               const std::vector<int>& out_he, int v) {
  GeodesicPathPoint pt;
  pt.v0 = pt.v1 = v;
  const int h = out_he[out_start[v]];
  pt.point.face = he.face(h);
  pt.point.bary = Vec3::Zero();
  pt.point.bary[he.corner(h)] = 1.0;
  pt.position = mesh.vertices[v];
  return pt;
}

// True when some face holds the supports (vertices with a non-zero
// barycentric coordinate) of both points.
bool share_face(const TriMesh& mesh, const Halfedges& he, const std::vector<int>& out_start,
                const std::vector<int>& out_he, const GeodesicPathPoint& a, const GeodesicPathPoint& b) {
  std::array<int, 6> sup{};
  int n = 0;
  for (const GeodesicPathPoint* p : {&a, &b})
    for (int k = 0; k < 3; ++k)
      if (p->point.bary[k] != 0.0) sup[n++] = mesh.faces[p->point.face][k];
  if (n == 0) return true;
  for (int i = out_start[sup[0]]; i < out_start[sup[0] + 1]; ++i) {
    const auto& t = mesh.faces[he.face(out_he[i])];
    bool all = true;
    for (int j = 0; j < n && all; ++j) all = t[0] == sup[j] || t[1] == sup[j] || t[2] == sup[j];
    if (all) return true;
  }
  return false;
}

// Classifies a face point: vertex, edge point or interior.
GeodesicPathPoint face_point(const TriMesh& mesh, int f, const Vec3& bary) {
  GeodesicPathPoint pt;
  pt.point.face = f;
  pt.point.bary = bary;
  const auto& t = mesh.faces[f];
  pt.position = bary[0] * mesh.vertices[t[0]] + bary[1] * mesh.vertices[t[1]] + bary[2] * mesh.vertices[t[2]];
  int nz = 0, ks[3];
  for (int k = 0; k < 3; ++k)
    if (bary[k] != 0.0) ks[nz++] = k;
  if (nz == 1) {
    pt.v0 = pt.v1 = t[ks[0]];
  } else if (nz == 2) {
    pt.v0 = t[ks[0]];
    pt.v1 = t[ks[1]];
    pt.ratio = bary[ks[1]];
  }
  return pt;
}

}  // namespace

GeodesicPathPoint GeodesicPropagation::seed_point(int seed, const Vec3& from3d, int which, bool line) const {
  const TriMesh& mesh = *g_.mesh;
  const Seed& s = seeds_[seed];
  const auto& t = mesh.faces[s.face];
  auto pos = [&](const Vec3& b) {
    return Vec3(b[0] * mesh.vertices[t[0]] + b[1] * mesh.vertices[t[1]] + b[2] * mesh.vertices[t[2]]);
  };
  const Vec3 P = pos(s.bp), Q = pos(s.bq);
  double u;
  if (line || which < 0) {  // closest point of the segment
    const Vec3 d = Q - P;
    u = d.squaredNorm() > 0.0 ? std::clamp((from3d - P).dot(d) / d.squaredNorm(), 0.0, 1.0) : 0.0;
  } else {
    u = which == 0 ? 0.0 : 1.0;
  }
  Vec3 b = (1.0 - u) * s.bp + u * s.bq;
  for (int k = 0; k < 3; ++k)
    if (s.bp[k] == 0.0 && s.bq[k] == 0.0) b[k] = 0.0;  // keep exact zeros
  if (u == 0.0) b = s.bp;
  if (u == 1.0) b = s.bq;
  return face_point(mesh, s.face, b);
}

// Appends the path from point x (in the frame of window wi: a point of
// face(h), on or beyond the window's edge) back to the source: the straight
// backward ray of the window's distance function, walked face by face in the
// unfolding until it reaches the root (seed point, seed segment or
// pseudo-source vertex).
void GeodesicPropagation::trace_window_from(int wi, Vec2 x, std::vector<GeodesicPathPoint>& out) const {
  const TriMesh& mesh = *g_.mesh;
  const Window& w0 = windows_[wi];
  const bool line = w0.line;
  Vec2 s = w0.s;  // point: source; line: ray direction n
  double sigma = w0.sigma;
  int h = w0.h;
  // Crossing of the first edge.
  double xc = window_xint(w0, x);
  if (!std::isfinite(xc)) xc = x.x();
  xc = std::clamp(xc, 0.0, g_.len[h]);
  // The root is reached within rounding of face f (the face on the source
  // side of the last crossing). When the root's point is not on f (it lies
  // within rounding of a corner of f, in a face beyond it), the path goes
  // through that corner, so that consecutive points still share a face.
  auto push_root_point = [&](const GeodesicPathPoint& p, int f) {
    if (!share_face(mesh, g_.he, g_.out_start, g_.out_he, out.back(), p)) {
      int best = mesh.faces[f][0];
      for (int v : mesh.faces[f])
        if ((mesh.vertices[v] - p.position).squaredNorm() < (mesh.vertices[best] - p.position).squaredNorm()) best = v;
      out.push_back(vertex_point(mesh, g_.he, g_.out_start, g_.out_he, best));
    }
    out.push_back(p);
  };
  auto finish_root = [&](const Vec3& from3d, int f) {
    if (w0.origin == Origin::Vertex) {
      push_root_point(vertex_point(mesh, g_.he, g_.out_start, g_.out_he, w0.origin_id), f);
      trace_vertex_into(w0.origin_id, out);
    } else if (w0.origin == Origin::Seed) {
      push_root_point(seed_point(w0.origin_id, from3d, w0.aux, line), f);
    }
  };
  const int max_steps = 4 * g_.he.num_halfedges() + 8;
  for (int step = 0; step < max_steps; ++step) {
    const double L = g_.len[h];
    out.push_back(edge_point(h, xc));
    const int g = g_.he.opposite(h);
    if (g < 0) return;  // cannot happen for windows; stop safely
    // Into the frame of g (the face on the source side): rotation by π about
    // the edge's midpoint.
    Vec2 X(L - xc, 0.0);
    if (line) {
      sigma = sigma + s.x() * L;
      s = -s;
    } else {
      s = Vec2(L - s.x(), -s.y());
    }
    const Vec2 A(0.0, 0.0), B(L, 0.0), C = g_.apex[g];
    const double area2 = cross2(B - A, C - A);
    auto inside = [&](const Vec2& p) {
      if (!(area2 > 0.0)) return false;
      const double tol = 1e-9 * area2 + 1e-12 * g_.scale * L;
      return cross2(B - A, p - A) >= -tol && cross2(C - B, p - B) >= -tol && cross2(A - C, p - C) >= -tol;
    };
    Vec2 d;  // backward ray direction
    if (line) {
      const double r = s.dot(X) + sigma;  // remaining distance
      const Vec2 foot = X - r * s;
      if (r <= 1e-12 * g_.scale || inside(foot)) {
        finish_root(out.back().position, g_.he.face(g));
        return;
      }
      d = -s;
    } else {
      if (inside(s) || (s - X).norm() <= 1e-12 * g_.scale) {
        finish_root(out.back().position, g_.he.face(g));
        return;
      }
      d = s - X;
    }
    // Exit through edge B->C (next(g)) or C->A (prev(g)).
    int best_e = -1;
    double best_t = 0.0, best_u = kInf;
    for (int k = 1; k <= 2; ++k) {
      const Vec2 e0 = k == 1 ? B : C, e1 = k == 1 ? C : A;
      const Vec2 e = e1 - e0;
      const double den = cross2(d, e);
      if (den == 0.0) continue;
      const double u = cross2(e0 - X, e) / den;  // along the ray
      const double t = cross2(e0 - X, d) / den;  // along the edge
      const double slack = 1e-9;
      if (u <= 0.0 || t < -slack || t > 1.0 + slack) continue;
      // Prefer the edge hit well inside; ties at C go to either.
      const double score = std::abs(t - 0.5);
      if (best_e < 0 || score < best_u) {
        best_e = k;
        best_t = std::clamp(t, 0.0, 1.0);
        best_u = score;
      }
    }
    if (best_e < 0) {
      // The ray starts at a corner of g and leaves g at once: the crossing
      // was at an end of the edge, and the path goes on through that vertex
      // into another face around it. Continue from the vertex (its own
      // distance is at most the window's there, so the path is as short).
      const double tol = 1e-9 * L;
      const int corner_vertex = L - xc <= tol ? g_.he.from(g) : (xc <= tol ? g_.he.to(g) : -1);
      const double remaining = line ? s.dot(X) + sigma : (s - X).norm();
      if (corner_vertex >= 0 && remaining > 1e-9 * g_.scale && dist_[corner_vertex] < kInf &&
          vorigin_[corner_vertex] != Origin::None) {
        trace_vertex_into(corner_vertex, out);
        return;
      }
      finish_root(out.back().position, g_.he.face(g));  // numerically at the root already
      return;
    }
    const int e = best_e == 1 ? g_.he.next(g) : g_.he.prev(g);
    const Vec2 o = best_e == 1 ? B : C, to = best_e == 1 ? C : A;
    const double le = g_.len[e];
    if (!(le > 0.0)) return;
    const Frame fr{o, (to - o) / le};
    if (line) {
      sigma = sigma + s.dot(fr.o);
      s = fr.dir(s);
    } else {
      s = fr.point(s);
    }
    h = e;
    xc = best_t * le;
  }
}

void GeodesicPropagation::trace_vertex_into(int v, std::vector<GeodesicPathPoint>& out) const {
  const TriMesh& mesh = *g_.mesh;
  for (int guard = 0; guard < static_cast<int>(dist_.size()) + 2; ++guard) {
    switch (vorigin_[v]) {
      case Origin::Seed: {
        const GeodesicPathPoint sp = seed_point(vorigin_id_[v], mesh.vertices[v], -1, true);
        if ((sp.position - mesh.vertices[v]).norm() > 0.0) out.push_back(sp);
        return;
      }
      case Origin::Window: {
        const Window& w = windows_[vorigin_id_[v]];
        trace_window_from(vorigin_id_[v], g_.apex[w.h], out);
        return;
      }
      case Origin::Edge:
        v = vorigin_id_[v];
        out.push_back(vertex_point(mesh, g_.he, g_.out_start, g_.out_he, v));
        continue;
      default:
        return;
    }
  }
}

std::vector<GeodesicPathPoint> GeodesicPropagation::trace_vertex(int v) const {
  std::vector<GeodesicPathPoint> out{vertex_point(*g_.mesh, g_.he, g_.out_start, g_.out_he, v)};
  trace_vertex_into(v, out);
  return out;
}

std::vector<GeodesicPathPoint> GeodesicPropagation::trace_boundary() const {
  const BoundaryHit& b = boundary_;
  if (b.halfedge < 0) {  // a boundary vertex
    return b.origin == Origin::Vertex ? trace_vertex(b.origin_id) : std::vector<GeodesicPathPoint>{};
  }
  const int g = b.halfedge;
  std::vector<GeodesicPathPoint> out{edge_point(g, b.t * g_.len[g])};
  switch (b.origin) {
    case Origin::Window: {
      const Window& w = windows_[b.origin_id];
      // The boundary edge g is next(w.h) or prev(w.h); express the point in w's frame.
      const int k = g == g_.he.next(w.h) ? 1 : 2;
      const Vec2 a = corner(w.h, k), c = corner(w.h, k + 1);
      trace_window_from(b.origin_id, a + b.t * (c - a), out);
      (void)w;
      break;
    }
    case Origin::Vertex:
      out.push_back(vertex_point(*g_.mesh, g_.he, g_.out_start, g_.out_he, b.origin_id));
      trace_vertex_into(b.origin_id, out);
      break;
    case Origin::Seed:
      out.push_back(seed_point(b.origin_id, out.back().position, -1, true));
      break;
    default:
      break;
  }
  return out;
}

double GeodesicPropagation::trace_point(const SurfacePoint& p, std::vector<GeodesicPathPoint>* path) const {
  const TriMesh& mesh = *g_.mesh;
  const Vec3 X = surface_point_position(mesh, p);
  // Faces containing p.
  std::vector<int> faces;
  {
    int nz = 0, ks[3];
    for (int k = 0; k < 3; ++k)
      if (p.bary[k] != 0.0) ks[nz++] = k;
    const auto& t = mesh.faces[p.face];
    if (nz == 3) {
      faces.push_back(p.face);
    } else {
      const int v = t[ks[0]];
      for (int i = g_.out_start[v]; i < g_.out_start[v + 1]; ++i) {
        const int f = g_.he.face(g_.out_he[i]);
        bool ok = true;
        for (int j = 0; j < nz; ++j)
          ok = ok &&
               (mesh.faces[f][0] == t[ks[j]] || mesh.faces[f][1] == t[ks[j]] || mesh.faces[f][2] == t[ks[j]]);
        if (ok) faces.push_back(f);
      }
    }
  }
  double best = kInf;
  enum { kNone, kVertex, kWindow, kSeed } kind = kNone;
  int id = -1;
  Vec2 xw = Vec2::Zero();
  for (int f : faces) {
    for (int v : mesh.faces[f]) {
      const double d = dist_[v] + (mesh.vertices[v] - X).norm();
      if (d < best) {
        best = d;
        kind = kVertex;
        id = v;
      }
    }
  }
  for (int si = 0; si < static_cast<int>(seeds_.size()); ++si) {
    if (std::find(faces.begin(), faces.end(), seeds_[si].face) == faces.end()) continue;
    const GeodesicPathPoint sp = seed_point(si, X, -1, true);
    const double d = (sp.position - X).norm();
    if (d < best) {
      best = d;
      kind = kSeed;
      id = si;
    }
  }
  for (int wi = 0; wi < static_cast<int>(windows_.size()); ++wi) {
    const Window& w = windows_[wi];
    const int f = g_.he.face(w.h);
    if (w.dead || w.key >= best || std::find(faces.begin(), faces.end(), f) == faces.end()) continue;
    // p in the frame of w.h.
    const int h0 = w.h;
    const auto& t = mesh.faces[f];
    const int k0 = g_.he.corner(h0);
    Vec2 x = Vec2::Zero();
    for (int k = 0; k < 3; ++k) {
      const int v = t[(k0 + k) % 3];
      double wgt = 0.0;
      for (int j = 0; j < 3; ++j)
        if (mesh.faces[p.face][j] == v) wgt = p.bary[j];
      x += wgt * corner(h0, k);
    }
    if (x.y() < 0.0) x.y() = 0.0;
    const double xc = window_xint(w, x);
    const double L = g_.len[h0];
    if (!(xc >= w.b0 - 1e-12 * L && xc <= w.b1 + 1e-12 * L)) continue;
    const double d = window_distance(w, x);
    // A window must beat the vertex and seed candidates by more than rounding:
    // near ties (p on the window's edge, at a vertex) trace more robustly
    // through the vertex.
    if (d < best - (kind == kWindow ? 0.0 : g_.eps)) {
      best = d;
      kind = kWindow;
      id = wi;
      xw = x;
    }
  }
  if (path) {
    path->clear();
    path->push_back(face_point(mesh, p.face, p.bary));
    switch (kind) {
      case kVertex:
        if ((mesh.vertices[id] - X).norm() > 0.0)
          path->push_back(vertex_point(mesh, g_.he, g_.out_start, g_.out_he, id));
        trace_vertex_into(id, *path);
        break;
      case kSeed: {
        const GeodesicPathPoint sp = seed_point(id, X, -1, true);
        if ((sp.position - X).norm() > 0.0) path->push_back(sp);
        break;
      }
      case kWindow:
        trace_window_from(id, xw, *path);
        break;
      default:
        break;
    }
  }
  return best;
}

}  // namespace knitforge::detail
