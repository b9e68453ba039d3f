// Example 05: is the divergence metric resolution-robust? (seed Fig. 3.17)
//
// The built-in hemisphere (r 75 mm) is meshed at 7 edge lengths; for 10
// random feasible boundary vectors b (eq. 3.8) the harmonic field is solved
// on each mesh and its area-normalised divergence metric I(f) / area
// (eq. 3.6) printed. The optimiser only needs the *ranking* of b to survive
// a coarse proxy, so the last lines give, per resolution, the Spearman rank
// correlation with the finest mesh and the ratio of the metric to the
// finest mesh's (median over b).
//
//   build/examples/example_05_metric_resolution [seed]
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <random>
#include <vector>

#include "knitforge/design/shortcolumn/divergence_metric.h"
#include "knitforge/design/shortcolumn/feasible_set.h"
#include "knitforge/design/shortcolumn/harmonic_field.h"
#include "knitforge/geometry/shapes.h"

namespace {

std::vector<double> ranks(const std::vector<double>& v) {
  std::vector<size_t> idx(v.size());
  for (size_t i = 0; i < idx.size(); ++i) idx[i] = i;
  std::sort(idx.begin(), idx.end(), [&](size_t a, size_t b) { return v[a] < v[b]; });
  std::vector<double> r(v.size());
  for (size_t k = 0; k < idx.size(); ++k) r[idx[k]] = static_cast<double>(k);
  return r;
}

double spearman(const std::vector<double>& a, const std::vector<double>& b) {
  const std::vector<double> ra = ranks(a), rb = ranks(b);
  const double n = static_cast<double>(a.size());
  double d2 = 0.0;
  for (size_t i = 0; i < a.size(); ++i) d2 += (ra[i] - rb[i]) * (ra[i] - rb[i]);
  return 1.0 - 6.0 * d2 / (n * (n * n - 1.0));
}

}  // namespace

int main(int argc, char** argv) {
  using namespace knitforge;
  const unsigned seed = argc > 1 ? static_cast<unsigned>(std::atoi(argv[1])) : 17u;
  const std::vector<double> edges = {8.0, 6.0, 5.0, 4.0, 3.0, 2.5, 2.0};
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<BoundaryVector> bs;
  for (int k = 0; k < 10; ++k) bs.push_back(boundary_from_unit(Eigen::Vector4d(u(rng), u(rng), u(rng), u(rng))));

  std::vector<std::vector<double>> metric(edges.size());  // [resolution][b]
  std::printf("edge_mm faces   I/area (1/mm) for 10 random b\n");
  for (size_t r = 0; r < edges.size(); ++r) {
    const TriMesh mesh = hemisphere(75.0, edges[r]);
    HarmonicFieldSolver solver(mesh);
    const DivergenceOperator div(mesh);
    std::printf("%5.1f %7d ", edges[r], mesh.num_faces());
    for (const BoundaryVector& b : bs) {
      const DivergenceMetric m = div.evaluate(solver.solve(b).value);
      metric[r].push_back(m.normalised());
      std::printf(" %.5f", m.normalised());
    }
    std::printf("\n");
  }
  std::printf("edge_mm  spearman_vs_finest  median_ratio_to_finest\n");
  for (size_t r = 0; r < edges.size(); ++r) {
    std::vector<double> ratio;
    for (size_t k = 0; k < bs.size(); ++k) ratio.push_back(metric[r][k] / metric.back()[k]);
    std::sort(ratio.begin(), ratio.end());
    std::printf("%5.1f  %18.3f  %22.3f\n", edges[r], spearman(metric[r], metric.back()), 0.5 * (ratio[4] + ratio[5]));
  }
  return 0;
}
