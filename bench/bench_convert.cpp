// Benchmarks of the map <-> stitch mesh conversions (docs/convert.md).
//
// The map: 300 x 300, 560 short-row ends (2 x (300 - 3) = 594 is the bound
// of one stacked pair per turn, first and last rows full; with no four ends
// stacked in a wale the generator fits about 560) and 200 short columns,
// from random_knitting_map(seed 1).

#include <benchmark/benchmark.h>

#include "knitforge/convert/map_to_stitch_mesh.h"
#include "knitforge/convert/random_knitting_map.h"
#include "knitforge/convert/relax_stitch_mesh.h"
#include "knitforge/convert/stitch_mesh_to_map.h"

using namespace knitforge;

namespace {

const KnitParams kParams{};

RandomMapOptions big_map_options(int short_row_ends) {
  RandomMapOptions o;
  o.seed = 1;
  o.rows = 300;
  o.cols = 300;
  o.short_row_ends = short_row_ends;
  o.short_columns = 200;
  return o;
}

const KnittingMap& big_map(int short_row_ends) {
  static const KnittingMap a = random_knitting_map(big_map_options(560));
  static const KnittingMap b = random_knitting_map(big_map_options(200));
  return short_row_ends == 560 ? a : b;
}

void BM_RandomKnittingMap(benchmark::State& state) {
  for (auto _ : state) benchmark::DoNotOptimize(random_knitting_map(big_map_options(static_cast<int>(state.range(0)))));
}

void BM_MapToStitchMeshTopology(benchmark::State& state) {
  const KnittingMap& map = big_map(static_cast<int>(state.range(0)));
  for (auto _ : state) benchmark::DoNotOptimize(map_to_stitch_mesh_topology(map, kParams));
  state.counters["stitches"] = map.num_stitches();
}

void BM_RelaxStitchMesh(benchmark::State& state) {
  const StitchMesh mesh = map_to_stitch_mesh_topology(big_map(static_cast<int>(state.range(0))), kParams);
  RelaxResult r;
  for (auto _ : state) {
    r = relax_stitch_mesh(mesh, kParams, RelaxOptions{});
    benchmark::DoNotOptimize(r.mesh.vertices.data());
  }
  state.counters["stitches"] = mesh.num_stitches();
  state.counters["iterations"] = r.iterations;
  state.counters["energy_ratio"] = r.energy.back() / r.energy.front();
}

void BM_StitchMeshToMap(benchmark::State& state) {
  const StitchMesh mesh = map_to_stitch_mesh_topology(big_map(static_cast<int>(state.range(0))), kParams);
  for (auto _ : state) benchmark::DoNotOptimize(stitch_mesh_to_map(mesh));
  state.counters["stitches"] = mesh.num_stitches();
}

}  // namespace

BENCHMARK(BM_RandomKnittingMap)->Arg(560)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_MapToStitchMeshTopology)->Arg(560)->Arg(200)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_RelaxStitchMesh)->Arg(560)->Arg(200)->Unit(benchmark::kMillisecond)->Iterations(2);
BENCHMARK(BM_StitchMeshToMap)->Arg(560)->Arg(200)->Unit(benchmark::kMillisecond);

BENCHMARK_MAIN();
