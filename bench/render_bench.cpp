// Benchmark: yarn model -> tubes -> .glb for a ~100k-stitch map
// (330 x 330 random map with a few short rows and short columns; goal:
// < 2 s for tubes + file, docs/render.md), by the direct path
// write_yarn_glb() at the preview and the default tube detail, and by the
// general path (yarn_tubes() RenderMeshes, then write_glb()); the tubes
// alone, and the raster preview of the 100k preview tubes.
#include <benchmark/benchmark.h>

#include <filesystem>

#include <unistd.h>

#include "knitforge/convert/map_to_stitch_mesh.h"
#include "knitforge/convert/random_knitting_map.h"
#include "knitforge/convert/stitch_mesh_to_yarn.h"
#include "knitforge/io/gltf.h"
#include "knitforge/render/raster_preview.h"
#include "knitforge/render/yarn_tubes.h"

using namespace knitforge;

namespace {

YarnModel make_yarn(int rows, int cols, int* stitches) {
  RandomMapOptions o;
  o.rows = rows;
  o.cols = cols;
  o.short_row_ends = 40;
  o.short_columns = 10;
  o.seed = 7;
  const KnittingMap map = random_knitting_map(o);
  const KnitParams params;
  const StitchMesh mesh = map_to_stitch_mesh_topology(map, params);
  *stitches = mesh.num_stitches();
  return stitch_mesh_to_yarn(mesh, params);
}

const YarnModel& yarn_100k(int* stitches) {
  static int n = 0;
  static const YarnModel yarn = make_yarn(330, 330, &n);
  *stitches = n;
  return yarn;
}

const YarnModel& yarn_10k(int* stitches) {
  static int n = 0;
  static const YarnModel yarn = make_yarn(100, 100, &n);
  *stitches = n;
  return yarn;
}

TubeOptions preview_detail() {
  TubeOptions t;
  t.vertices_per_ply = 1;  // the plain twisted hexagonal prism of the seed
  t.ring_spacing = 1.0;
  t.capped = false;
  return t;
}

std::string temp_glb() {
  return (std::filesystem::temp_directory_path() /
          ("knitforge_render_bench_" + std::to_string(::getpid()) + ".glb"))
      .string();
}

// The general path: RenderMeshes, then write_glb.
void run_meshes_glb(benchmark::State& state, const YarnModel& yarn, int stitches, const TubeOptions& tube) {
  const std::string path = temp_glb();
  size_t vertices = 0;
  for (auto _ : state) {
    const std::vector<RenderMesh> tubes = yarn_tubes(yarn, KnitParams{}, tube);
    write_glb(path, tubes);
    vertices = 0;
    for (const auto& m : tubes) vertices += m.mesh.vertices.size();
  }
  state.counters["stitches"] = stitches;
  state.counters["vertices"] = static_cast<double>(vertices);
  state.counters["glb_MB"] = static_cast<double>(std::filesystem::file_size(path)) / 1e6;
  std::filesystem::remove(path);
}

// The direct path: write_yarn_glb.
void run_direct_glb(benchmark::State& state, const YarnModel& yarn, int stitches, const TubeOptions& tube) {
  const std::string path = temp_glb();
  for (auto _ : state) write_yarn_glb(path, yarn, KnitParams{}, tube);
  state.counters["stitches"] = stitches;
  state.counters["yarns"] = static_cast<double>(yarn.yarns.size());
  state.counters["glb_MB"] = static_cast<double>(std::filesystem::file_size(path)) / 1e6;
  std::filesystem::remove(path);
}

void BM_YarnToGlb100kPreview(benchmark::State& state) {
  int n = 0;
  const YarnModel& yarn = yarn_100k(&n);
  run_direct_glb(state, yarn, n, preview_detail());
}
// The default detail (12 vertices per ring every 0.42 mm, capped): about
// 460 vertices per stitch, a 1.7 GB file for 100k stitches.
void BM_YarnToGlb100kDefault(benchmark::State& state) {
  int n = 0;
  const YarnModel& yarn = yarn_100k(&n);
  run_direct_glb(state, yarn, n, TubeOptions{});
}
void BM_YarnToGlb10kDefault(benchmark::State& state) {
  int n = 0;
  const YarnModel& yarn = yarn_10k(&n);
  run_direct_glb(state, yarn, n, TubeOptions{});
}
void BM_MeshesToGlb100kPreview(benchmark::State& state) {
  int n = 0;
  const YarnModel& yarn = yarn_100k(&n);
  run_meshes_glb(state, yarn, n, preview_detail());
}
void BM_MeshesToGlb10kDefault(benchmark::State& state) {
  int n = 0;
  const YarnModel& yarn = yarn_10k(&n);
  run_meshes_glb(state, yarn, n, TubeOptions{});
}

void BM_YarnTubes100kPreviewOnly(benchmark::State& state) {
  int stitches = 0;
  const YarnModel& yarn = yarn_100k(&stitches);
  for (auto _ : state) benchmark::DoNotOptimize(yarn_tubes(yarn, KnitParams{}, preview_detail()));
  state.counters["stitches"] = stitches;
}

void BM_RasterPreview100k(benchmark::State& state) {
  int stitches = 0;
  const YarnModel& yarn = yarn_100k(&stitches);
  const std::vector<RenderMesh> tubes = yarn_tubes(yarn, KnitParams{}, preview_detail());
  std::vector<Vec3> pts;
  for (const auto& y : yarn.yarns) pts.insert(pts.end(), y.points.begin(), y.points.end());
  const Camera cam = frame_points(pts, 4.0 / 3.0);
  RasterOptions ro;
  ro.width = 1600;
  ro.height = 1200;
  for (auto _ : state) benchmark::DoNotOptimize(rasterize(tubes, cam, ro));
  state.counters["stitches"] = stitches;
}

}  // namespace

BENCHMARK(BM_YarnToGlb100kPreview)->Unit(benchmark::kMillisecond)->Iterations(3);
BENCHMARK(BM_YarnToGlb10kDefault)->Unit(benchmark::kMillisecond)->Iterations(3);
BENCHMARK(BM_YarnToGlb100kDefault)->Unit(benchmark::kMillisecond)->Iterations(1);
BENCHMARK(BM_MeshesToGlb100kPreview)->Unit(benchmark::kMillisecond)->Iterations(2);
BENCHMARK(BM_MeshesToGlb10kDefault)->Unit(benchmark::kMillisecond)->Iterations(2);
BENCHMARK(BM_YarnTubes100kPreviewOnly)->Unit(benchmark::kMillisecond)->Iterations(2);
BENCHMARK(BM_RasterPreview100k)->Unit(benchmark::kMillisecond)->Iterations(2);

BENCHMARK_MAIN();
