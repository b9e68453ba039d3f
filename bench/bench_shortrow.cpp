// Benchmarks of the short-row design route (docs/shortrow.md): the whole
// route without evaluation (field, wales, tessellation, post-processing,
// courses, map, knittability) and each stage on its own, on the issue's
// inputs: the built-in hemisphere (r 75 mm, stitch 3.2 x 2.2) and
// mannequin_front (cm, source x = 0, stitch 3 x 2 and 1.25 x 1.0); and a
// cap-like annulus of 23.5k vertices (the built-in cap at edge 2 mm: a face
// and a neck opening, stitch 3.5 x 2.8, source x = 0), whose seam is part of
// the route (stage 0, cut_to_disk.h). The mannequin needs ../shared/data
// (KNITFORGE_SHARED_DATA); without it those benchmarks are skipped with a
// message.

#include <filesystem>

#include <benchmark/benchmark.h>

#include "knitforge/design/shortrow/design_short_rows.h"
#include "knitforge/geometry/geodesic_distance.h"
#include "knitforge/geometry/shapes.h"
#include "knitforge/io/mesh_io.h"

using namespace knitforge;

namespace {

struct Input {
  TriMesh mesh;
  GeodesicSource source;
  bool ok = false;
};

const Input& hemisphere_input() {
  static const Input in = [] {
    Input i;
    i.mesh = hemisphere(75.0);
    i.source = source_from_plane(i.mesh, Vec3(1, 0, 0), 0.0);
    i.ok = true;
    return i;
  }();
  return in;
}

const Input& mannequin_input() {
  static const Input in = [] {
    Input i;
    const std::string path = std::string(KNITFORGE_SHARED_DATA) + "/mannequin_front.obj";
    if (!std::filesystem::exists(path)) return i;
    i.mesh = read_mesh(path);
    for (Vec3& v : i.mesh.vertices) v *= 10.0;  // cm -> mm
    i.source = source_from_plane(i.mesh, Vec3(1, 0, 0), 0.0);
    i.ok = true;
    return i;
  }();
  return in;
}

const Input& cap_input() {
  static const Input in = [] {
    Input i;
    i.mesh = cap(CapShape{}, 2.0);
    i.source = source_from_plane(i.mesh, Vec3(1, 0, 0), 0.0);
    i.ok = true;
    return i;
  }();
  return in;
}

void run_route(benchmark::State& state, const Input& in, KnitParams p, bool evaluate) {
  if (!in.ok) {
    state.SkipWithError("test data not found (KNITFORGE_SHARED_DATA)");
    return;
  }
  ShortRowOptions o;
  o.params = p;
  o.evaluate = evaluate;
  ShortRowDesign d;
  for (auto _ : state) {
    d = design_short_rows(in.mesh, in.source, o);
    benchmark::DoNotOptimize(d.map.cells.data());
  }
  state.counters["stitches"] = d.stitch_mesh.num_stitches();
  state.counters["knittable"] = d.map_check.ok() && d.mesh_check.ok();
  state.counters["vertices"] = in.mesh.num_vertices();
  state.counters["seams_s"] = d.seconds.seams;
  state.counters["field_s"] = d.seconds.field;
  state.counters["wales_s"] = d.seconds.wales;
  state.counters["tessellation_s"] = d.seconds.tessellation;
  state.counters["courses_s"] = d.seconds.courses + d.seconds.post_processing;
  state.counters["map_check_s"] = d.seconds.map + d.seconds.check;
  state.counters["evaluation_s"] = d.seconds.evaluation;
}

void BM_ShortRowHemisphere(benchmark::State& state) {
  run_route(state, hemisphere_input(), {3.2, 2.2}, state.range(0) != 0);
}
void BM_ShortRowMannequin3x2(benchmark::State& state) {
  run_route(state, mannequin_input(), {3.0, 2.0}, state.range(0) != 0);
}
void BM_ShortRowMannequin125x100(benchmark::State& state) {
  run_route(state, mannequin_input(), {1.25, 1.0}, state.range(0) != 0);
}

void BM_ShortRowCap(benchmark::State& state) { run_route(state, cap_input(), {3.5, 2.8}, state.range(0) != 0); }

}  // namespace

// Argument: 0 = design only, 1 = with the evaluation (relaxation, alignment).
BENCHMARK(BM_ShortRowHemisphere)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_ShortRowMannequin3x2)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_ShortRowMannequin125x100)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_ShortRowCap)->Arg(0)->Unit(benchmark::kMillisecond)->UseRealTime();

BENCHMARK_MAIN();
