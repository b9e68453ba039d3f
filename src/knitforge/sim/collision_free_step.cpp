#include "knitforge/sim/collision_free_step.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace knitforge {

namespace {

constexpr double kKeep = 0.1;  // keep at least this fraction of the start distance
constexpr int kMaxAdvances = 10000;

// Distance from p to the body at time t of its motion start -> end, if
// within `bound` (else +inf).
double distance_at(const TriMesh& start, const std::vector<Vec3>* end, const AabbTree& tree, const Vec3& p,
                   double t, double bound) {
  double best2 = bound * bound;
  bool found = false;
  tree.nearest(p, best2, [&](int f, double& bound2) {
    const auto& tri = start.faces[f];
    Vec3 c[3];
    for (int k = 0; k < 3; ++k) {
      c[k] = start.vertices[tri[k]];
      if (end) c[k] += t * ((*end)[tri[k]] - c[k]);
    }
    const double d2 = (closest_point_on_triangle(p, c[0], c[1], c[2]) - p).squaredNorm();
    if (d2 <= bound2) bound2 = d2, found = true;
  });
  return found ? std::sqrt(best2) : std::numeric_limits<double>::infinity();
}

double advance(const TriMesh& start, const std::vector<Vec3>* end, const AabbTree& tree, double body_speed,
               const Eigen::VectorXd& x0, const Eigen::VectorXd& x1, const std::vector<char>& skip) {
  double t_min = 1.0;
  const int n = static_cast<int>(x0.size() / 3);
  for (int v = 0; v < n && t_min > 0; ++v) {
    if (!skip.empty() && skip[v]) continue;
    const Vec3 p0 = x0.segment<3>(3 * v);
    const Vec3 dp = x1.segment<3>(3 * v) - p0;
    const double l = dp.norm() + body_speed;
    if (!(l > 0)) continue;
    // Farther than l / (1 - kKeep): the whole move keeps 90 % of the distance.
    const double reach = l / (1.0 - kKeep);
    const double d0 = distance_at(start, end, tree, p0, 0.0, reach);
    if (!std::isfinite(d0)) continue;
    if (!(d0 > 0)) return 0.0;
    const double g = kKeep * d0;
    double t = 0.0, d = d0;
    bool limited = true;
    for (int it = 0; it < kMaxAdvances; ++it) {
      const double next = t + 0.9 * (d - g) / l;
      // Past the step, or past what another vertex allows: not limiting.
      if (next >= t_min || next >= 1.0) {
        limited = false;
        break;
      }
      t = next;
      d = distance_at(start, end, tree, p0 + t * dp, t, d0 + l);
      if (d - g <= 0.1 * (d0 - g)) break;
    }
    if (limited) t_min = std::min(t_min, t);
  }
  return t_min;
}

}  // namespace

double collision_free_step(const KinematicBody& body, const Eigen::VectorXd& x0, const Eigen::VectorXd& x1,
                           const std::vector<char>& skip) {
  if (body.empty()) return 1.0;
  return advance(body.mesh(), nullptr, body.tree(), 0.0, x0, x1, skip);
}

double collision_free_step(const KinematicBody& body, const std::vector<Vec3>& body_end, const Eigen::VectorXd& x0,
                           const Eigen::VectorXd& x1, const std::vector<char>& skip) {
  if (body.empty()) return 1.0;
  double speed = 0.0;
  for (size_t k = 0; k < body_end.size(); ++k) speed = std::max(speed, (body_end[k] - body.mesh().vertices[k]).norm());
  const AabbTree swept(face_boxes(body.mesh(), &body_end));
  return advance(body.mesh(), &body_end, swept, speed, x0, x1, skip);
}

double min_distance_to_body(const KinematicBody& body, const Eigen::VectorXd& x, double max_distance,
                            const std::vector<char>& skip) {
  double best = std::numeric_limits<double>::infinity();
  if (body.empty()) return best;
  for (int v = 0; v < static_cast<int>(x.size() / 3); ++v) {
    if (!skip.empty() && skip[v]) continue;
    const auto q = body.closest_point_within(x.segment<3>(3 * v), std::min(best, max_distance));
    if (q) best = std::min(best, std::sqrt(q->distance2));
  }
  return best;
}

}  // namespace knitforge
