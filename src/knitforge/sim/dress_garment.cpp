#include "knitforge/sim/dress_garment.h"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "knitforge/geometry/alpha_close.h"  // enclosed_volume()
#include "knitforge/geometry/pseudo_normals.h"
#include "knitforge/util/errors.h"

namespace knitforge {

namespace {

constexpr double kFar = 1e9;  // mm: every body point is nearer

struct Side {
  BodyPoint closest;
  double signed_distance = 0.0;  // > 0 outside
  Vec3 outward = Vec3::Zero();   // unit
};

// +1, or -1 for a closed body whose faces point inwards (its enclosed volume
// is negative): then its outside is where its normals do not point.
double outward_sign(const KinematicBody& body) {
  return is_closed_mesh(body.mesh()) && enclosed_volume(body.mesh()) < 0.0 ? -1.0 : 1.0;
}

Side side_of(const KinematicBody& body, const PseudoNormals& normals, double sign, const Vec3& p) {
  Side s;
  s.closest = *body.closest_point_within(p, kFar);
  const Vec3 d = p - s.closest.where.point;
  const Vec3 n = sign * normals.at(body.mesh(), s.closest.face, s.closest.where);
  const double dist = std::sqrt(s.closest.distance2);
  const bool outside = d.dot(n) > 0.0;
  s.signed_distance = outside ? dist : -dist;
  if (outside && dist > 0.0) {
    s.outward = d / dist;
  } else {
    const double len = n.norm();
    s.outward = len > 0.0 ? Vec3(n / len) : Vec3(sign * body.face_normal(s.closest.face));
  }
  return s;
}

// The vertices not to touch, after checking every point is finite.
std::vector<char> skip_mask(const std::vector<int>& skip, const std::vector<Vec3>& points, const char* who) {
  const size_t n = points.size();
  for (size_t v = 0; v < n; ++v)
    if (!points[v].allFinite()) throw InvalidInput(fmt::format("{}: vertex {} is not finite", who, v));
  std::vector<char> mask(n, 0);
  for (int v : skip) {
    if (v < 0 || static_cast<size_t>(v) >= n)
      throw InvalidInput(fmt::format("{}: vertex {} out of range ({} vertices)", who, v, n));
    mask[static_cast<size_t>(v)] = 1;
  }
  return mask;
}

}  // namespace

DressResult dress_garment(const KinematicBody& body, const std::vector<Vec3>& garment, const std::vector<int>& skip,
                          const DressOptions& o) {
  if (!(o.clearance_mm > 0.0) || !std::isfinite(o.clearance_mm))
    throw InvalidInput(fmt::format("dressing: the clearance must be positive, got {} mm", o.clearance_mm));
  if (!(o.max_depth_mm > 0.0))
    throw InvalidInput(fmt::format("dressing: the largest depth must be positive, got {} mm", o.max_depth_mm));
  if (body.empty()) throw InvalidInput("dressing: the body has no faces");
  const std::vector<char> fixed = skip_mask(skip, garment, "dressing");
  const PseudoNormals normals = pseudo_normals(body.mesh());
  const double sign = outward_sign(body);
  DressResult r;
  r.positions = garment;
  std::vector<char> moved(garment.size(), 0);
  for (int pass = 0; pass < kDressPasses; ++pass) {
    bool any = false;
    for (size_t v = 0; v < garment.size(); ++v) {
      if (fixed[v]) continue;
      const Side s = side_of(body, normals, sign, r.positions[v]);
      if (s.signed_distance >= o.clearance_mm * (1.0 - 1e-9)) continue;
      if (pass == 0 && s.signed_distance <= 0.0) {
        ++r.inside;
        r.deepest_mm = std::max(r.deepest_mm, -s.signed_distance);
        if (-s.signed_distance > o.max_depth_mm)
          throw InvalidInput(fmt::format(
              "dressing: garment vertex {} lies {:.1f} mm inside the body, deeper than {} mm: the garment is not "
              "where the body is; place it around the body (or raise the largest depth)",
              v, -s.signed_distance, o.max_depth_mm));
      }
      r.positions[v] = s.closest.where.point + o.clearance_mm * s.outward;
      r.largest_move_mm = std::max(r.largest_move_mm, (r.positions[v] - garment[v]).norm());
      moved[v] = 1;
      any = true;
    }
    if (!any) break;
    r.passes = pass + 1;
  }
  for (size_t v = 0; v < garment.size(); ++v) {
    if (!moved[v]) continue;
    ++r.moved;
    const Side s = side_of(body, normals, sign, r.positions[v]);
    if (s.signed_distance < 0.5 * o.clearance_mm)
      throw InvalidInput(fmt::format(
          "dressing: garment vertex {} is still {:.2f} mm from the body after {} passes (a crevice narrower than "
          "the clearance of {} mm); use a smaller clearance or place the garment there yourself",
          v, s.signed_distance, kDressPasses, o.clearance_mm));
  }
  return r;
}

std::vector<InsidePoint> points_inside_body(const KinematicBody& body, const std::vector<Vec3>& points,
                                            const std::vector<int>& skip) {
  std::vector<InsidePoint> out;
  if (body.empty() || !is_closed_mesh(body.mesh())) return out;
  const std::vector<char> fixed = skip_mask(skip, points, "inside test");
  const PseudoNormals normals = pseudo_normals(body.mesh());
  const double sign = outward_sign(body);
  for (size_t v = 0; v < points.size(); ++v) {
    if (fixed[v]) continue;
    const Side s = side_of(body, normals, sign, points[v]);
    if (s.signed_distance < 0.0) out.push_back({static_cast<int>(v), -s.signed_distance});
  }
  std::stable_sort(out.begin(), out.end(), [](const InsidePoint& a, const InsidePoint& b) { return a.depth_mm > b.depth_mm; });
  return out;
}

}  // namespace knitforge
