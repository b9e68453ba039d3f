#include "knitforge/geometry/loop_tessellation.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <set>
#include <utility>

#include <fmt/core.h>

#include "knitforge/util/errors.h"

namespace knitforge {

namespace {

void check_loop(std::span<const Vec3> loop, const char* name) {
  if (loop.size() < 3) {
    throw InvalidInput(fmt::format("loop_tessellation: loop {} has {} points; a closed loop needs at least 3",
                                   name, loop.size()));
  }
  for (std::size_t i = 0; i < loop.size(); ++i) {
    if (!loop[i].allFinite()) {
      throw InvalidInput(fmt::format("loop_tessellation: point {} of loop {} is not finite", i, name));
    }
  }
}

double tri_area(const Vec3& p, const Vec3& q, const Vec3& r) { return 0.5 * (q - p).cross(r - p).norm(); }

/// Dynamic programme over the bridge grid for one start alignment.
class BandSolver {
 public:
  BandSolver(std::span<const Vec3> a, std::span<const Vec3> b, LoopTessellationCost cost)
      : a_(a), b_(b), m_(static_cast<int>(a.size())), n_(static_cast<int>(b.size())), cost_(cost) {
    dist_.resize(static_cast<std::size_t>(m_) * n_);
    for (int i = 0; i < m_; ++i)
      for (int j = 0; j < n_; ++j) dist_[static_cast<std::size_t>(i) * n_ + j] = (a_[i] - b_[j]).norm();
    table_.resize(static_cast<std::size_t>(m_ + 1) * (n_ + 1));
    from_a_.resize(table_.size());
  }

  double bridge(int i, int j) const { return dist_[static_cast<std::size_t>(i % m_) * n_ + (j % n_)]; }

  /// Cost of the step that advances on A from grid node (i, j) (offsets from the start).
  double step_a(int i, int j) const {
    if (cost_ == LoopTessellationCost::BridgeLength) return bridge(i + 1, j);
    return tri_area(a_[i % m_], a_[(i + 1) % m_], b_[j % n_]);
  }
  double step_b(int i, int j) const {
    if (cost_ == LoopTessellationCost::BridgeLength) return bridge(i, j + 1);
    return tri_area(a_[i % m_], b_[(j + 1) % n_], b_[j % n_]);
  }

  /// Minimal cost of the band starting at bridge (i0, j0); fills the tables.
  double solve(int i0, int j0) {
    const int w = n_ + 1;
    for (int i = 0; i <= m_; ++i) {
      for (int j = 0; j <= n_; ++j) {
        const std::size_t k = static_cast<std::size_t>(i) * w + j;
        if (i == 0 && j == 0) {
          table_[k] = 0.0;
          continue;
        }
        double best = std::numeric_limits<double>::infinity();
        bool via_a = false;
        if (i > 0) {
          best = table_[k - w] + step_a(i0 + i - 1, j0 + j);
          via_a = true;
        }
        if (j > 0) {
          const double c = table_[k - 1] + step_b(i0 + i, j0 + j - 1);
          if (c < best) {
            best = c;
            via_a = false;
          }
        }
        table_[k] = best;
        from_a_[k] = via_a ? 1 : 0;
      }
    }
    return table_.back();
  }

  /// Triangles of the last solve() (start (i0, j0)), in band order.
  std::vector<std::array<int, 3>> triangles(int i0, int j0) const {
    std::vector<std::array<int, 3>> out;
    out.reserve(static_cast<std::size_t>(m_ + n_));
    int i = m_, j = n_;
    const int w = n_ + 1;
    while (i > 0 || j > 0) {
      const std::size_t k = static_cast<std::size_t>(i) * w + j;
      if (from_a_[k]) {
        --i;
        out.push_back({(i0 + i) % m_, (i0 + i + 1) % m_, m_ + (j0 + j) % n_});
      } else {
        --j;
        out.push_back({(i0 + i) % m_, m_ + (j0 + j + 1) % n_, m_ + (j0 + j) % n_});
      }
    }
    std::reverse(out.begin(), out.end());
    return out;
  }

 private:
  std::span<const Vec3> a_, b_;
  int m_, n_;
  LoopTessellationCost cost_;
  std::vector<double> dist_;
  std::vector<double> table_;
  std::vector<char> from_a_;
};

}  // namespace

LoopTessellation loop_tessellation(std::span<const Vec3> a, std::span<const Vec3> b,
                                   const LoopTessellationOptions& options) {
  check_loop(a, "A");
  check_loop(b, "B");
  if (!(options.max_exhaustive_work >= 0.0)) {
    throw InvalidInput("loop_tessellation: max_exhaustive_work must be non-negative");
  }
  const int m = static_cast<int>(a.size()), n = static_cast<int>(b.size());
  BandSolver solver(a, b, options.cost);
  LoopTessellation result;
  const double s = std::min(m, n), l = std::max(m, n);
  result.exhaustive = s * s * l <= options.max_exhaustive_work;
  std::vector<std::pair<int, int>> starts;
  if (result.exhaustive) {
    // Vertex 0 of the longer loop lies on some bridge of every band.
    if (m >= n) {
      for (int j = 0; j < n; ++j) starts.emplace_back(0, j);
    } else {
      for (int i = 0; i < m; ++i) starts.emplace_back(i, 0);
    }
  } else {
    // Seed: cut both loops open at the shortest bridge.
    int bi = 0, bj = 0;
    for (int i = 0; i < m; ++i)
      for (int j = 0; j < n; ++j)
        if (solver.bridge(i, j) < solver.bridge(bi, bj)) bi = i, bj = j;
    starts.emplace_back(bi, bj);
  }
  double best = std::numeric_limits<double>::infinity();
  for (const auto& [i0, j0] : starts) {
    const double c = solver.solve(i0, j0);
    if (c < best) {
      best = c;
      result.start_a = i0;
      result.start_b = j0;
    }
  }
  solver.solve(result.start_a, result.start_b);
  result.triangles = solver.triangles(result.start_a, result.start_b);
  result.cost = best;
  return result;
}

double loop_tessellation_cost(std::span<const Vec3> a, std::span<const Vec3> b,
                              const std::vector<std::array<int, 3>>& triangles, LoopTessellationCost cost) {
  const int m = static_cast<int>(a.size()), n = static_cast<int>(b.size());
  auto point = [&](int v) -> const Vec3& {
    if (v < 0 || v >= m + n) {
      throw InvalidInput(fmt::format("loop_tessellation_cost: vertex index {} is outside [0, {})", v, m + n));
    }
    return v < m ? a[v] : b[v - m];
  };
  double total = 0.0;
  if (cost == LoopTessellationCost::TriangleArea) {
    for (const auto& t : triangles) total += tri_area(point(t[0]), point(t[1]), point(t[2]));
    return total;
  }
  std::set<std::pair<int, int>> bridges;
  for (const auto& t : triangles) {
    for (int k = 0; k < 3; ++k) {
      int u = t[k], v = t[(k + 1) % 3];
      point(u);
      point(v);
      if ((u < m) == (v < m)) continue;
      if (u > v) std::swap(u, v);
      if (bridges.emplace(u, v).second) total += (a[u] - b[v - m]).norm();
    }
  }
  return total;
}

}  // namespace knitforge
