#include "knitforge/render/yarn_tubes.h"

#include <algorithm>
#include <climits>
#include <cmath>
#include <limits>
#include <numbers>

#include <fmt/core.h>

#include "knitforge/util/errors.h"

namespace knitforge {

namespace {

constexpr double kDuplicate = 1e-9;

// Consecutive distinct points of a polyline.
std::vector<Vec3> distinct_points(std::span<const Vec3> points) {
  std::vector<Vec3> p;
  p.reserve(points.size());
  for (size_t i = 0; i < points.size(); ++i) {
    if (!points[i].allFinite()) throw InvalidInput(fmt::format("yarn point {} is not finite", i));
    if (p.empty() || (points[i] - p.back()).squaredNorm() > kDuplicate * kDuplicate) p.push_back(points[i]);
  }
  return p;
}

// The knots of the centripetal Catmull-Rom segment p1 -> p2 (t0 = 0) and
// the reciprocals of the knot differences the pyramid divides by.
struct Knots {
  double t1, t2, t3;
  double r10, r21, r32, r20, r31;
};

Knots knots(const Vec3& p0, const Vec3& p1, const Vec3& p2, const Vec3& p3) {
  Knots k{};
  k.t1 = std::sqrt((p1 - p0).norm());
  k.t2 = k.t1 + std::sqrt((p2 - p1).norm());
  k.t3 = k.t2 + std::sqrt((p3 - p2).norm());
  k.r10 = 1.0 / k.t1;
  k.r21 = 1.0 / (k.t2 - k.t1);
  k.r32 = 1.0 / (k.t3 - k.t2);
  k.r20 = 1.0 / k.t2;
  k.r31 = 1.0 / (k.t3 - k.t1);
  return k;
}

// Point at parameter u in [0, 1] of the centripetal Catmull-Rom segment
// p1 -> p2 (Barry-Goldman pyramid).
Vec3 catmull_rom(const Vec3& p0, const Vec3& p1, const Vec3& p2, const Vec3& p3, const Knots& k, double u) {
  const double t1 = k.t1, t2 = k.t2, t3 = k.t3;
  const double t = t1 + u * (t2 - t1);
  const Vec3 a1 = ((t1 - t) * p0 + t * p1) * k.r10;
  const Vec3 a2 = ((t2 - t) * p1 + (t - t1) * p2) * k.r21;
  const Vec3 a3 = ((t3 - t) * p2 + (t - t2) * p3) * k.r32;
  const Vec3 b1 = ((t2 - t) * a1 + t * a2) * k.r20;
  const Vec3 b2 = ((t3 - t) * a2 + (t - t1) * a3) * k.r31;
  return ((t2 - t) * b1 + (t - t1) * b2) * k.r21;
}

Vec3 any_orthogonal(const Vec3& t) {
  const Vec3 a = t.cwiseAbs();
  Vec3 axis = Vec3::UnitX();
  if (a.y() <= a.x() && a.y() <= a.z())
    axis = Vec3::UnitY();
  else if (a.z() <= a.x() && a.z() <= a.y())
    axis = Vec3::UnitZ();
  return (axis - axis.dot(t) * t).normalized();
}

// Walks the rotation-minimising frames of curve x in one pass (double
// reflection, Wang et al. 2008), calling
// f(i, tangent, normal, arc length at i, length of segment i -> i+1 or 0).
template <class F>
void walk_frames(std::span<const Vec3> x, F&& f) {
  const size_t n = x.size();
  if (n < 2) throw InvalidInput("parallel_transport_frames: a curve needs at least 2 samples");
  Vec3 a = Vec3::Zero();  // unit direction of segment i-1
  Vec3 v_prev = Vec3::Zero(), t_prev = Vec3::Zero(), r_prev = Vec3::Zero();
  double c_prev = 0.0, arc = 0.0;
  for (size_t i = 0; i < n; ++i) {
    Vec3 v = Vec3::Zero(), b = Vec3::Zero();
    double c = 0.0, len = 0.0;
    if (i + 1 < n) {
      v = x[i + 1] - x[i];
      c = v.squaredNorm();
      len = std::sqrt(c);
      if (!(len > 0.0) || !std::isfinite(len)) {
        throw InvalidInput(fmt::format("parallel_transport_frames: samples {} and {} coincide", i, i + 1));
      }
      b = v * (1.0 / len);
    }
    Vec3 t = a + b;
    const double tt = t.squaredNorm();
    if (tt < 1e-24)
      t = i + 1 < n ? b : a;  // a cusp: keep the outgoing direction (unit)
    else
      t /= std::sqrt(tt);
    Vec3 r;
    if (i == 0) {
      r = any_orthogonal(t);
    } else {
      // reflect (normal, tangent) of i-1 in the bisector plane of the
      // segment, then in the plane that maps the reflected tangent to t
      const double two_c = 2.0 / c_prev;
      const Vec3 rl = r_prev - (two_c * v_prev.dot(r_prev)) * v_prev;
      const Vec3 tl = t_prev - (two_c * v_prev.dot(t_prev)) * v_prev;
      const Vec3 v2 = t - tl;
      const double c2 = v2.squaredNorm();
      const double two_c2 = c2 > 1e-24 ? 2.0 / c2 : 0.0;  // (off the r dependency chain)
      r = rl - (two_c2 * v2.dot(rl)) * v2;
      r -= r.dot(t) * t;  // remove rounding drift
      // reflections keep |r| = 1 up to rounding: one Newton step for
      // 1 / |r| (error ~ (|r|^2 - 1)^2) instead of a square root and a
      // division on the dependency chain
      const double rr = r.squaredNorm();
      if (std::abs(rr - 1.0) < 1e-6) {
        r *= 0.5 * (3.0 - rr);
      } else {
        const double rn = std::sqrt(rr);
        r = rn > 1e-12 ? Vec3(r / rn) : any_orthogonal(t);
      }
    }
    f(i, t, r, arc, len);
    a = b;
    v_prev = v;
    c_prev = c;
    t_prev = t;
    r_prev = r;
    arc += len;
  }
}

void check_options(const TubeOptions& o, double radius) {
  if (!(radius > 0.0) || !std::isfinite(radius)) {
    throw InvalidInput(fmt::format("tube radius = {} must be positive (mm)", radius));
  }
  if (o.plies < 1) throw InvalidInput(fmt::format("plies = {} must be at least 1", o.plies));
  if (o.vertices_per_ply < 1)
    throw InvalidInput(fmt::format("vertices_per_ply = {} must be at least 1", o.vertices_per_ply));
  if (static_cast<int64_t>(o.plies) * o.vertices_per_ply > (int64_t{1} << 20)) {
    throw InvalidInput(fmt::format("plies x vertices_per_ply = {} x {} is more than 2^20 vertices per ring",
                                   o.plies, o.vertices_per_ply));
  }
  if (!(o.ply_depth >= 0.0 && o.ply_depth <= 1.0))
    throw InvalidInput(fmt::format("ply_depth = {} must be in [0, 1]", o.ply_depth));
  if (!std::isfinite(o.twist_per_mm)) throw InvalidInput("twist_per_mm must be finite");
  if (!(o.ring_spacing >= 0.0) || !std::isfinite(o.ring_spacing)) {
    throw InvalidInput(fmt::format("ring_spacing = {} must be >= 0 (mm; 0 = the radius)", o.ring_spacing));
  }
}

// Vertex k of a ring (the one expression both the double and the float
// output use, so they agree to float rounding).
Vec3 ring_point(const TubeSection& s, const TubeRing& r, size_t k) {
  return r.centre + s.x[k] * r.u + s.y[k] * r.w;
}
Vec3 ring_normal(const TubeSection& s, const TubeRing& r, size_t k) { return s.nx[k] * r.u + s.ny[k] * r.w; }

// Calls emit(a, b, c) for the side triangles between consecutive rings,
// vertex j K + k + base = ring j, vertex k.
template <class Emit>
void for_each_side_triangle(std::span<const TubeRing> rings, uint32_t K, uint32_t base, Emit&& emit) {
  const size_t n = rings.size() < 2 ? 0 : rings.size() - 1;
  for (size_t j = 0; j < n; ++j) {
    const uint32_t s = static_cast<uint32_t>(rings[j].shift) % K;
    const uint32_t r0 = base + static_cast<uint32_t>(j) * K, r1 = r0 + K;
    uint32_t ks = s;                        // (k + s) mod K
    uint32_t k1s = s + 1 == K ? 0 : s + 1;  // (k + 1 + s) mod K
    for (uint32_t k = 0; k < K; ++k) {
      const uint32_t k1 = k + 1 == K ? 0 : k + 1;
      const uint32_t a = r0 + k, b = r0 + k1, c = r1 + k1s, d = r1 + ks;
      emit(a, b, d);
      emit(b, c, d);
      ks = k1s;
      k1s = k1s + 1 == K ? 0 : k1s + 1;
    }
  }
}

template <class Index>
void side_indices(std::span<const TubeRing> rings, int k_ring, uint32_t base, std::span<Index> out) {
  const size_t n = rings.size() < 2 ? 0 : rings.size() - 1;
  if (k_ring < 1 || out.size() != 6 * static_cast<size_t>(k_ring) * n) {
    throw InvalidInput(
        fmt::format("tube_side_indices: {} indices for {} ring pairs of {} vertices", out.size(), n, k_ring));
  }
  const uint64_t largest = base + static_cast<uint64_t>(k_ring) * (n + 1) - 1;
  if (n > 0 && largest > std::numeric_limits<Index>::max()) {
    throw InvalidInput(fmt::format("tube_side_indices: index {} does not fit the index type", largest));
  }
  Index* o = out.data();
  for_each_side_triangle(rings, static_cast<uint32_t>(k_ring), base, [&](uint32_t a, uint32_t b, uint32_t c) {
    o[0] = static_cast<Index>(a);
    o[1] = static_cast<Index>(b);
    o[2] = static_cast<Index>(c);
    o += 3;
  });
}

}  // namespace

std::vector<Vec3> smooth_polyline(std::span<const Vec3> points, double spacing) {
  if (!(spacing > 0.0) || !std::isfinite(spacing)) {
    throw InvalidInput(fmt::format("smooth_polyline: spacing = {} must be positive (mm)", spacing));
  }
  const std::vector<Vec3> p = distinct_points(points);
  if (p.size() < 3) return p;  // a straight segment (or less) is its own curve
  const size_t m = p.size();
  // exact output size: every segment's sample count (a rare near-duplicate
  // sample is dropped below, so this is an upper bound)
  size_t total = 1;
  std::vector<int> steps(m - 1);
  for (size_t i = 0; i + 1 < m; ++i) {
    const double len = (p[i + 1] - p[i]).norm();
    steps[i] = std::max(1, static_cast<int>(std::min(std::ceil(len / spacing - 1e-9), 1e9)));
    total += static_cast<size_t>(steps[i]);
  }
  std::vector<Vec3> out;
  out.reserve(total);
  for (size_t i = 0; i + 1 < m; ++i) {
    const Vec3& p1 = p[i];
    const Vec3& p2 = p[i + 1];
    out.push_back(p1);
    const int n = steps[i];
    if (n == 1) continue;
    const Vec3 p0 = i > 0 ? p[i - 1] : Vec3(2.0 * p1 - p2);
    const Vec3 p3 = i + 2 < m ? p[i + 2] : Vec3(2.0 * p2 - p1);
    const Knots kn = knots(p0, p1, p2, p3);
    for (int k = 1; k < n; ++k) {
      const Vec3 q = catmull_rom(p0, p1, p2, p3, kn, static_cast<double>(k) / n);
      if ((q - out.back()).squaredNorm() > kDuplicate * kDuplicate) out.push_back(q);
    }
  }
  if ((p.back() - out.back()).norm() > kDuplicate) out.push_back(p.back());
  return out;
}

CurveFrames parallel_transport_frames(std::span<const Vec3> x) {
  if (x.size() < 2) throw InvalidInput("parallel_transport_frames: a curve needs at least 2 samples");
  CurveFrames f;
  f.tangents.resize(x.size());
  f.normals.resize(x.size());
  f.arc_length.resize(x.size());
  walk_frames(x, [&](size_t i, const Vec3& t, const Vec3& r, double arc, double) {
    f.tangents[i] = t;
    f.normals[i] = r;
    f.arc_length[i] = arc;
  });
  return f;
}

TubeSection tube_section(const TubeOptions& o, double radius) {
  check_options(o, radius);
  TubeSection s;
  s.plies = o.plies;
  s.vertices_per_ply = o.vertices_per_ply;
  const int n = o.plies;
  const size_t K = static_cast<size_t>(o.plies) * static_cast<size_t>(o.vertices_per_ply);
  const double two_pi = 2.0 * std::numbers::pi;
  // Radius factor per cross-section vertex: the envelope of n touching ply
  // circles (centres at distance c, radius rho = c sin(pi/n), c + rho = R).
  std::vector<double> angle(K), factor(K, 1.0);
  for (size_t k = 0; k < K; ++k) {
    angle[k] = two_pi * static_cast<double>(k) / static_cast<double>(K);
    if (n >= 2) {
      const double sn = std::sin(std::numbers::pi / n);
      const double c = 1.0 / (1.0 + sn), rho = c * sn;
      // offset from the ply's centre line
      double d =
          two_pi * static_cast<double>(k % static_cast<size_t>(o.vertices_per_ply)) / static_cast<double>(K);
      if (d > std::numbers::pi / n) d -= two_pi / n;
      const double env =
          c * std::cos(d) + std::sqrt(std::max(0.0, rho * rho - c * c * std::sin(d) * std::sin(d)));
      factor[k] = 1.0 - o.ply_depth * (1.0 - env);
    }
  }
  s.x.resize(K);
  s.y.resize(K);
  for (size_t k = 0; k < K; ++k) {
    s.x[k] = radius * factor[k] * std::cos(angle[k]);
    s.y[k] = radius * factor[k] * std::sin(angle[k]);
  }
  // Shading normal of cross-section vertex k: the outward perpendicular of
  // the chord between its two neighbours in the cross-section plane (the
  // exact radial direction for a round section; follows the ply relief).
  s.nx.resize(K);
  s.ny.resize(K);
  for (size_t k = 0; k < K; ++k) {
    const size_t prev = (k + K - 1) % K;
    const size_t next = (k + 1) % K;
    double du = s.y[next] - s.y[prev], dw = -(s.x[next] - s.x[prev]);
    if (K < 3) {  // a degenerate section: the radial direction
      du = std::cos(angle[k]);
      dw = std::sin(angle[k]);
    }
    const double len = std::hypot(du, dw);
    s.nx[k] = du / len;
    s.ny[k] = dw / len;
  }
  return s;
}

double tube_ring_spacing(const TubeOptions& o, double radius) {
  return o.ring_spacing > 0.0 ? o.ring_spacing : radius;
}

void for_each_tube_ring(std::span<const Vec3> curve, const TubeOptions& o,
                        const std::function<void(size_t, const TubeRing&)>& emit) {
  if (o.plies < 1 || o.vertices_per_ply < 1 || !std::isfinite(o.twist_per_mm)) {
    check_options(o, 1.0);  // throws the option's message
  }
  const int n = o.plies;
  const long k_ring = static_cast<long>(o.plies) * o.vertices_per_ply;
  const double two_pi = 2.0 * std::numbers::pi;
  TubeRing ring;
  walk_frames(curve, [&](size_t i, const Vec3& t, const Vec3& nrm, double arc, double len) {
    ring.centre = curve[i];
    // the twist phase, reduced to one turn first (exact for long yarns)
    const double turns = o.twist_per_mm * arc;
    const double phase = two_pi * (turns - std::floor(turns));
    const double cp = std::cos(phase), sp = std::sin(phase);
    const Vec3 b = t.cross(nrm);
    ring.u = cp * nrm + sp * b;
    ring.w = -sp * nrm + cp * b;
    // Ring i+1 is rotated by the twist against ring i; connecting vertex k
    // to vertex k + shift of the next ring (shift a whole number of plies,
    // so a ply crest meets a crest) keeps the side triangles from shearing
    // more than half a ply.
    double q = o.twist_per_mm * len * n;  // plies turned between the rings
    if (!(std::abs(q) < 1e15)) q = std::fmod(q, static_cast<double>(n));
    long p = static_cast<long>(q >= 0.0 ? q + 0.5 : q - 0.5);  // std::lround
    if (p < 0 || p >= n) p = ((p % n) + n) % n;                // usually 0 or 1 already
    ring.shift = p == 0 ? 0 : static_cast<int>(k_ring - p * o.vertices_per_ply);
    emit(i, ring);
  });
}

std::vector<TubeRing> tube_rings(std::span<const Vec3> polyline, const TubeOptions& o, double radius) {
  check_options(o, radius);
  const std::vector<Vec3> curve = smooth_polyline(polyline, tube_ring_spacing(o, radius));
  std::vector<TubeRing> rings;
  if (curve.size() < 2) return rings;
  rings.resize(curve.size());
  for_each_tube_ring(curve, o, [&](size_t i, const TubeRing& r) { rings[i] = r; });
  return rings;
}

void tube_ring_vertices(const TubeSection& section, std::span<const TubeRing> rings,
                        std::span<float> positions, std::span<float> normals) {
  const size_t K = static_cast<size_t>(section.size());
  if (section.x.size() != K || section.y.size() != K || section.nx.size() != K || section.ny.size() != K ||
      positions.size() != 3 * K * rings.size() || normals.size() != positions.size()) {
    throw InvalidInput(
        fmt::format("tube_ring_vertices: {} position and {} normal floats for {} rings of {} vertices",
                    positions.size(), normals.size(), rings.size(), K));
  }
  float* p = positions.data();
  float* q = normals.data();
  for (const TubeRing& r : rings) {
    for (size_t k = 0; k < K; ++k) {
      const Vec3 v = ring_point(section, r, k);
      const Vec3 nv = ring_normal(section, r, k);
      p[0] = static_cast<float>(v.x());
      p[1] = static_cast<float>(v.y());
      p[2] = static_cast<float>(v.z());
      q[0] = static_cast<float>(nv.x());
      q[1] = static_cast<float>(nv.y());
      q[2] = static_cast<float>(nv.z());
      p += 3;
      q += 3;
    }
  }
}

void tube_side_indices(std::span<const TubeRing> rings, int k_ring, uint32_t base,
                       std::span<uint32_t> indices) {
  side_indices(rings, k_ring, base, indices);
}
void tube_side_indices(std::span<const TubeRing> rings, int k_ring, uint32_t base,
                       std::span<uint16_t> indices) {
  side_indices(rings, k_ring, base, indices);
}

RenderMesh yarn_tube(std::span<const Vec3> polyline, const TubeOptions& o, double radius,
                     const RenderColour& colour) {
  const TubeSection section = tube_section(o, radius);
  RenderMesh out;
  out.colour = colour;
  const std::vector<TubeRing> rings = tube_rings(polyline, o, radius);
  if (rings.empty()) return out;

  const int k_ring = section.size();
  const size_t K = static_cast<size_t>(k_ring);
  const size_t n_rings = rings.size();
  const size_t cap_vertices = o.capped ? 2 * (K + 1) : 0;
  const size_t nv = n_rings * K + cap_vertices;
  if (nv > static_cast<size_t>(INT_MAX)) {
    throw InvalidInput(
        fmt::format("a tube would have {} vertices (more than 2^31); increase ring_spacing", nv));
  }
  out.mesh.vertices.resize(nv);
  out.normals.resize(nv);
  for (size_t i = 0; i < n_rings; ++i) {
    Vec3* ring = out.mesh.vertices.data() + i * K;
    Vec3* ring_n = out.normals.data() + i * K;
    for (size_t k = 0; k < K; ++k) {
      ring[k] = ring_point(section, rings[i], k);
      ring_n[k] = ring_normal(section, rings[i], k);
    }
  }
  const size_t side_faces = 2 * (n_rings - 1) * K;
  out.mesh.faces.reserve(side_faces + (o.capped ? 2 * K : 0));  // exact: no growth
  {
    auto& faces = out.mesh.faces;
    for_each_side_triangle(std::span<const TubeRing>(rings), static_cast<uint32_t>(k_ring), 0,
                           [&](uint32_t a, uint32_t b, uint32_t c) {
                             faces.push_back({static_cast<int>(a), static_cast<int>(b), static_cast<int>(c)});
                           });
  }
  if (o.capped) {
    const int base = static_cast<int>(n_rings) * k_ring;
    for (int end = 0; end < 2; ++end) {
      const TubeRing& r = end == 0 ? rings.front() : rings.back();
      const size_t ring = end == 0 ? 0 : n_rings - 1;
      const Vec3 tangent = r.u.cross(r.w).normalized();
      const Vec3 axis = end == 0 ? Vec3(-tangent) : tangent;
      const int first = base + end * (k_ring + 1);
      const int centre = first + k_ring;
      for (size_t k = 0; k < K; ++k) {
        out.mesh.vertices[static_cast<size_t>(first) + k] = out.mesh.vertices[ring * K + k];
        out.normals[static_cast<size_t>(first) + k] = axis;
      }
      out.mesh.vertices[static_cast<size_t>(centre)] = r.centre;
      out.normals[static_cast<size_t>(centre)] = axis;
      for (int k = 0; k < k_ring; ++k) {
        const int k1 = (k + 1) % k_ring;
        if (end == 0)
          out.mesh.faces.push_back({centre, first + k1, first + k});
        else
          out.mesh.faces.push_back({centre, first + k, first + k1});
      }
    }
  }
  return out;
}

double tube_radius(const TubeOptions& options, const KnitParams& params) {
  if (options.radius != 0.0) return options.radius;
  if (!(params.stitch_width > 0.0) || !std::isfinite(params.stitch_width)) {
    throw InvalidInput(fmt::format("stitch width = {} must be positive (mm)", params.stitch_width));
  }
  return 0.12 * params.stitch_width;
}

std::vector<RenderMesh> yarn_tubes(const YarnModel& yarn, const KnitParams& params,
                                   const TubeOptions& options, std::span<const RenderColour> colours) {
  const double radius = tube_radius(options, params);
  std::vector<RenderMesh> out;
  out.reserve(yarn.yarns.size());
  for (size_t i = 0; i < yarn.yarns.size(); ++i) {
    const Yarn& y = yarn.yarns[i];
    const RenderColour c = colours.empty() ? RenderColour{200, 200, 200} : colours[i % colours.size()];
    try {
      out.push_back(yarn_tube(y.points, options, radius, c));
    } catch (const InvalidInput& e) {
      throw InvalidInput(fmt::format("yarn {} (id {}): {}", i, y.id, e.what()));
    }
    out.back().name = fmt::format("yarn {}", y.id);
  }
  return out;
}

}  // namespace knitforge
