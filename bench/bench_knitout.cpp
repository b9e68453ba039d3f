// Benchmark: knitting map -> knitout for a 300 x 300 map with about the most
// short-row ends the random generator fits in 300 rows (560; at most 594 fit
// as one stacked pair per turn, fewer with no four ends stacked in a wale;
// 1,000 do not fit) and 200 short columns.
// Goal (issue 4): < 0.5 s, verified (issue 12). Results are recorded in docs/benchmarks.md.
#include <benchmark/benchmark.h>

#include "knitforge/convert/random_knitting_map.h"
#include "knitforge/machine/knitout_writer.h"
#include "knitforge/machine/machine_profile.h"

namespace {

const knitforge::KnittingMap& big_map() {
  static const knitforge::KnittingMap map = [] {
    knitforge::RandomMapOptions o;
    o.seed = 3;
    o.rows = 300;
    o.cols = 300;
    o.short_row_ends = 560;
    o.short_columns = 200;
    return knitforge::random_knitting_map(o);
  }();
  return map;
}

// The writer alone (no verification), and the writer as users get it: the
// program verified on the virtual machine and compared with the map.
void BM_WriteKnitout300(benchmark::State& state) {
  const auto& map = big_map();
  const auto& prof = knitforge::machine_profile("shima-swg091n2");
  knitforge::KnitoutOptions o;
  o.verify = state.range(0) != 0;
  size_t bytes = 0;
  for (auto _ : state) {
    const auto prog = knitforge::write_knitout(map, prof, o);
    bytes = prog.text.size();
    benchmark::DoNotOptimize(bytes);
  }
  state.counters["bytes"] = static_cast<double>(bytes);
}
BENCHMARK(BM_WriteKnitout300)->Arg(0)->Arg(1)->ArgName("verify")->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
