#include "knitforge/render/yarn_tubes.h"

#include <algorithm>
#include <climits>
#include <cmath>
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
    if (p.empty() || (points[i] - p.back()).norm() > kDuplicate) p.push_back(points[i]);
  }
  return p;
}

// Point at parameter u in [0, 1] of the centripetal Catmull-Rom segment
// p1 -> p2 (Barry-Goldman pyramid).
Vec3 catmull_rom(const Vec3& p0, const Vec3& p1, const Vec3& p2, const Vec3& p3, double u) {
  const double t0 = 0.0;
  const double t1 = t0 + std::sqrt((p1 - p0).norm());
  const double t2 = t1 + std::sqrt((p2 - p1).norm());
  const double t3 = t2 + std::sqrt((p3 - p2).norm());
  const double t = t1 + u * (t2 - t1);
  const Vec3 a1 = ((t1 - t) * p0 + (t - t0) * p1) / (t1 - t0);
  const Vec3 a2 = ((t2 - t) * p1 + (t - t1) * p2) / (t2 - t1);
  const Vec3 a3 = ((t3 - t) * p2 + (t - t2) * p3) / (t3 - t2);
  const Vec3 b1 = ((t2 - t) * a1 + (t - t0) * a2) / (t2 - t0);
  const Vec3 b2 = ((t3 - t) * a2 + (t - t1) * a3) / (t3 - t1);
  return ((t2 - t) * b1 + (t - t1) * b2) / (t2 - t1);
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

}  // namespace

std::vector<Vec3> smooth_polyline(std::span<const Vec3> points, double spacing) {
  if (!(spacing > 0.0) || !std::isfinite(spacing)) {
    throw InvalidInput(fmt::format("smooth_polyline: spacing = {} must be positive (mm)", spacing));
  }
  const std::vector<Vec3> p = distinct_points(points);
  if (p.size() < 3) return p;  // a straight segment (or less) is its own curve
  const size_t m = p.size();
  std::vector<Vec3> out;
  out.reserve(m * 2);
  for (size_t i = 0; i + 1 < m; ++i) {
    const Vec3& p1 = p[i];
    const Vec3& p2 = p[i + 1];
    const Vec3 p0 = i > 0 ? p[i - 1] : Vec3(2.0 * p1 - p2);
    const Vec3 p3 = i + 2 < m ? p[i + 2] : Vec3(2.0 * p2 - p1);
    const double len = (p2 - p1).norm();
    const int n = std::max(1, static_cast<int>(std::ceil(len / spacing - 1e-9)));
    out.push_back(p1);
    for (int k = 1; k < n; ++k) {
      const Vec3 q = catmull_rom(p0, p1, p2, p3, static_cast<double>(k) / n);
      if ((q - out.back()).norm() > kDuplicate) out.push_back(q);
    }
  }
  if ((p.back() - out.back()).norm() > kDuplicate) out.push_back(p.back());
  return out;
}

CurveFrames parallel_transport_frames(std::span<const Vec3> x) {
  const size_t n = x.size();
  if (n < 2) throw InvalidInput("parallel_transport_frames: a curve needs at least 2 samples");
  CurveFrames f;
  f.tangents.resize(n);
  f.normals.resize(n);
  f.arc_length.resize(n);
  f.arc_length[0] = 0.0;
  for (size_t i = 0; i + 1 < n; ++i) {
    const double len = (x[i + 1] - x[i]).norm();
    if (!(len > 0.0))
      throw InvalidInput(fmt::format("parallel_transport_frames: samples {} and {} coincide", i, i + 1));
    f.arc_length[i + 1] = f.arc_length[i] + len;
  }
  for (size_t i = 0; i < n; ++i) {
    const Vec3 a = i > 0 ? Vec3((x[i] - x[i - 1]).normalized()) : Vec3::Zero();
    const Vec3 b = i + 1 < n ? Vec3((x[i + 1] - x[i]).normalized()) : Vec3::Zero();
    Vec3 t = a + b;
    if (t.norm() < 1e-12) t = b.norm() > 0.0 ? b : a;  // a cusp: keep the outgoing direction
    f.tangents[i] = t.normalized();
  }
  f.normals[0] = any_orthogonal(f.tangents[0]);
  for (size_t i = 0; i + 1 < n; ++i) {
    const Vec3 v1 = x[i + 1] - x[i];
    const double c1 = v1.squaredNorm();
    const Vec3& r = f.normals[i];
    const Vec3& t = f.tangents[i];
    const Vec3 rl = r - (2.0 / c1) * v1.dot(r) * v1;
    const Vec3 tl = t - (2.0 / c1) * v1.dot(t) * v1;
    const Vec3 v2 = f.tangents[i + 1] - tl;
    const double c2 = v2.squaredNorm();
    Vec3 rn = c2 > 1e-24 ? Vec3(rl - (2.0 / c2) * v2.dot(rl) * v2) : rl;
    const Vec3& tn = f.tangents[i + 1];
    rn -= rn.dot(tn) * tn;  // remove rounding drift
    const double len = rn.norm();
    f.normals[i + 1] = len > 1e-12 ? Vec3(rn / len) : any_orthogonal(tn);
  }
  return f;
}

