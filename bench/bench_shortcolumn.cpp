// Benchmarks of the short-column route (docs/shortcolumn.md, issue 14's
// speed goals): one field + metric evaluation on the optimisation proxy
// (goal < 50 ms) and on the surface itself; the optimisation (budget 100) and
// the design (without evaluation) of the built-in hemisphere; optimisation +
// design of a 25k-triangle hemisphere (goal < 10 s).

#include <benchmark/benchmark.h>

#include "knitforge/design/shortcolumn/design_short_columns.h"
#include "knitforge/design/shortcolumn/divergence_metric.h"
#include "knitforge/design/shortcolumn/harmonic_field.h"
#include "knitforge/design/shortcolumn/optimise_boundary.h"
#include "knitforge/geometry/shapes.h"

using namespace knitforge;

namespace {

const BoundaryVector kB{0.84, 0.84, 1.34, 1.34};  // near the optimum on the hemisphere

const TriMesh& surface(int edge_tenths) {
  static TriMesh fine = hemisphere(75.0, 1.8), normal = hemisphere(75.0);
  return edge_tenths == 18 ? fine : normal;
}

/// One objective evaluation: numeric factorisation, solve, metric.
void BM_FieldAndMetric(benchmark::State& state) {
  const TriMesh mesh = state.range(0) > 0 ? optimisation_proxy(surface(25), static_cast<int>(state.range(0))) : surface(25);
  HarmonicFieldSolver solver(mesh);
  const DivergenceOperator div(mesh);
  double m = 0.0;
  for (auto _ : state) {
    const HarmonicField h = solver.solve(kB);
    m = div.total(h.value);
    benchmark::DoNotOptimize(m);
  }
  state.counters["faces"] = mesh.num_faces();
  state.counters["metric_mm"] = m;
}

void BM_OptimiseHemisphere(benchmark::State& state) {
  BoundaryOptimisationOptions o;
  o.turbo.max_evaluations = 100;
  BoundaryOptimisation r;
  for (auto _ : state) {
    r = optimise_boundary(surface(25), o);
    benchmark::DoNotOptimize(r.best);
  }
  state.counters["best_estimate"] = r.best_value;
  state.counters["proxy_s"] = r.seconds_proxy;
  state.counters["evaluations_s"] = r.seconds_evaluations;
}

void run_design(benchmark::State& state, const TriMesh& mesh, bool optimise) {
  ShortColumnOptions so;
  so.params = KnitParams{3.5, 2.8};
  so.evaluate = false;
  ShortColumnDesign d;
  double optimise_s = 0.0;
  for (auto _ : state) {
    BoundaryVector b = kB;
    if (optimise) {
      BoundaryOptimisationOptions o;
      o.turbo.max_evaluations = 100;
      const BoundaryOptimisation r = optimise_boundary(mesh, o);
      b = r.best;
      optimise_s = r.seconds;
    }
    d = design_short_columns(mesh, harmonic_field(mesh, b).value, so);
    benchmark::DoNotOptimize(d.map.cells.data());
  }
  state.counters["faces"] = mesh.num_faces();
  state.counters["stitches"] = d.counts.stitches;
  state.counters["transfers"] = d.counts.transfers();
  state.counters["knittable"] = d.knittable();
  state.counters["optimise_s"] = optimise_s;
  state.counters["wales_s"] = d.seconds.wales;
  state.counters["tessellation_s"] = d.seconds.tessellation;
  state.counters["rest_s"] = d.seconds.total - d.seconds.wales - d.seconds.tessellation;
}

void BM_DesignHemisphere(benchmark::State& state) { run_design(state, surface(25), false); }
void BM_OptimiseAndDesignHemisphere25k(benchmark::State& state) { run_design(state, surface(18), true); }

}  // namespace

// Argument: proxy faces (0 = the surface itself, 8.6k faces).
BENCHMARK(BM_FieldAndMetric)->Arg(3000)->Arg(0)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_OptimiseHemisphere)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(3);
BENCHMARK(BM_DesignHemisphere)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(3);
BENCHMARK(BM_OptimiseAndDesignHemisphere25k)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(1);

BENCHMARK_MAIN();
