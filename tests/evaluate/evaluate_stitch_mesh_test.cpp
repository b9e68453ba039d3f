#include "knitforge/evaluate/evaluate_stitch_mesh.h"

#include <cmath>

#include <gtest/gtest.h>

#include "knitforge/convert/map_to_stitch_mesh.h"
#include "knitforge/convert/random_knitting_map.h"
#include "knitforge/convert/relax_stitch_mesh.h"
#include "knitforge/util/errors.h"

namespace knitforge {
namespace {

const KnitParams kP{3.5, 2.8};

// The stitches as triangles (quads split along corner 0-2).
TriMesh triangulate(const StitchMesh& m) {
  TriMesh t;
  t.vertices = m.vertices;
  for (const Stitch& s : m.stitches) {
    t.faces.push_back({s.v[0], s.v[1], s.v[2]});
    if (s.corners() == 4) t.faces.push_back({s.v[0], s.v[2], s.v[3]});
  }
  return t;
}

// The rectangle [x0, x1] x [y0, y1] in the plane z = 0, as n x n quads split in two.
TriMesh flat_rectangle(double x0, double x1, double y0, double y1, int n) {
  TriMesh m;
  for (int i = 0; i <= n; ++i) {
    for (int j = 0; j <= n; ++j) m.vertices.emplace_back(x0 + (x1 - x0) * j / n, y0 + (y1 - y0) * i / n, 0.0);
  }
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j) {
      const int a = i * (n + 1) + j, b = a + 1, c = a + n + 2, d = a + n + 1;
      m.faces.push_back({a, b, c});
      m.faces.push_back({a, c, d});
    }
  }
  return m;
}

TEST(EvaluateStitchMesh, IdealFlatFabricOnAFlatTargetHasNoError) {
  const KnittingMap map(12, 15, CellType::Knit);
  const StitchMesh mesh = map_to_stitch_mesh_topology(map, kP);
  const TriMesh target = flat_rectangle(0, 15 * kP.stitch_width, 0, 12 * kP.stitch_height, 7);
  const StitchMeshEvaluation ev = evaluate_stitch_mesh(mesh, target, kP);
  EXPECT_LT(ev.rms_error, 1e-9);
  EXPECT_LT(ev.max_error, 1e-9);
  EXPECT_LT(ev.designed_max_error, 1e-12);
  EXPECT_LT(ev.correspondence_rms, 1e-9);
  EXPECT_NEAR(ev.target_size, std::hypot(15 * kP.stitch_width, 12 * kP.stitch_height), 1e-12);
  EXPECT_LT(ev.designed_distortion_stats.max, 1e-12);
  EXPECT_LT(ev.relaxed_distortion_stats.max, 1e-9);
  EXPECT_EQ(ev.designed_distortion_stats.count, 180);
  ASSERT_EQ(ev.stitch_error.size(), 180u);
  ASSERT_EQ(ev.vertex_error.size(), static_cast<size_t>(mesh.num_vertices()));
  EXPECT_EQ(ev.relaxed.num_stitches(), mesh.num_stitches());
  EXPECT_GE(ev.seconds.total, ev.seconds.relax);
}

TEST(EvaluateStitchMesh, ScaledDesignRelaxesBackAndShowsItsDistortion) {
  // The flat fabric stretched by 1.2 in x: the designed stitches have
  // sigma = (1.2, 1); the rest shape is ideal again and, aligned back onto
  // the (stretched) target, lies in its plane but cannot cover it exactly.
  const KnittingMap map(10, 10, CellType::Knit);
  StitchMesh mesh = map_to_stitch_mesh_topology(map, kP);
  for (Vec3& p : mesh.vertices) p.x() *= 1.2;
  const TriMesh target = triangulate(mesh);
  const StitchMeshEvaluation ev = evaluate_stitch_mesh(mesh, target, kP);
  EXPECT_NEAR(ev.designed_distortion_stats.min, 0.2, 1e-12);
  EXPECT_NEAR(ev.designed_distortion_stats.max, 0.2, 1e-12);
  EXPECT_LT(ev.relaxed_distortion_stats.max, 1e-6);
  for (const StitchDistortion& d : ev.designed_distortion) {
    EXPECT_NEAR(d.sigma1, 1.2, 1e-12);
    EXPECT_NEAR(d.sigma2, 1.0, 1e-12);
  }
  // The rest shape is the 10 x 10 ideal rectangle in the plane z = 0: it
  // lies inside the stretched target, so the distances are ~0, while its
  // corners moved from the design.
  EXPECT_LT(ev.max_error, 1e-6);
  EXPECT_GT(ev.correspondence_rms, 1.0);
}

