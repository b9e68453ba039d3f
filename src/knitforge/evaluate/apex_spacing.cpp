#include "knitforge/evaluate/apex_spacing.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

#include <fmt/core.h>

#include "knitforge/util/errors.h"

namespace knitforge {

ApexSpacing apex_spacing(const StitchMesh& mesh) {
  ApexSpacing out;
  const int nv = mesh.num_vertices();
  for (int s = 0; s < mesh.num_stitches(); ++s) {
    const Stitch& st = mesh.stitches[s];
    const int k = apex_corner(st.type);
    if (k < 0) continue;
    const int v = st.v[k];
    if (v < 0 || v >= nv) {
      throw TopologyError(fmt::format("stitch {}: apex vertex {} out of range (valid: 0..{})", s, v, nv - 1));
    }
    if (!mesh.vertices[v].allFinite()) throw InvalidInput(fmt::format("apex vertex {} has a non-finite position", v));
    out.apexes.push_back(v);
  }
  std::sort(out.apexes.begin(), out.apexes.end());
  out.apexes.erase(std::unique(out.apexes.begin(), out.apexes.end()), out.apexes.end());
  const int n = static_cast<int>(out.apexes.size());
  if (n < 2) return out;

  // Nearest neighbours by a sweep along x: candidates are visited outward
  // from each apex in x order and the scan stops once |dx| exceeds the best
  // distance found.
  std::vector<int> order(n);
  std::iota(order.begin(), order.end(), 0);
  const auto pos = [&](int i) -> const Vec3& { return mesh.vertices[out.apexes[i]]; };
  std::sort(order.begin(), order.end(), [&](int a, int b) { return pos(a).x() < pos(b).x() || (pos(a).x() == pos(b).x() && a < b); });
  out.nearest.assign(n, std::numeric_limits<double>::infinity());
  for (int r = 0; r < n; ++r) {
    const int i = order[r];
    double best2 = std::numeric_limits<double>::infinity();
    for (int step : {-1, +1}) {
      for (int q = r + step; q >= 0 && q < n; q += step) {
        const double dx = pos(order[q]).x() - pos(i).x();
        if (dx * dx >= best2) break;
        best2 = std::min(best2, (pos(order[q]) - pos(i)).squaredNorm());
      }
    }
    out.nearest[i] = std::sqrt(best2);
  }
  out.stats = scalar_stats(out.nearest);
  return out;
}

}  // namespace knitforge
