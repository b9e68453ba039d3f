// Benchmark: stitch mesh -> yarn model on the 300 x 300 foundation map
// (594 short-row ends — the most 300 rows hold — and 200 short columns).
// Goal: < 0.5 s (docs/benchmarks.md).
#include <benchmark/benchmark.h>

#include "knitforge/convert/map_to_stitch_mesh.h"
#include "knitforge/convert/random_knitting_map.h"
#include "knitforge/convert/stitch_mesh_to_yarn.h"

using namespace knitforge;

static void BM_StitchMeshToYarn300(benchmark::State& state) {
  RandomMapOptions o;
  o.rows = 300;
  o.cols = 300;
  o.short_row_ends = 594;  // the most 300 rows hold (see docs/benchmarks.md)
  o.short_columns = 200;
  o.seed = 7;
  const KnittingMap map = random_knitting_map(o);
  const KnitParams params;
  const StitchMesh mesh = map_to_stitch_mesh_topology(map, params);
  size_t points = 0;
  for (auto _ : state) {
    const YarnModel yarn = stitch_mesh_to_yarn(mesh, params);
    points = yarn.yarns.front().points.size();
    benchmark::DoNotOptimize(points);
  }
  state.counters["stitches"] = mesh.num_stitches();
  state.counters["yarn_points"] = static_cast<double>(points);
}
BENCHMARK(BM_StitchMeshToYarn300)->Unit(benchmark::kMillisecond);

BENCHMARK_MAIN();
