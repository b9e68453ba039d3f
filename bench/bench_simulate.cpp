// Benchmarks of the knitout simulator (docs/machines.md, "The simulator").
//
// The program: write_knitout() of a 300 x 300 map with 560 short-row ends
// (about the most the random generator fits in 300 rows: see bench_knitout;
// 1,000 do not fit) and 200 short columns, random_knitting_map(seed 1), for
// the Shima-like profile. Goal: parse + simulate < 0.5 s.

#include <benchmark/benchmark.h>

#include "knitforge/convert/random_knitting_map.h"
#include "knitforge/convert/sample_knitting_map.h"
#include "knitforge/machine/knit_graph_compare.h"
#include "knitforge/machine/knit_graph_to_map.h"
#include "knitforge/machine/knitout_parse.h"
#include "knitforge/machine/knitout_simulate.h"
#include "knitforge/machine/knitout_writer.h"
#include "knitforge/machine/machine_profile.h"

using namespace knitforge;

namespace {

const KnittingMap& big_map() {
  static const KnittingMap map = [] {
    RandomMapOptions o;
    o.seed = 1;
    o.rows = 300;
    o.cols = 300;
    o.short_row_ends = 560;
    o.short_columns = 200;
    return random_knitting_map(o);
  }();
  return map;
}

const std::string& big_program() {
  static const std::string text = write_knitout(big_map(), machine_profile("shima-swg091n2")).text;
  return text;
}

void BM_ParseKnitout(benchmark::State& state) {
  for (auto _ : state) benchmark::DoNotOptimize(parse_knitout(big_program()));
}

void BM_ParseAndSimulateKnitout(benchmark::State& state) {
  const MachineProfile& p = machine_profile("shima-swg091n2");
  for (auto _ : state) {
    const KnitoutSimulation sim = simulate_knitout(parse_knitout(big_program()), p);
    if (!sim.ok()) state.SkipWithError("the benchmark program does not simulate cleanly");
    benchmark::DoNotOptimize(sim.stats.time_s);
  }
  state.counters["lines"] = static_cast<double>(parse_knitout(big_program()).num_lines);
}

void BM_CompareKnitGraph(benchmark::State& state) {
  const KnitoutSimulation sim =
      simulate_knitout(parse_knitout(big_program()), machine_profile("shima-swg091n2"));
  for (auto _ : state) benchmark::DoNotOptimize(compare_knit_graph(sim.graph, big_map()).mismatches);
}

// The program's fabric as a knitting map (the fabric view of simulate --report).
void BM_KnitGraphFabric(benchmark::State& state) {
  const KnitoutSimulation sim =
      simulate_knitout(parse_knitout(big_program()), machine_profile("shima-swg091n2"));
  for (auto _ : state) {
    const KnitGraphFabric f = knit_graph_fabric(sim);
    if (f.kind != "sheet") state.SkipWithError("the benchmark program's fabric is not a sheet");
    benchmark::DoNotOptimize(f.map.rows);
  }
}

// The same for a shaped tube: 200 stitches round narrowing to 40 in 40
// decrease rounds, 200 rounds, on the Kniterate (knit_graph_to_map.h, "Tubes").
void BM_KnitGraphFabricTube(benchmark::State& state) {
  TubeMapOptions o;
  o.round = 200;
  o.rows = 200;
  o.decrease_rounds = 40;
  o.every = 4;
  const KnitoutProgram p = write_knitout(tube_knitting_map(o), machine_profile("kniterate"));
  for (auto _ : state) {
    const KnitGraphFabric f = knit_graph_fabric(*p.simulation);
    if (f.kind != "tube" || !f.map.tubular()) state.SkipWithError("the benchmark tube is not read back as its map");
    benchmark::DoNotOptimize(f.map.rows);
  }
  state.counters["stitches"] = static_cast<double>(knit_graph_fabric(*p.simulation).stitch_loops.size());
}

}  // namespace

BENCHMARK(BM_KnitGraphFabric)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_KnitGraphFabricTube)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_ParseKnitout)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_ParseAndSimulateKnitout)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_CompareKnitGraph)->Unit(benchmark::kMillisecond);
BENCHMARK_MAIN();
