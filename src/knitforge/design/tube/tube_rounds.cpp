#include "knitforge/design/tube/tube_rounds.h"

#include <algorithm>
#include <cmath>
#include <tuple>

#include <fmt/format.h>

#include "knitforge/geometry/isocurves.h"
#include "knitforge/geometry/mesh_measures.h"
#include "knitforge/util/errors.h"

namespace knitforge {

namespace {

Vec3 vector_area(const std::vector<Vec3>& p) {
  Vec3 a = Vec3::Zero();
  for (size_t i = 0; i < p.size(); ++i) a += p[i].cross(p[(i + 1) % p.size()]);
  return a;
}

double closed_length(const std::vector<Vec3>& p) {
  double l = 0.0;
  for (size_t i = 0; i < p.size(); ++i) l += (p[(i + 1) % p.size()] - p[i]).norm();
  return l;
}

// The closed polyline p turned to start at its point nearest to q (a point
// inside a segment is inserted).
std::vector<Vec3> start_nearest(const std::vector<Vec3>& p, const Vec3& q) {
  const size_t n = p.size();
  size_t best = 0;
  double best_d = -1.0;
  Vec3 best_p = p[0];
  for (size_t i = 0; i < n; ++i) {
    const Vec3 c = closest_point_on_segment(q, p[i], p[(i + 1) % n]);
    const double d = (c - q).squaredNorm();
    if (best_d < 0.0 || d < best_d) best_d = d, best = i, best_p = c;
  }
  std::vector<Vec3> out;
  out.reserve(n + 1);
  size_t first = (best + 1) % n;  // the polyline goes on from here after the start
  if ((best_p - p[best]).squaredNorm() == 0.0) {
    first = best;
  } else if ((best_p - p[first]).squaredNorm() > 0.0) {
    out.push_back(best_p);
  }
  for (size_t k = 0; k < n; ++k) out.push_back(p[(first + k) % n]);
  return out;
}

}  // namespace

std::vector<RoundCurve> tube_round_curves(const TriMesh& mesh, const TubeField& field,
                                          const std::vector<double>& levels, const std::optional<Vec3>& start) {
  const size_t K = levels.size() - 1;
  std::vector<double> inner(levels.begin() + 1, levels.end() - 1);
  const auto curves = inner.empty() ? std::vector<std::vector<Isocurve>>{}
                                    : extract_isocurves(mesh, field.value, inner);
  std::vector<RoundCurve> rounds(K + 1);
  auto loop_points = [&](const std::vector<int>& loop) {
    std::vector<Vec3> p;
    for (int v : loop) p.push_back(mesh.vertices[static_cast<size_t>(v)]);
    return p;
  };
  std::vector<Vec3> p0 = loop_points(field.start_loop);
  size_t s0 = 0;
  for (size_t i = 1; i < p0.size(); ++i) {
    if (std::tie(p0[i].x(), p0[i].y(), p0[i].z()) < std::tie(p0[s0].x(), p0[s0].y(), p0[s0].z())) s0 = i;
  }
  std::rotate(p0.begin(), p0.begin() + static_cast<long>(s0), p0.end());
  rounds[0].points = start ? start_nearest(p0, *start) : std::move(p0);
  for (size_t k = 1; k <= K; ++k) {
    std::vector<Vec3> p;
    if (k == K) {
      p = loop_points(field.end_loop);
    } else {
      const auto& c = curves[k - 1];
      if (c.size() != 1 || !c[0].closed) {
        throw InvalidInput(fmt::format(
            "tube rounds: round {} (u = {:.4f}) is {} piece(s){}, not one closed loop round the tube; the field "
            "has a critical point there (design the surface without --tube)",
            k, levels[k], c.size(), c.size() == 1 ? ", open" : ""));
      }
      p = c[0].positions;
    }
    if (vector_area(p).dot(vector_area(rounds[k - 1].points)) < 0.0) std::reverse(p.begin(), p.end());
    rounds[k].points = start_nearest(p, rounds[k - 1].points[0]);
  }
  for (RoundCurve& r : rounds) r.length = closed_length(r.points);
  return rounds;
}

std::vector<Vec3> sample_round(const RoundCurve& round, int count, int front) {
  const std::vector<Vec3>& p = round.points;
  const size_t n = p.size();
  std::vector<double> s(n + 1, 0.0);  // arc length at point i (s[n]: back at the start)
  for (size_t i = 0; i < n; ++i) s[i + 1] = s[i] + (p[(i + 1) % n] - p[i]).norm();
  const double L = s[n];
  std::vector<Vec3> out;
  out.reserve(static_cast<size_t>(count));
  size_t seg = 0;
  for (int i = 0; i < count; ++i) {
    const double t = i < front ? 0.5 * L * i / front : 0.5 * L + 0.5 * L * (i - front) / (count - front);
    while (seg + 1 < n && s[seg + 1] < t) ++seg;
    const double len = s[seg + 1] - s[seg];
    const double a = len > 0.0 ? std::clamp((t - s[seg]) / len, 0.0, 1.0) : 0.0;
    out.push_back((1.0 - a) * p[seg] + a * p[(seg + 1) % n]);
  }
  return out;
}

Vec3 round_point_at(const RoundCurve& round, double f) {
  const std::vector<Vec3>& p = round.points;
  const size_t n = p.size();
  if (n == 1) return p[0];
  f -= std::floor(f);
  double target = f * round.length, s = 0.0;
  for (size_t i = 0; i < n; ++i) {
    const Vec3& a = p[i];
    const Vec3& b = p[(i + 1) % n];
    const double len = (b - a).norm();
    if (s + len >= target && len > 0.0) return a + std::clamp((target - s) / len, 0.0, 1.0) * (b - a);
    s += len;
  }
  return p[0];
}

}  // namespace knitforge
