// The flattening never folds (issue: a bumpy disk with --auto-darts 3 gave
// 13 flipped triangles and max log sigma 3.6, reported as a success).
#include <cmath>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "saddle_dart.h"

#include "knitforge/design/flatten/dart_hints.h"
#include "knitforge/design/flatten/flatten_surface.h"
#include "knitforge/geometry/arap_flatten.h"
#include "knitforge/geometry/shapes.h"
#include "knitforge/geometry/surface_checks.h"

namespace knitforge {
namespace {

// A disk of radius 80 mm with two bumps and a dip (Gaussians of height
// `amplitude` and width `sigma`, mm).
TriMesh bumpy_disk(double amplitude, double sigma, double edge = 4.0) {
  TriMesh m = flat_disk(80.0, edge);
  auto g = [&](const Vec3& p, double cx, double cy, double a) {
    return a * std::exp(-((p.x() - cx) * (p.x() - cx) + (p.y() - cy) * (p.y() - cy)) / (2 * sigma * sigma));
  };
  for (Vec3& p : m.vertices)
    p.z() = g(p, -35, 15, amplitude) + g(p, 30, 25, amplitude) + g(p, 5, -35, -amplitude);
  return m;
}

void expect_no_fold(const Flattening& f) {
  EXPECT_TRUE(f.flipped_faces.empty());
  EXPECT_EQ(f.stats.flipped_faces, 0);
  for (int i = 0; i < f.mesh.num_faces(); ++i)
    ASSERT_GT(signed_uv_area(f.mesh, f.uv, i), 0.0) << "face " << i;
}

FlattenOptions three_by_two() {
  FlattenOptions opt;
  opt.stitch_width = 3.0;
  opt.stitch_height = 2.0;
  opt.enforce_dart_angle = false;
  return opt;
}

TEST(FlattenInjective, BumpyDiskWhereArapFoldsIsFlattenedWithoutFolds) {
  const TriMesh m = bumpy_disk(30.0, 12.0);
  const Flattening f = flatten_surface(m, {}, three_by_two());
  EXPECT_GT(f.arap_flipped_faces, 0);  // ARAP alone folds here ...
  EXPECT_TRUE(f.injective_solver);     // ... so the fold-free solver made the pattern
  expect_no_fold(f);
  EXPECT_LT(f.stats.max_abs_log_sigma(), 1.0);
}

TEST(FlattenInjective, AbandoningAFoldedArapRunGivesTheSamePattern) {
  // Without darts a folded ARAP result is replaced by the fold-free solver's
  // from Tutte's start, so stopping ARAP once it stays folded changes only
  // the ARAP iterations spent, not the pattern.
  const TriMesh m = bumpy_disk(30.0, 12.0);
  FlattenOptions full = three_by_two();
  full.abandon_folded_arap_after = 0;
  const Flattening a = flatten_surface(m, {}, full);
  const Flattening b = flatten_surface(m, {}, three_by_two());
  EXPECT_GT(a.arap_flipped_faces, 5);
  EXPECT_GT(b.arap_flipped_faces, 0);
  ASSERT_TRUE(a.injective_solver);
  ASSERT_TRUE(b.injective_solver);
  EXPECT_LT(b.iterations, a.iterations);
  ASSERT_EQ(a.uv.size(), b.uv.size());
  for (size_t v = 0; v < a.uv.size(); ++v) ASSERT_EQ(a.uv[v], b.uv[v]) << "vertex " << v;
}

TEST(FlattenInjective, ProgressNamesTheSolverAndItsIteration) {
  // Progress for a long run: ARAP every 20 iterations, then the fold-free
  // solver's start and every 5th of its iterations; the same pattern as
  // without a listener.
  const TriMesh m = bumpy_disk(30.0, 12.0);
  std::vector<std::string> told;
  FlattenOptions opt = three_by_two();
  opt.progress = [&](const std::string& s) { told.push_back(s); };
  const Flattening f = flatten_surface(m, {}, opt);
  const Flattening quiet = flatten_surface(m, {}, three_by_two());
  EXPECT_EQ(f.uv, quiet.uv);
  ASSERT_TRUE(f.injective_solver);
  int arap = 0, start = -1;
  for (size_t i = 0; i < told.size(); ++i) {
    if (told[i].rfind("ARAP, iteration ", 0) == 0) {
      ++arap;
      EXPECT_EQ(start, -1) << told[i];
    }
    if (told[i] == "ARAP folded the pattern: the fold-free solver starts") start = static_cast<int>(i);
    if (told[i].rfind("fold-free solver, iteration ", 0) == 0) {
      EXPECT_GE(start, 0) << told[i];
    }
  }
  EXPECT_GE(start, 0);
  EXPECT_EQ(told.front(), "ARAP, iteration 20 of at most 300");
  EXPECT_GT(arap, 0);
}

TEST(FlattenInjective, DartWhereArapFoldsKeepsItsAlignmentWithoutFolds) {
  const TriMesh m = bumpy_disk(30.0, 14.0);
  const Flattening plain = flatten_surface(m, {}, three_by_two());
  EXPECT_EQ(plain.arap_flipped_faces, 0);
  const auto hint = propose_dart(plain);
  ASSERT_TRUE(hint.has_value());
  const Flattening f = flatten_surface(m, {hint->spec}, three_by_two());
  EXPECT_GT(f.arap_flipped_faces, 0);  // ARAP folds at the new dart's tip
  EXPECT_TRUE(f.injective_solver);
  expect_no_fold(f);
  ASSERT_EQ(f.darts.size(), 1u);
  EXPECT_LE(f.darts[0].alignment_error, 1e-6 * 160.0);
  const Vec2 gap = f.uv[f.darts[0].notch_a] - f.uv[f.darts[0].notch_b];
  EXPECT_GT(gap.norm(), 1.0);  // the dart opened
}

TEST(FlattenInjective, AutomaticDartsLowerTheMaximumAndNeverFold) {
  const TriMesh m = bumpy_disk(30.0, 14.0);
  const AutoDarts a = add_darts_automatically(m, {}, 3, three_by_two());
  expect_no_fold(a.flattening);
  EXPECT_GE(a.added.size(), 1u);
  ASSERT_EQ(a.max_sequence.size(), a.rms_sequence.size());
  for (size_t k = 1; k < a.max_sequence.size(); ++k) {
    EXPECT_LT(a.max_sequence[k], a.max_sequence[k - 1]);
    EXPECT_LT(a.rms_sequence[k], a.rms_sequence[k - 1]);
  }
  EXPECT_DOUBLE_EQ(a.max_sequence.back(), a.flattening.stitch_max_abs_log_sigma);
  // Before: max log sigma 3.6 to 4.9 with folds; a fold-free pattern of this
  // disk stays well below.
  EXPECT_LT(a.flattening.stats.max_abs_log_sigma(), 1.5);
}

TEST(FlattenInjective, ClosedDartsMeshWeldsTheCopiesOfCutVertices) {
  const TriMesh m = monkey_saddle(6.0);
  const DartSpec d = saddle_two_end_dart();
  const CutDarts cut = cut_darts(m, {d});
  ASSERT_EQ(cut.vertex_class.size(), cut.mesh.vertices.size());
  const TriMesh closed = closed_darts_mesh(cut);
  EXPECT_EQ(closed.num_faces(), cut.mesh.num_faces());
  EXPECT_LT(closed.num_vertices(), cut.mesh.num_vertices());  // the slit's copies are one again
  const SurfaceReport rep = validate_surface(closed);
  EXPECT_TRUE(rep.is_disk) << rep.summary();  // the slit is closed: a disk again
  EXPECT_EQ(cut.vertex_class[cut.darts[0].notch_a], cut.vertex_class[cut.darts[0].notch_b]);
}

TEST(FlattenInjective, TwoEndDartSlitThroughTheFoldFreeSolver) {
  // Every pattern through the injective solver (limit 0) on a mesh with a
  // slit (two boundary loops): the slit opens, the notches align (from a
  // start that does not align them), nothing folds.
  const TriMesh m = monkey_saddle(6.0);
  const DartSpec d = saddle_two_end_dart();
  FlattenOptions opt;
  opt.enforce_dart_angle = false;
  opt.max_arap_log_sigma = 0.0;
  const Flattening plain = flatten_surface(m, {}, opt);
  const Flattening f = flatten_surface(m, {d}, opt);
  EXPECT_TRUE(f.injective_solver);
  expect_no_fold(f);
  ASSERT_EQ(f.darts.size(), 1u);
  EXPECT_LE(f.darts[0].alignment_error, 1e-6 * 100.0);
  EXPECT_GT((f.uv[f.darts[0].notch_a] - f.uv[f.darts[0].notch_b]).norm(), 1.0);  // the slit opened
  EXPECT_LT(f.stats.rms_log_sigma, plain.stats.rms_log_sigma);
}

}  // namespace
}  // namespace knitforge