RenderMesh yarn_tube(std::span<const Vec3> polyline, const TubeOptions& o, double radius,
                     const RenderColour& colour) {
  if (!(radius > 0.0) || !std::isfinite(radius)) {
    throw InvalidInput(fmt::format("tube radius = {} must be positive (mm)", radius));
  }
  if (o.plies < 1) throw InvalidInput(fmt::format("plies = {} must be at least 1", o.plies));
  if (o.vertices_per_ply < 1)
    throw InvalidInput(fmt::format("vertices_per_ply = {} must be at least 1", o.vertices_per_ply));
  if (!(o.ply_depth >= 0.0 && o.ply_depth <= 1.0))
    throw InvalidInput(fmt::format("ply_depth = {} must be in [0, 1]", o.ply_depth));
  if (!std::isfinite(o.twist_per_mm)) throw InvalidInput("twist_per_mm must be finite");
  if (!(o.ring_spacing >= 0.0) || !std::isfinite(o.ring_spacing)) {
    throw InvalidInput(fmt::format("ring_spacing = {} must be >= 0 (mm; 0 = the radius)", o.ring_spacing));
  }
  const double spacing = o.ring_spacing > 0.0 ? o.ring_spacing : radius;
  RenderMesh out;
  const std::vector<Vec3> curve = smooth_polyline(polyline, spacing);
  if (curve.size() < 2) return out;
  const CurveFrames fr = parallel_transport_frames(curve);

  const int n = o.plies;
  const int k_ring = o.plies * o.vertices_per_ply;
  const size_t rings = curve.size();
  const size_t cap_vertices = o.capped ? 2 * (static_cast<size_t>(k_ring) + 1) : 0;
  const size_t nv = rings * static_cast<size_t>(k_ring) + cap_vertices;
  if (nv > static_cast<size_t>(INT_MAX)) {
    throw InvalidInput(
        fmt::format("a tube would have {} vertices (more than 2^31); increase ring_spacing", nv));
  }

  // Radius factor per cross-section vertex: the envelope of n touching ply
  // circles (centres at distance c, radius rho = c sin(pi/n), c + rho = R).
  std::vector<double> factor(static_cast<size_t>(k_ring), 1.0);
  std::vector<double> angle(static_cast<size_t>(k_ring));
  const double two_pi = 2.0 * std::numbers::pi;
  for (int k = 0; k < k_ring; ++k) {
    angle[static_cast<size_t>(k)] = two_pi * k / k_ring;
    if (n >= 2) {
      const double s = std::sin(std::numbers::pi / n);
      const double c = 1.0 / (1.0 + s), rho = c * s;
      double d = two_pi * (k % o.vertices_per_ply) / k_ring;  // offset from the ply's centre line
      if (d > std::numbers::pi / n) d -= two_pi / n;
      const double env =
          c * std::cos(d) + std::sqrt(std::max(0.0, rho * rho - c * c * std::sin(d) * std::sin(d)));
      factor[static_cast<size_t>(k)] = 1.0 - o.ply_depth * (1.0 - env);
    }
  }

  // cross-section offsets in the (rotated) frame, radius included
  std::vector<double> ring_cos(static_cast<size_t>(k_ring)), ring_sin(static_cast<size_t>(k_ring));
  for (size_t k = 0; k < static_cast<size_t>(k_ring); ++k) {
    ring_cos[k] = radius * factor[k] * std::cos(angle[k]);
    ring_sin[k] = radius * factor[k] * std::sin(angle[k]);
  }
  // Shading normal of cross-section vertex k: the outward perpendicular of
  // the chord between its two neighbours in the cross-section plane (the
  // exact radial direction for a round section; follows the ply relief).
  std::vector<double> normal_u(static_cast<size_t>(k_ring)), normal_w(static_cast<size_t>(k_ring));
  for (size_t k = 0; k < static_cast<size_t>(k_ring); ++k) {
    const size_t prev = (k + static_cast<size_t>(k_ring) - 1) % static_cast<size_t>(k_ring);
    const size_t next = (k + 1) % static_cast<size_t>(k_ring);
    double du = ring_sin[next] - ring_sin[prev], dw = -(ring_cos[next] - ring_cos[prev]);
    if (k_ring < 3) {  // a degenerate section: the radial direction
      du = std::cos(angle[k]);
      dw = std::sin(angle[k]);
    }
    const double len = std::hypot(du, dw);
    normal_u[k] = du / len;
    normal_w[k] = dw / len;
  }
  out.mesh.vertices.resize(nv);
  out.normals.resize(nv);
  const size_t side_faces = 2 * (rings - 1) * static_cast<size_t>(k_ring);
  out.mesh.faces.reserve(side_faces + (o.capped ? 2 * static_cast<size_t>(k_ring) : 0));
  for (size_t i = 0; i < rings; ++i) {
    const Vec3& t = fr.tangents[i];
    const Vec3& nrm = fr.normals[i];
    const Vec3 b = t.cross(nrm);
    const double phase = two_pi * o.twist_per_mm * fr.arc_length[i];
    const double cp = std::cos(phase), sp = std::sin(phase);
    // rotate the frame by the twist phase once per ring
    const Vec3 u = cp * nrm + sp * b, w = -sp * nrm + cp * b;
    Vec3* ring = out.mesh.vertices.data() + i * static_cast<size_t>(k_ring);
    Vec3* ring_n = out.normals.data() + i * static_cast<size_t>(k_ring);
    for (size_t k = 0; k < static_cast<size_t>(k_ring); ++k) {
      ring[k] = curve[i] + ring_cos[k] * u + ring_sin[k] * w;
      ring_n[k] = normal_u[k] * u + normal_w[k] * w;
    }
  }
  // Ring i+1 is rotated by the twist against ring i; connecting vertex k to
  // vertex k + shift of the next ring (shift a whole number of plies, so a
  // ply crest meets a crest) keeps the side triangles from shearing more
  // than half a ply.
  for (size_t i = 0; i + 1 < rings; ++i) {
    const double turns = o.twist_per_mm * (fr.arc_length[i + 1] - fr.arc_length[i]);
    const long plies_turned = std::lround(turns * n);
    int s = static_cast<int>((-plies_turned * o.vertices_per_ply) % k_ring);
    if (s < 0) s += k_ring;
    const int r0 = static_cast<int>(i) * k_ring, r1 = r0 + k_ring;
    for (int k = 0; k < k_ring; ++k) {
      const int k1 = (k + 1) % k_ring;
      const int a = r0 + k, b = r0 + k1, c = r1 + (k1 + s) % k_ring, d = r1 + (k + s) % k_ring;
      out.mesh.faces.push_back({a, b, d});
      out.mesh.faces.push_back({b, c, d});
    }
  }
  if (o.capped) {
    const int base = static_cast<int>(rings) * k_ring;
    for (int end = 0; end < 2; ++end) {
      const size_t ring = end == 0 ? 0 : rings - 1;
      const Vec3 axis = end == 0 ? Vec3(-fr.tangents[0]) : fr.tangents[rings - 1];
      const int first = base + end * (k_ring + 1);
      const int centre = first + k_ring;
      for (int k = 0; k < k_ring; ++k) {
        out.mesh.vertices[static_cast<size_t>(first + k)] =
            out.mesh.vertices[ring * static_cast<size_t>(k_ring) + static_cast<size_t>(k)];
        out.normals[static_cast<size_t>(first + k)] = axis;
      }
      out.mesh.vertices[static_cast<size_t>(centre)] = curve[ring];
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
  out.vertex_colours.assign(nv, colour);
  out.colour = colour;
  return out;
}

std::vector<RenderMesh> yarn_tubes(const YarnModel& yarn, const KnitParams& params,
                                   const TubeOptions& options, std::span<const RenderColour> colours) {
  double radius = options.radius;
  if (radius == 0.0) {
    if (!(params.stitch_width > 0.0) || !std::isfinite(params.stitch_width)) {
      throw InvalidInput(fmt::format("stitch width = {} must be positive (mm)", params.stitch_width));
    }
    radius = 0.12 * params.stitch_width;
  }
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
