// Benchmarks of the fabric simulator (docs/sim.md): where a Newton
// iteration's time goes (energy + Hessian assembly, Cholesky factorisation
// with the symbolic analysis reused), a backward-Euler step of a sheet
// draped on a dome, and the free predicted shape of the built-in cup map.
//
// Sizes: square sheets of N x N stitches of 3.5 x 2.8 mm (N = 32, 64, 128:
// about 1k, 4k and 16k stitches).

#include <algorithm>

#include <benchmark/benchmark.h>

#include "knitforge/convert/map_to_stitch_mesh.h"
#include "knitforge/convert/relax_stitch_mesh.h"
#include "knitforge/convert/sample_knitting_map.h"
#include "knitforge/geometry/shapes.h"
#include "knitforge/sim/arm_motion.h"
#include "knitforge/sim/bending_energy.h"
#include "knitforge/sim/membrane_energy.h"
#include "knitforge/sim/predict_shape.h"
#include "knitforge/sim/simulate_cloth.h"
#include "knitforge/sim/step_simulation.h"

using namespace knitforge;

namespace {

const KnitParams kParams{};

StitchMesh sheet(int n) {
  StitchMesh m;
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) m.vertices.emplace_back(kParams.stitch_width * i, kParams.stitch_height * j, 0.0);
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < n; ++i) {
      Stitch s;
      s.type = StitchType::Knit;
      s.v = {j * (n + 1) + i, j * (n + 1) + i + 1, (j + 1) * (n + 1) + i + 1, (j + 1) * (n + 1) + i};
      s.course = j;
      s.wale = i;
      m.stitches.push_back(s);
    }
  }
  return m;
}

Eigen::VectorXd stretched(const SimModel& model) {
  Eigen::VectorXd x(3 * model.num_vertices());
  for (int v = 0; v < model.num_vertices(); ++v) {
    const Vec3 p = model.rest_positions[v];
    x.segment<3>(3 * v) = Vec3(1.1 * p.x(), p.y(), 0.5 * std::sin(0.1 * p.x()));
  }
  return x;
}

void BM_AssembleEnergyHessian(benchmark::State& state) {
  const SimModel model = build_sim_model(sheet(static_cast<int>(state.range(0))), kParams);
  const auto pattern = build_hessian_pattern(model);
  const Eigen::VectorXd x = stretched(model);
  for (auto _ : state) {
    EnergyEval ev(model.num_vertices(), Derivatives::Hessian, pattern);
    add_membrane_energy(model, x, PsdProjection::Clamp, ev);
    add_bending_energy(model, x, ev);
    benchmark::DoNotOptimize(ev.value);
  }
  state.counters["stitches"] = static_cast<double>(model.num_elements()) / 2;
}
BENCHMARK(BM_AssembleEnergyHessian)->Arg(32)->Arg(64)->Arg(128)->Unit(benchmark::kMillisecond);

void BM_FactorHessian(benchmark::State& state) {
  const SimModel model = build_sim_model(sheet(static_cast<int>(state.range(0))), kParams);
  const auto pattern = build_hessian_pattern(model);
  const Eigen::VectorXd x = stretched(model);
  EnergyEval ev(model.num_vertices(), Derivatives::Hessian, pattern);
  add_membrane_energy(model, x, PsdProjection::Clamp, ev);
  add_bending_energy(model, x, ev);
  // A mass term keeps it positive definite, as in a time step.
  for (int r = 0; r < 3 * model.num_vertices(); ++r) ev.hessian_values[pattern->diagonal_index(r)] += 1.0;
  const SparseMatrix H = pattern->matrix(ev.hessian_values);
  SparseSolver solver;
  solver.factor(H);  // the symbolic analysis, once
  for (auto _ : state) solver.refactor(H);
  state.counters["unknowns"] = 3.0 * model.num_vertices();
}
BENCHMARK(BM_FactorHessian)->Arg(32)->Arg(64)->Arg(128)->Unit(benchmark::kMillisecond);

// One 1/60 s step of a 40 x 40 sheet (1600 stitches) falling onto a dome of
// radius 50 mm, 20 steps in (in contact).
void BM_DrapeStep(benchmark::State& state) {
  const SimModel model = build_sim_model(sheet(40), kParams);
  SimWorkspace ws(model);
  const KinematicBody body(hemisphere(50.0, 4.0));
  StepOptions o;
  Eigen::VectorXd x(3 * model.num_vertices());
  for (int v = 0; v < model.num_vertices(); ++v)
    x.segment<3>(3 * v) = model.rest_positions[v] + Vec3(-70.0, -56.0, 50.4);
  SimState s{x, Eigen::VectorXd::Zero(x.size()), 0.0};
  for (int k = 0; k < 20; ++k) s = step_simulation(ws, s, body, {}, {}, o).state;
  int iterations = 0, steps = 0;
  for (auto _ : state) {
    const StepResult r = step_simulation(ws, s, body, {}, {}, o);
    iterations += r.newton_iterations;
    ++steps;
    benchmark::DoNotOptimize(r.energy);
  }
  state.counters["newton_per_step"] = static_cast<double>(iterations) / steps;
}
BENCHMARK(BM_DrapeStep)->Unit(benchmark::kMillisecond);

