#include "knitforge/sim/arm_motion.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include <fmt/core.h>

#include "knitforge/geometry/shapes.h"
#include "knitforge/util/errors.h"

namespace knitforge {

namespace {

constexpr double kPi = std::numbers::pi;

void check_params(const ArmMotionParams& p) {
  const double sizes[] = {p.upper_length_mm, p.forearm_length_mm, p.upper_radius_mm, p.forearm_radius_mm,
                          p.body_edge_mm,    p.sleeve_edge_mm,    p.clearance_mm,    p.transition_mm};
  for (double s : sizes) {
    if (!(s > 0) || !std::isfinite(s)) {
      throw InvalidInput(fmt::format(
          "arm motion: lengths, radii, edges, clearance and transition must be positive finite mm (got {})", s));
    }
  }
  if (p.forearm_radius_mm > p.upper_radius_mm) {
    throw InvalidInput(fmt::format("arm motion: the forearm radius {} mm exceeds the upper arm's {} mm",
                                   p.forearm_radius_mm, p.upper_radius_mm));
  }
  if (p.body_edge_mm > p.forearm_radius_mm || p.sleeve_edge_mm > p.forearm_radius_mm) {
    throw InvalidInput(fmt::format("arm motion: the edges ({} mm body, {} mm sleeve) must not exceed the forearm "
                                   "radius {} mm",
                                   p.body_edge_mm, p.sleeve_edge_mm, p.forearm_radius_mm));
  }
  if (!(p.max_angle_deg >= 0 && p.max_angle_deg <= 150)) {
    throw InvalidInput(fmt::format("arm motion: the elbow angle {} degrees must be in [0, 150]", p.max_angle_deg));
  }
}

// A closed capsule along local +x from 0 to `length` (radius r, edge e),
// outward normals: rings of equal vertex count between two poles.
TriMesh capsule(double length, double r, double e) {
  const int n = std::max(8, static_cast<int>(std::lround(2 * kPi * r / e)));
  const int m = std::max(2, static_cast<int>(std::lround(0.5 * kPi * r / e)));
  const int c = std::max(1, static_cast<int>(std::lround(length / e)));
  std::vector<std::pair<double, double>> profile;  // (x, ring radius)
  for (int k = 1; k <= m; ++k) {
    const double a = 0.5 * kPi * k / m;
    profile.emplace_back(-r * std::cos(a), r * std::sin(a));
  }
  for (int k = 1; k <= c; ++k) profile.emplace_back(length * k / c, r);
  for (int k = 1; k < m; ++k) {
    const double b = 0.5 * kPi * k / m;
    profile.emplace_back(length + r * std::sin(b), r * std::cos(b));
  }
  TriMesh t;
  t.vertices.emplace_back(-r, 0.0, 0.0);
  for (const auto& [x, rho] : profile) {
    for (int j = 0; j < n; ++j) {
      const double phi = 2 * kPi * j / n;
      t.vertices.emplace_back(x, rho * std::cos(phi), rho * std::sin(phi));
    }
  }
  t.vertices.emplace_back(length + r, 0.0, 0.0);
  const int rings = static_cast<int>(profile.size());
  const int last = t.num_vertices() - 1;
  auto ring = [&](int k, int j) { return 1 + k * n + (j % n); };
  for (int j = 0; j < n; ++j) t.faces.push_back({0, ring(0, j + 1), ring(0, j)});
  for (int k = 0; k + 1 < rings; ++k) {
    for (int j = 0; j < n; ++j) {
      t.faces.push_back({ring(k, j), ring(k, j + 1), ring(k + 1, j + 1)});
      t.faces.push_back({ring(k, j), ring(k + 1, j + 1), ring(k + 1, j)});
    }
  }
  for (int j = 0; j < n; ++j) t.faces.push_back({last, ring(rings - 1, j), ring(rings - 1, j + 1)});
  // Orient every face away from the axis segment (the construction's winding
  // depends on the sense of the angle; this makes it explicit).
  for (auto& f : t.faces) {
    const Vec3 a = t.vertices[f[0]], b = t.vertices[f[1]], d = t.vertices[f[2]];
    const Vec3 centre = (a + b + d) / 3.0;
    const Vec3 axis_point(std::clamp(centre.x(), 0.0, length), 0.0, 0.0);
    if ((b - a).cross(d - a).dot(centre - axis_point) < 0) std::swap(f[1], f[2]);
  }
  return t;
}

// The sleeve's radius at x along the straight arm.
double sleeve_radius(const ArmMotionParams& p, double x) {
  const double t = std::clamp((x - p.upper_length_mm) / p.transition_mm, 0.0, 1.0);
  const double s = t * t * (3 - 2 * t);
  return (p.upper_radius_mm + p.clearance_mm) * (1 - s) + (p.forearm_radius_mm + p.clearance_mm) * s;
}

}  // namespace

double arm_elbow_angle_deg(const ArmMotionParams& p, int frame, int frames) {
  if (frames < 1 || frame < 0 || frame > frames) {
    throw InvalidInput(fmt::format("arm motion: frame {} of {} (frames must be >= 1, the frame in [0, frames])",
                                   frame, frames));
  }
  const double s = static_cast<double>(frame) / frames;
  return p.max_angle_deg * s * s * (3 - 2 * s);
}

double arm_signed_distance(const ArmMotionParams& p, double angle_deg, const Vec3& x) {
  const double a = angle_deg * kPi / 180.0;
  const Vec3 elbow(p.upper_length_mm, 0, 0);
  const Vec3 wrist = elbow + p.forearm_length_mm * Vec3(std::cos(a), 0, std::sin(a));
  auto to_segment = [&](const Vec3& s0, const Vec3& s1) {
    const double t = std::clamp((x - s0).dot(s1 - s0) / (s1 - s0).squaredNorm(), 0.0, 1.0);
    return (x - (s0 + t * (s1 - s0))).norm();
  };
  return std::min(to_segment(Vec3::Zero(), elbow) - p.upper_radius_mm, to_segment(elbow, wrist) - p.forearm_radius_mm);
}

int arm_upper_vertex_count(const ArmMotionParams& p) {
  check_params(p);
  return capsule(p.upper_length_mm, p.upper_radius_mm, p.body_edge_mm).num_vertices();
}

TriMesh arm_body_mesh(const ArmMotionParams& p, double angle_deg) {
  check_params(p);
  if (!std::isfinite(angle_deg)) throw InvalidInput("arm motion: the elbow angle is not finite");
  TriMesh body = capsule(p.upper_length_mm, p.upper_radius_mm, p.body_edge_mm);
  const TriMesh fore = capsule(p.forearm_length_mm, p.forearm_radius_mm, p.body_edge_mm);
  const double a = angle_deg * kPi / 180.0;
  Mat3 R;  // maps +x to (cos a, 0, sin a): the forearm flexes upwards
  R << std::cos(a), 0, -std::sin(a), 0, 1, 0, std::sin(a), 0, std::cos(a);
  const Vec3 elbow(p.upper_length_mm, 0, 0);
  const int base = body.num_vertices();
  for (const Vec3& v : fore.vertices) body.vertices.push_back(elbow + R * v);
  for (const auto& f : fore.faces) body.faces.push_back({f[0] + base, f[1] + base, f[2] + base});
  return body;
}

SleeveMesh arm_sleeve_mesh(const ArmMotionParams& p) {
  check_params(p);
  const double start = p.sleeve_start_mm, end = p.upper_length_mm + p.forearm_length_mm - p.wrist_margin_mm;
  if (!(start >= 0 && start < p.upper_length_mm - p.sleeve_edge_mm)) {
    throw InvalidInput(fmt::format("arm motion: the sleeve must start on the upper arm (0 <= start < {} mm), not "
                                   "at {} mm",
                                   p.upper_length_mm - p.sleeve_edge_mm, start));
  }
  if (!(end >= p.upper_length_mm + p.transition_mm && p.wrist_margin_mm >= 0)) {
    throw InvalidInput(fmt::format(
        "arm motion: the cuff ({} mm from the shoulder) must lie on the forearm past the transition ({} mm); "
        "shorten the wrist margin or the transition",
        end, p.upper_length_mm + p.transition_mm));
  }
  const double length = end - start;
  const TriMesh tube = open_tube(p.upper_radius_mm + p.clearance_mm, length, p.sleeve_edge_mm);
  SleeveMesh out;
  out.mesh.faces = tube.faces;
  out.mesh.vertices.reserve(tube.vertices.size());
  for (size_t v = 0; v < tube.vertices.size(); ++v) {
    const Vec3& q = tube.vertices[v];
    const double x = start + q.z();
    const double rho = sleeve_radius(p, x);
    const double l = std::hypot(q.x(), q.y());
    // (x, y, z) -> (z, x, y) is a rotation: the tube's outward normals stay outward.
    out.mesh.vertices.emplace_back(x, rho * q.x() / l, rho * q.y() / l);
    if (q.z() == 0.0) out.shoulder_ring.push_back(static_cast<int>(v));
    if (q.z() == length) out.cuff_ring.push_back(static_cast<int>(v));
  }
  out.attached = out.shoulder_ring;
  out.attached.insert(out.attached.end(), out.cuff_ring.begin(), out.cuff_ring.end());
  std::sort(out.attached.begin(), out.attached.end());
  out.course_directions.reserve(out.mesh.faces.size());
  for (const auto& f : out.mesh.faces) {
    const Vec3 c = (out.mesh.vertices[f[0]] + out.mesh.vertices[f[1]] + out.mesh.vertices[f[2]]) / 3.0;
    out.course_directions.push_back(Vec3(0.0, -c.z(), c.y()).normalized());
  }
  return out;
}

}  // namespace knitforge