TEST(EvaluateStitchMesh, OwnTargetIsBetterThanAWrongOne) {
  RandomMapOptions o;
  o.seed = 5;
  o.rows = 24;
  o.cols = 20;
  o.short_row_ends = 16;
  const KnittingMap map = random_knitting_map(o);
  // Relaxed with the z warm-up: a 3D shape. Without bending, quads hinge
  // freely along whole courses and wales, so the rest shape is not unique:
  // a second relaxation drifts along those folds by an amount that depends
  // on round-off (0.2 mm on one CPU, 0.4 mm on another). With a bending
  // term the rest shape is unique, so relaxed to convergence here and again
  // in the evaluation it must stay on its own surface. How many iterations
  // that takes depends on round-off (about 400 on one CPU, 816 on an AMD
  // EPYC): the first relaxation must itself be converged, or the second one
  // goes on where it stopped (0.04 mm).
  RelaxOptions ro;
  ro.max_iterations = 3000;
  ro.tolerance = 1e-12;
  ro.bending = 0.1;
  const RelaxResult at_rest = relax_stitch_mesh(map_to_stitch_mesh_topology(map, kP), kP, ro);
  ASSERT_TRUE(at_rest.converged);
  const StitchMesh& shaped = at_rest.mesh;
  double zmax = 0;
  for (const Vec3& p : shaped.vertices) zmax = std::max(zmax, std::abs(p.z()));
  ASSERT_GT(zmax, 1.0);

  EvaluateOptions eo;
  eo.relax.bending = ro.bending;
  const StitchMeshEvaluation own = evaluate_stitch_mesh(shaped, triangulate(shaped), kP, eo);
  // At rest: relaxing it again leaves it on its own surface (measured
  // 4e-6 mm; a wrong alignment or a drifting relaxation gives millimetres).
  EXPECT_TRUE(own.relax_converged);
  EXPECT_LT(own.rms_error, 1e-2);
  EXPECT_LT(own.relative_rms_error, 5e-3);
  EXPECT_LT(own.designed_max_error, 1e-12);

  const TriMesh flat = flat_rectangle(0, o.cols * kP.stitch_width, 0, o.rows * kP.stitch_height, 10);
  const StitchMeshEvaluation wrong = evaluate_stitch_mesh(shaped, flat, kP, eo);
  EXPECT_GT(wrong.rms_error, 10 * own.rms_error);
  EXPECT_GT(wrong.rms_error, 0.1 * zmax);
  EXPECT_GE(wrong.max_error, wrong.rms_error);
  EXPECT_NEAR(wrong.relative_rms_error, wrong.rms_error / wrong.target_size, 1e-15);
  // The distortion does not depend on the target.
  EXPECT_EQ(wrong.designed_distortion_stats.mean, own.designed_distortion_stats.mean);

  // ICP improves on the correspondence fit alone (or leaves it).
  EvaluateOptions no_icp = eo;
  no_icp.refine_with_icp = false;
  const StitchMeshEvaluation coarse = evaluate_stitch_mesh(shaped, flat, kP, no_icp);
  EXPECT_LE(wrong.rms_error, coarse.rms_error * (1 + 1e-12));
}

TEST(EvaluateStitchMesh, Deterministic) {
  RandomMapOptions o;
  o.seed = 9;
  o.rows = 16;
  o.cols = 16;
  o.short_row_ends = 8;
  o.short_columns = 2;
  const KnittingMap map = random_knitting_map(o);
  const StitchMesh shaped = map_to_stitch_mesh(map, kP);
  const TriMesh target = flat_rectangle(-5, 60, -5, 50, 9);
  const StitchMeshEvaluation a = evaluate_stitch_mesh(shaped, target, kP);
  const StitchMeshEvaluation b = evaluate_stitch_mesh(shaped, target, kP);
  EXPECT_EQ(a.vertex_error, b.vertex_error);
  EXPECT_EQ(a.stitch_error, b.stitch_error);
  EXPECT_EQ(a.relaxed.vertices, b.relaxed.vertices);
  EXPECT_EQ(a.rms_error, b.rms_error);
  EXPECT_EQ(a.relaxed_distortion_stats.p90, b.relaxed_distortion_stats.p90);
}

TEST(EvaluateStitchMesh, BadInputThrows) {
  const KnittingMap map(4, 4, CellType::Knit);
  const StitchMesh mesh = map_to_stitch_mesh_topology(map, kP);
  const TriMesh target = flat_rectangle(0, 10, 0, 10, 2);
  EXPECT_THROW(evaluate_stitch_mesh(StitchMesh{}, target, kP), InvalidInput);
  EXPECT_THROW(evaluate_stitch_mesh(mesh, TriMesh{}, kP), InvalidInput);
  EXPECT_THROW(evaluate_stitch_mesh(mesh, target, KnitParams{-1, 2}), InvalidInput);
  StitchMesh bad = mesh;
  bad.stitches[3].v[1] = 1000;
  EXPECT_THROW(evaluate_stitch_mesh(bad, target, kP), TopologyError);
}

}  // namespace
}  // namespace knitforge
