#include "knitforge/sim/leg_motion.h"

#include <cmath>
#include <numbers>

#include <fmt/core.h>

#include "knitforge/util/errors.h"

namespace knitforge {

namespace {

// +x (the arm's axis) to -z (the leg's), z to +x: a rotation about y.
Vec3 to_leg(const Vec3& a) { return Vec3(a.z(), a.y(), -a.x()); }
Vec3 to_arm(const Vec3& l) { return Vec3(-l.z(), l.y(), l.x()); }

// The leg's checks, in the leg's words (the arm's would name the arm).
void check(const LegMotionParams& p) {
  const std::pair<const char*, double> sizes[] = {
      {"thigh_length_mm", p.thigh_length_mm}, {"shin_length_mm", p.shin_length_mm},
      {"thigh_radius_mm", p.thigh_radius_mm}, {"shin_radius_mm", p.shin_radius_mm},
      {"body_edge_mm", p.body_edge_mm},       {"legging_edge_mm", p.legging_edge_mm},
      {"clearance_mm", p.clearance_mm},       {"transition_mm", p.transition_mm}};
  for (const auto& [name, v] : sizes) {
    if (!(v > 0) || !std::isfinite(v))
      throw InvalidInput(fmt::format("leg motion: {} must be a positive finite length in mm (got {})", name, v));
  }
  if (p.shin_radius_mm > p.thigh_radius_mm) {
    throw InvalidInput(fmt::format("leg motion: the shin radius {} mm exceeds the thigh's {} mm", p.shin_radius_mm,
                                   p.thigh_radius_mm));
  }
  if (p.body_edge_mm > p.shin_radius_mm || p.legging_edge_mm > p.shin_radius_mm) {
    throw InvalidInput(fmt::format("leg motion: the edges ({} mm body, {} mm legging) must not exceed the shin "
                                   "radius {} mm",
                                   p.body_edge_mm, p.legging_edge_mm, p.shin_radius_mm));
  }
  if (!(p.max_angle_deg >= 0 && p.max_angle_deg <= 150)) {
    throw InvalidInput(fmt::format("leg motion: the knee angle {} degrees must be in [0, 150]", p.max_angle_deg));
  }
  if (!(p.waist_margin_mm >= 0 && p.waist_margin_mm < p.thigh_length_mm - p.legging_edge_mm)) {
    throw InvalidInput(fmt::format("leg motion: waist_margin_mm {} must be in [0, {}) (the legging starts on the thigh)",
                                   p.waist_margin_mm, p.thigh_length_mm - p.legging_edge_mm));
  }
  if (!(p.ankle_margin_mm >= 0 && p.thigh_length_mm + p.shin_length_mm - p.ankle_margin_mm >=
                                      p.thigh_length_mm + p.transition_mm)) {
    throw InvalidInput(fmt::format("leg motion: the ankle cuff ({} mm below the hip) must lie on the shin past the "
                                   "transition ({} mm below the hip); shorten ankle_margin_mm or transition_mm",
                                   p.thigh_length_mm + p.shin_length_mm - p.ankle_margin_mm,
                                   p.thigh_length_mm + p.transition_mm));
  }
}

ArmMotionParams as_limb(const LegMotionParams& p) {
  check(p);
  ArmMotionParams a;
  a.upper_length_mm = p.thigh_length_mm;
  a.forearm_length_mm = p.shin_length_mm;
  a.upper_radius_mm = p.thigh_radius_mm;
  a.forearm_radius_mm = p.shin_radius_mm;
  a.max_angle_deg = p.max_angle_deg;
  a.body_edge_mm = p.body_edge_mm;
  a.sleeve_edge_mm = p.legging_edge_mm;
  a.clearance_mm = p.clearance_mm;
  a.sleeve_start_mm = p.waist_margin_mm;
  a.wrist_margin_mm = p.ankle_margin_mm;
  a.transition_mm = p.transition_mm;
  return a;
}

}  // namespace

double leg_knee_angle_deg(const LegMotionParams& p, int frame, int frames) {
  return arm_elbow_angle_deg(as_limb(p), frame, frames);
}

TriMesh leg_body_mesh(const LegMotionParams& p, double angle_deg) {
  TriMesh m = arm_body_mesh(as_limb(p), angle_deg);
  for (Vec3& v : m.vertices) v = to_leg(v);
  return m;
}

double leg_signed_distance(const LegMotionParams& p, double angle_deg, const Vec3& x) {
  return arm_signed_distance(as_limb(p), angle_deg, to_arm(x));
}

Vec3 leg_knee(const LegMotionParams& p) { return Vec3(0, 0, -p.thigh_length_mm); }

Vec3 leg_ankle(const LegMotionParams& p, double angle_deg) {
  const double a = angle_deg * std::numbers::pi / 180.0;
  return leg_knee(p) + p.shin_length_mm * Vec3(std::sin(a), 0, -std::cos(a));
}

SleeveMesh legging_mesh(const LegMotionParams& p) {
  SleeveMesh s = arm_sleeve_mesh(as_limb(p));
  for (Vec3& v : s.mesh.vertices) v = to_leg(v);
  for (Vec3& c : s.course_directions) c = to_leg(c);
  return s;
}

}  // namespace knitforge
