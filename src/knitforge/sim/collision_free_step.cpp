#include "knitforge/sim/collision_free_step.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <mutex>

#include "knitforge/util/parallel_ranges.h"

namespace knitforge {

namespace {

constexpr double kKeep = 0.1;  // keep at least this fraction of the start distance
constexpr int kMaxAdvances = 10000;

// Distance from p to the body at time t of its motion start -> end, if
// within `bound` (else +inf). The tree's nearest() takes the bound by value
// and lowers its own copy: the best distance is kept here, in best2.
double distance_at(const TriMesh& start, const std::vector<Vec3>* end, const AabbTree& tree, const Vec3& p,
                   double t, double bound) {
  double best2 = bound * bound;
  bool found = false;
  tree.nearest(p, bound * bound, [&](int f, double& bound2) {
    const auto& tri = start.faces[f];
    Vec3 c[3];
    for (int k = 0; k < 3; ++k) {
      c[k] = start.vertices[tri[k]];
      if (end) c[k] += t * ((*end)[tri[k]] - c[k]);
    }
    const double d2 = (closest_point_on_triangle(p, c[0], c[1], c[2]) - p).squaredNorm();
    if (d2 <= bound2) bound2 = best2 = d2, found = true;
  });
  return found ? std::sqrt(best2) : std::numeric_limits<double>::infinity();
}

// The smallest of range(first, last) over ranges covering [0, n), the
// ranges on all hardware threads.
double smallest_over_ranges(size_t n, const std::function<double(int, int)>& range) {
  double smallest = 1.0;
  std::mutex m;
  parallel_ranges(n, 2048, [&](size_t begin, size_t end) {
    const double t = range(static_cast<int>(begin), static_cast<int>(end));
    const std::lock_guard<std::mutex> lock(m);
    smallest = std::min(smallest, t);
  });
  return smallest;
}

// The largest fraction t (< t_limit) of the move x0 -> x1 over which a
// vertex of a body at rest keeps kKeep of its start distance: conservative
// advancement, the distance changing at most at the vertex's speed; for the
// vertices [first, last).
double advance_range(const TriMesh& start, const AabbTree& tree, const Eigen::VectorXd& x0, const Eigen::VectorXd& x1,
                     const std::vector<char>& skip, int first, int last) {
  double t_min = 1.0;
  for (int v = first; v < last && t_min > 0; ++v) {
    if (!skip.empty() && skip[v]) continue;
    const Vec3 p0 = x0.segment<3>(3 * v);
    const Vec3 dp = x1.segment<3>(3 * v) - p0;
    const double l = dp.norm();
    if (!(l > 0)) continue;
    // Farther than l / (1 - kKeep): the whole move keeps 90 % of the distance.
    const double reach = l / (1.0 - kKeep);
    const double d0 = distance_at(start, nullptr, tree, p0, 0.0, reach);
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
      d = distance_at(start, nullptr, tree, p0 + t * dp, t, d0 + l);
      if (d - g <= 0.1 * (d0 - g)) break;
    }
    if (limited) t_min = std::min(t_min, t);
  }
  return t_min;
}

// The same for a moving body, face by face: the distance from the vertex to
// one face changes at most at the vertex's speed plus the face's (the
// largest of its corners' displacements), so each face gets its own bound
// and keeps kKeep of its own start distance. A vertex resting on a still part
// of the body is then held back only by the moving faces near it, by how
// near they are, not by the fastest part of the body or by its distance to
// the still part.
// With per_vertex, every vertex's own fraction is stored there (and the
// search does not stop at the first vertex that allows none).
double advance_moving_range(const TriMesh& start, const std::vector<Vec3>& end, const AabbTree& swept,
                            const std::vector<double>& face_speed, double body_speed, const Eigen::VectorXd& x0,
                            const Eigen::VectorXd& x1, const std::vector<char>& skip, std::vector<double>* per_vertex,
                            int first, int last) {
  double t_all = 1.0;
  for (int v = first; v < last && (per_vertex || t_all > 0); ++v) {
    if (!skip.empty() && skip[v]) continue;
    double t_min = per_vertex ? 1.0 : t_all;
    const Vec3 p0 = x0.segment<3>(3 * v);
    const Vec3 dp = x1.segment<3>(3 * v) - p0;
    const double speed = dp.norm();
    if (!(speed + body_speed > 0)) continue;
    const Aabb path = Aabb::of({p0, p0 + dp});
    swept.for_each_overlapping(path.inflated((speed + body_speed) / (1.0 - kKeep)), [&](int f) {
      if (t_min <= 0) return;
      const double l = speed + face_speed[f];
      if (!(l > 0)) return;
      const auto& tri = start.faces[f];
      auto distance = [&](double t) {
        Vec3 c[3];
        for (int k = 0; k < 3; ++k) c[k] = start.vertices[tri[k]] + t * (end[tri[k]] - start.vertices[tri[k]]);
        const Vec3 p = p0 + t * dp;
        return (closest_point_on_triangle(p, c[0], c[1], c[2]) - p).norm();
      };
      const double d0 = distance(0.0);
      if (d0 * (1.0 - kKeep) >= l) return;  // keeps 90 % over the whole move
      if (!(d0 > 0)) {
        t_min = 0.0;
        return;
      }
      const double g = kKeep * d0;
      double t = 0.0, d = d0;
      for (int it = 0; it < kMaxAdvances; ++it) {
        const double next = t + 0.9 * (d - g) / l;
        if (next >= t_min || next >= 1.0) return;  // not limiting
        t = next;
        d = distance(t);
        if (d - g <= 0.1 * (d0 - g)) break;
      }
      t_min = std::min(t_min, t);
    });
    t_all = std::min(t_all, t_min);
    if (per_vertex) (*per_vertex)[v] = t_min;
  }
  return t_all;
}

// The searches above over all vertices, in ranges on all hardware threads,
// each range bounded by its own smallest fraction so far: a vertex stopped
// by that bound ends at or above it (t only grows), so the minimum over the
// ranges is the serial search's exactly.
double advance(const TriMesh& start, const AabbTree& tree, const Eigen::VectorXd& x0, const Eigen::VectorXd& x1,
               const std::vector<char>& skip) {
  return smallest_over_ranges(static_cast<size_t>(x0.size() / 3), [&](int first, int last) {
    return advance_range(start, tree, x0, x1, skip, first, last);
  });
}

double advance_moving(const TriMesh& start, const std::vector<Vec3>& end, const AabbTree& swept,
                      const std::vector<double>& face_speed, double body_speed, const Eigen::VectorXd& x0,
                      const Eigen::VectorXd& x1, const std::vector<char>& skip, std::vector<double>* per_vertex) {
  const int n = static_cast<int>(x0.size() / 3);
  if (per_vertex) per_vertex->assign(n, 1.0);
  return smallest_over_ranges(static_cast<size_t>(n), [&](int first, int last) {
    return advance_moving_range(start, end, swept, face_speed, body_speed, x0, x1, skip, per_vertex, first, last);
  });
}

}  // namespace

double collision_free_step(const KinematicBody& body, const Eigen::VectorXd& x0, const Eigen::VectorXd& x1,
                           const std::vector<char>& skip) {
  if (body.empty()) return 1.0;
  return advance(body.mesh(), body.tree(), x0, x1, skip);
}

double collision_free_step(const KinematicBody& body, const std::vector<Vec3>& body_end, const Eigen::VectorXd& x0,
                           const Eigen::VectorXd& x1, const std::vector<char>& skip, std::vector<double>* per_vertex) {
  if (body.empty()) {
    if (per_vertex) per_vertex->assign(x0.size() / 3, 1.0);
    return 1.0;
  }
  const TriMesh& m = body.mesh();
  std::vector<double> face_speed(m.faces.size(), 0.0);
  double speed = 0.0;
  for (size_t f = 0; f < m.faces.size(); ++f) {
    for (int k : m.faces[f]) face_speed[f] = std::max(face_speed[f], (body_end[k] - m.vertices[k]).norm());
    speed = std::max(speed, face_speed[f]);
  }
  const AabbTree swept(face_boxes(m, &body_end));
  return advance_moving(m, body_end, swept, face_speed, speed, x0, x1, skip, per_vertex);
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