// Free predicted shape of the cup map (1288 stitches) from its Shape-Up shape
// (L-BFGS phase, then Newton: PredictOptions' default).
void BM_PredictCup(benchmark::State& state) {
  const StitchMesh start =
      relax_stitch_mesh(map_to_stitch_mesh_topology(sample_knitting_map("cup"), kParams), kParams, RelaxOptions{}).mesh;
  for (auto _ : state) {
    const PredictResult r = predict_shape(start, kParams, nullptr);
    state.counters["iterations"] = r.solve.iterations;  // Newton's
    state.counters["lbfgs_iterations"] = r.solve.quasi_newton_iterations;
    state.counters["factorizations"] = r.solve.factorizations;
    state.counters["converged"] = r.solve.converged;
    state.counters["max_force_mN"] = r.solve.max_force_mn;
  }
}
BENCHMARK(BM_PredictCup)->Unit(benchmark::kSecond)->Iterations(1);

// The built-in `cloth` scene (a capsule arm bending 0 -> 90 degrees over 30
// frames at 30 Hz, 2 substeps, inside a sleeve attached at shoulder and
// cuff): the first `frames` frames with the sleeve's edge length (mm) from
// the argument (x 0.1). 130 = the default (about 2.5k triangles); 42 gives
// about 20k triangles, the size. Counter: seconds per frame.
void BM_ClothSleeve(benchmark::State& state) {
  ArmMotionParams p;
  p.sleeve_edge_mm = 0.1 * static_cast<double>(state.range(0));
  const int frames = static_cast<int>(state.range(1)), motion_frames = 30;
  const SleeveMesh sleeve = arm_sleeve_mesh(p);
  SimModel model = build_sim_model(sleeve.mesh, sleeve.course_directions);
  const std::vector<int>& attached = sleeve.attached;
  model.pinned = attached;
  std::vector<std::vector<Vec3>> poses;
  for (int f = 0; f <= frames; ++f) poses.push_back(arm_body_mesh(p, arm_elbow_angle_deg(p, f, motion_frames)).vertices);
  ClothOptions o;
  o.frames = frames;
  for (auto _ : state) {
    const ClothResult r = simulate_cloth(model, arm_body_mesh(p, 0.0), poses, attached, o);
    state.counters["newton_per_frame"] = static_cast<double>(r.newton_iterations) / frames;
    state.counters["lbfgs_per_frame"] = static_cast<double>(r.quasi_newton_iterations) / frames;
    state.counters["factorizations_per_frame"] = static_cast<double>(r.factorizations) / frames;
    state.counters["converged"] = r.converged ? 1 : 0;
    state.counters["min_distance_mm"] = r.min_distance_mm;
    state.counters["factor_s_per_frame"] = r.seconds.factor / frames;
    state.counters["evaluate_s_per_frame"] = (r.seconds.evaluate + r.seconds.line_search) / frames;
    state.counters["ccd_s_per_frame"] = r.seconds.max_step / frames;
  }
  state.counters["triangles"] = model.num_elements();
  state.counters["vertices"] = model.num_vertices();
}
BENCHMARK(BM_ClothSleeve)->Args({130, 30})->Args({42, 3})->Unit(benchmark::kSecond)->Iterations(1);

// The same scene by the projective-dynamics preview (ClothSolver::Preview),
// the arm bending over the `frames` frames run: {42, 60} is the issue's
// 20k-triangle garment for 60 frames. Counters: seconds per frame, rounds
// per step, whether every step reached the preview's tolerance, and the
// closest approach to the body mesh.
void BM_ClothSleevePreview(benchmark::State& state) {
  ArmMotionParams p;
  p.sleeve_edge_mm = 0.1 * static_cast<double>(state.range(0));
  const int frames = static_cast<int>(state.range(1));
  const SleeveMesh sleeve = arm_sleeve_mesh(p);
  SimModel model = build_sim_model(sleeve.mesh, sleeve.course_directions);
  model.pinned = sleeve.attached;
  std::vector<std::vector<Vec3>> poses;
  for (int f = 0; f <= frames; ++f) poses.push_back(arm_body_mesh(p, arm_elbow_angle_deg(p, f, frames)).vertices);
  ClothOptions o;
  o.frames = frames;
  o.solver = ClothSolver::Preview;
  for (auto _ : state) {
    const ClothResult r = simulate_cloth(model, arm_body_mesh(p, 0.0), poses, sleeve.attached, o);
    state.counters["s_per_frame"] =
        (r.seconds.factor + r.seconds.evaluate + r.seconds.max_step + r.measure_seconds) / frames;
    state.counters["rounds_per_step"] = static_cast<double>(r.preview_iterations) / r.steps;
    state.counters["converged"] = r.converged ? 1 : 0;
    state.counters["min_distance_mm"] = r.min_distance_mm;
  }
  state.counters["triangles"] = model.num_elements();
}
BENCHMARK(BM_ClothSleevePreview)->Args({130, 30})->Args({42, 60})->Unit(benchmark::kSecond)->Iterations(1);

}  // namespace

BENCHMARK_MAIN();
