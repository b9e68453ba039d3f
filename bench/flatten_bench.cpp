// Benchmarks of the flattening route (docs/flatten.md, seed ch. 2) on
// mannequin_front (cm -> mm, 26.6k faces) and the built-in hemisphere:
//  - BM_FlattenAnalysis: Tutte + ARAP + distortion (goal < 1 s on mannequin);
//  - BM_FlattenToMap: that plus rasterisation and the knittability check
//    (goal < 2 s);
//  - BM_FlattenToMapEvaluated: plus lifting the stitch mesh onto the target
//    and evaluating it (relaxation, alignment, shape error);
//  - BM_FlattenWithDarts: the hemisphere with 4 one-end darts (cutting
//    includes the exact geodesic paths).
// The mannequin needs ../shared/data (KNITFORGE_SHARED_DATA); without it
// those benchmarks report an error and are skipped.

#include <cmath>
#include <filesystem>

#include <benchmark/benchmark.h>

#include "knitforge/design/flatten/flatten_surface.h"
#include "knitforge/design/flatten/knit_flattened_pattern.h"
#include "knitforge/geometry/shapes.h"
#include "knitforge/io/mesh_io.h"

using namespace knitforge;

namespace {

struct Input {
  TriMesh mesh;
  bool ok = false;
};

const Input& mannequin() {
  static const Input in = [] {
    Input i;
    const std::string path = std::string(KNITFORGE_SHARED_DATA) + "/mannequin_front.obj";
    if (!std::filesystem::exists(path)) return i;
    i.mesh = read_mesh(path);
    for (auto& v : i.mesh.vertices) v *= 10.0;  // cm -> mm
    i.ok = true;
    return i;
  }();
  return in;
}

void BM_FlattenAnalysis(benchmark::State& state) {
  const Input& in = mannequin();
  if (!in.ok) {
    state.SkipWithError("test data not found (KNITFORGE_SHARED_DATA)");
    return;
  }
  Flattening f;
  for (auto _ : state) {
    f = flatten_surface(in.mesh);
    benchmark::DoNotOptimize(f.uv.data());
  }
  state.counters["faces"] = in.mesh.num_faces();
  state.counters["iterations"] = f.iterations;
  state.counters["rms_log_sigma"] = f.stats.rms_log_sigma;
  state.counters["flipped"] = static_cast<double>(f.flipped_faces.size());
}

void BM_FlattenToMap(benchmark::State& state) {
  const Input& in = mannequin();
  if (!in.ok) {
    state.SkipWithError("test data not found (KNITFORGE_SHARED_DATA)");
    return;
  }
  const bool evaluate = state.range(0) != 0;
  KnitPatternOptions o;
  o.evaluate = evaluate;
  KnitPatternResult k;
  for (auto _ : state) {
    const Flattening f = flatten_surface(in.mesh);
    k = knit_flattened_pattern(f, in.mesh, KnitParams{3.0, 2.0}, o);
    benchmark::DoNotOptimize(k.raster.map.cells.data());
  }
  state.counters["stitches"] = k.raster.map.num_stitches();
  state.counters["knittable"] = k.knittability.ok();
  state.counters["rasterize_s"] = k.seconds.rasterize;
  state.counters["check_s"] = k.seconds.check;
  state.counters["lift_s"] = k.seconds.lift;
  state.counters["evaluate_s"] = k.seconds.evaluate;
  if (k.evaluation) state.counters["shape_rms_mm"] = k.evaluation->rms_error;
}

void BM_FlattenWithDarts(benchmark::State& state) {
  const TriMesh m = hemisphere(75.0, 4.0);
  std::vector<DartSpec> darts;
  const double r = 40.0, z = std::sqrt(75.0 * 75.0 - r * r);
  const Vec3 tips[4] = {Vec3(r, 0, z), Vec3(-r, 0, z), Vec3(0, r, z), Vec3(0, -r, z)};
  for (int i = 0; i < 4; ++i) {
    DartSpec d;
    d.orientation = i < 2 ? DartOrientation::Horizontal : DartOrientation::Vertical;
    d.points = {DartWaypoint::at_position(tips[i])};
    d.to_boundary = true;
    darts.push_back(d);
  }
  Flattening f;
  for (auto _ : state) {
    f = flatten_surface(m, darts);
    benchmark::DoNotOptimize(f.uv.data());
  }
  state.counters["faces"] = m.num_faces();
  state.counters["cut_s"] = f.seconds_cut;
  state.counters["flatten_s"] = f.seconds_flatten;
  state.counters["rms_log_sigma"] = f.stats.rms_log_sigma;
}

}  // namespace

BENCHMARK(BM_FlattenAnalysis)->Unit(benchmark::kMillisecond);
// Argument: 0 = map and check only, 1 = with the evaluation.
BENCHMARK(BM_FlattenToMap)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_FlattenWithDarts)->Unit(benchmark::kMillisecond);

BENCHMARK_MAIN();
