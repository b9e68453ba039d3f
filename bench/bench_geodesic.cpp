// Benchmark: the governing geodesic field of the short-row route (seed §3.2.1)
// on the test meshes of ../shared/data (cm, scaled to mm) with the symmetry
// plane x = 0 as source, and on the built-in triple-peak and hemisphere.
// Goal: a small part of the budget of the whole route (hemisphere 0.2 s,
// mannequin_front 0.5 s; docs/geometry.md).
#include <benchmark/benchmark.h>

#include <algorithm>
#include <ctime>
#include <string>

#include "knitforge/geometry/geodesic_distance.h"
#include "knitforge/geometry/geodesic_path.h"
#include "knitforge/geometry/geodesic_source.h"
#include "knitforge/geometry/shapes.h"
#include "knitforge/io/mesh_io.h"

using namespace knitforge;

namespace {

// ../shared/data next to the repository (this file is bench/bench_geodesic.cpp).
std::string shared_data() {
  std::string f = __FILE__;
  return f.substr(0, f.rfind('/')) + "/../../shared/data";
}

TriMesh load_mm(const std::string& name) {
  TriMesh m = read_mesh(shared_data() + "/" + name);
  for (Vec3& p : m.vertices) p *= 10.0;  // cm -> mm
  return m;
}

const TriMesh& mesh_for(int which) {
  static const TriMesh mannequin = load_mm("mannequin_front.obj");
  static const TriMesh peak_file = load_mm("triple_peak.obj");
  static const TriMesh peak_builtin = triple_peak(2.5);
  static const TriMesh hemi = hemisphere(75.0);
  return which == 0 ? mannequin : which == 1 ? peak_file : which == 2 ? peak_builtin : hemi;
}

const char* name_of(int which) {
  return which == 0   ? "mannequin_front"
         : which == 1 ? "triple_peak.obj"
         : which == 2 ? "triple-peak (built-in, 2.5 mm)"
                      : "hemisphere (built-in, r 75 mm, default edge)";
}

// The whole field: source extraction + precomputation + propagation.
void BM_GeodesicFieldPlaneX0(benchmark::State& state) {
  const TriMesh& m = mesh_for(static_cast<int>(state.range(0)));
  GeodesicField f;
  for (auto _ : state) {
    const GeodesicSource src = source_from_plane(m, Vec3(1, 0, 0), 0.0);
    f = geodesic_distance(m, src);
    benchmark::DoNotOptimize(f.distance.data());
  }
  state.SetLabel(name_of(static_cast<int>(state.range(0))));
  state.counters["faces"] = m.num_faces();
  state.counters["windows"] = static_cast<double>(f.num_windows);
  state.counters["max_mm"] = f.max_abs_distance;
}
BENCHMARK(BM_GeodesicFieldPlaneX0)->Arg(0)->Arg(1)->Arg(2)->Arg(3)->Unit(benchmark::kMillisecond);

// The approximate field (GeodesicOptions::tolerance, mm) for short-row use.
void BM_GeodesicFieldPlaneX0Approx(benchmark::State& state) {
  const TriMesh& m = mesh_for(static_cast<int>(state.range(0)));
  GeodesicOptions opt;
  opt.tolerance = static_cast<double>(state.range(1)) * 1e-4;
  GeodesicField f;
  for (auto _ : state) {
    const GeodesicSource src = source_from_plane(m, Vec3(1, 0, 0), 0.0);
    f = geodesic_distance(m, src, opt);
    benchmark::DoNotOptimize(f.distance.data());
  }
  state.SetLabel(name_of(static_cast<int>(state.range(0))));
  state.counters["tol_mm"] = opt.tolerance;
  state.counters["windows"] = static_cast<double>(f.num_windows);
}
BENCHMARK(BM_GeodesicFieldPlaneX0Approx)
    ->Args({0, 10})
    ->Args({1, 10})
    ->Args({3, 10})
    ->Args({3, 30})
    ->Unit(benchmark::kMillisecond);

// Wall time (->UseRealTime(): the CPU time of the process does not show the
// gain of running the two sides concurrently) of the whole field: args mesh,
// tolerance in 1e-4 mm, split_sides (0: the single propagation, 1: the two
// side propagations in two threads).
void BM_GeodesicFieldPlaneX0Wall(benchmark::State& state) {
  const TriMesh& m = mesh_for(static_cast<int>(state.range(0)));
  GeodesicOptions opt;
  opt.tolerance = static_cast<double>(state.range(1)) * 1e-4;
  opt.split_sides = state.range(2) != 0;
  GeodesicField f;
  const std::clock_t c0 = std::clock();  // CPU time of the process (all threads)
  for (auto _ : state) {
    const GeodesicSource src = source_from_plane(m, Vec3(1, 0, 0), 0.0);
    f = geodesic_distance(m, src, opt);
    benchmark::DoNotOptimize(f.distance.data());
  }
  const double cpu_s = static_cast<double>(std::clock() - c0) / CLOCKS_PER_SEC;
  state.SetLabel(name_of(static_cast<int>(state.range(0))));
  state.counters["tol_mm"] = opt.tolerance;
  state.counters["split"] = f.split_sides ? 1 : 0;
  // (The "CPU" column is the main thread's only.)
  state.counters["proc_cpu_ms"] = 1e3 * cpu_s / static_cast<double>(std::max<benchmark::IterationCount>(state.iterations(), 1));
  state.counters["windows"] = static_cast<double>(f.num_windows);
}
BENCHMARK(BM_GeodesicFieldPlaneX0Wall)
    ->ArgsProduct({{0, 1, 3}, {0, 10, 30}, {0, 1}})
    ->UseRealTime()
    ->Unit(benchmark::kMillisecond);

// The stages separately on mannequin_front: source, precomputation, propagation.
void BM_GeodesicSourcePlane(benchmark::State& state) {
  const TriMesh& m = mesh_for(static_cast<int>(state.range(0)));
  for (auto _ : state) {
    const GeodesicSource src = source_from_plane(m, Vec3(1, 0, 0), 0.0);
    benchmark::DoNotOptimize(src.polylines.data());
  }
  state.SetLabel(name_of(static_cast<int>(state.range(0))));
}
BENCHMARK(BM_GeodesicSourcePlane)->Arg(0)->Unit(benchmark::kMillisecond);

void BM_GeodesicSolverSetup(benchmark::State& state) {
  const TriMesh& m = mesh_for(static_cast<int>(state.range(0)));
  for (auto _ : state) {
    GeodesicSolver solver(m);
    benchmark::DoNotOptimize(&solver);
  }
  state.SetLabel(name_of(static_cast<int>(state.range(0))));
}
BENCHMARK(BM_GeodesicSolverSetup)->Arg(0)->Unit(benchmark::kMillisecond);

void BM_GeodesicPropagation(benchmark::State& state) {
  const TriMesh& m = mesh_for(static_cast<int>(state.range(0)));
  const GeodesicSource src = source_from_plane(m, Vec3(1, 0, 0), 0.0);
  const GeodesicSolver solver(m);
  for (auto _ : state) {
    const GeodesicField f = solver.distance(src);
    benchmark::DoNotOptimize(f.distance.data());
  }
  state.SetLabel(name_of(static_cast<int>(state.range(0))));
}
BENCHMARK(BM_GeodesicPropagation)->Arg(0)->Arg(1)->Arg(3)->Unit(benchmark::kMillisecond);

// A vertex source (the classic single-source exact problem) for comparison.
void BM_GeodesicVertexSource(benchmark::State& state) {
  const TriMesh& m = mesh_for(static_cast<int>(state.range(0)));
  const GeodesicSolver solver(m);
  const GeodesicSource src = source_from_vertex(m, 0);
  GeodesicField f;
  for (auto _ : state) {
    f = solver.distance(src);
    benchmark::DoNotOptimize(f.distance.data());
  }
  state.SetLabel(name_of(static_cast<int>(state.range(0))));
  state.counters["windows"] = static_cast<double>(f.num_windows);
}
BENCHMARK(BM_GeodesicVertexSource)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond);

// The cut of a closed wale: shortest path from an interior point to the boundary.
void BM_GeodesicPathToBoundary(benchmark::State& state) {
  const TriMesh& m = mesh_for(static_cast<int>(state.range(0)));
  const GeodesicSource src = source_from_plane(m, Vec3(1, 0, 0), 0.0);
  const SurfacePoint start = src.polylines.front()[src.polylines.front().size() / 2];
  GeodesicPath path;
  for (auto _ : state) {
    path = geodesic_path_to_boundary(m, start);
    benchmark::DoNotOptimize(path.points.data());
  }
  state.SetLabel(name_of(static_cast<int>(state.range(0))));
  state.counters["length_mm"] = path.length;
  state.counters["points"] = static_cast<double>(path.points.size());
}
BENCHMARK(BM_GeodesicPathToBoundary)->Arg(0)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
