#include <cmath>
#include <numbers>

#include <gtest/gtest.h>

#include "knitforge/design/flatten/flattening_distortion.h"
#include "knitforge/geometry/arap_flatten.h"
#include "knitforge/geometry/halfedges.h"
#include "knitforge/geometry/shapes.h"
#include "knitforge/geometry/tutte_embedding.h"
#include "knitforge/util/errors.h"

namespace knitforge {
namespace {

TEST(TutteEmbedding, HemisphereIsBijectiveWithBoundaryOnCircle) {
  const TriMesh m = hemisphere(40.0, 5.0);
  const TutteEmbedding t = tutte_embedding(m);
  for (int v : t.outer_loop) EXPECT_NEAR(t.uv[v].norm(), t.radius, 1e-9 * t.radius);
  for (int f = 0; f < m.num_faces(); ++f) EXPECT_GT(signed_uv_area(m, t.uv, f), 0.0) << "face " << f;
  // Arc-length parameterisation: circumference = boundary length = 2 pi r.
  EXPECT_NEAR(t.radius, 40.0, 0.2);
}

TEST(TutteEmbedding, ClosedMeshIsRejected) {
  TriMesh tet;
  tet.vertices = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1)};
  tet.faces = {{0, 2, 1}, {0, 1, 3}, {1, 2, 3}, {0, 3, 2}};
  EXPECT_THROW(tutte_embedding(tet), TopologyError);
}

TEST(ArapFlatten, CylinderPatchFlattensIsometrically) {
  const TriMesh m = cylinder_patch(30.0, std::numbers::pi, 40.0, 5.0);
  ArapFlattenOptions opt;
  opt.tolerance = 1e-12;
  opt.max_iterations = 3000;
  const ArapFlattenResult r = arap_flatten(m, opt);
  EXPECT_TRUE(r.flipped_faces.empty());
  const auto d = flattening_distortion(m, r.uv);
  for (size_t f = 0; f < d.size(); ++f) {
    ASSERT_NEAR(d[f].sigma1, 1.0, 1e-3) << "face " << f;
    ASSERT_NEAR(d[f].sigma2, 1.0, 1e-3) << "face " << f;
  }
  // The inscribed triangles are not exactly developable: tiny residual.
  EXPECT_LT(r.relative_energy, 1e-6);
}

TEST(ArapFlatten, FlatDiskStaysCongruent) {
  const TriMesh m = flat_disk(30.0, 5.0);
  ArapFlattenOptions opt;
  opt.tolerance = 1e-13;
  opt.max_iterations = 3000;
  const ArapFlattenResult r = arap_flatten(m, opt);
  double worst = 0.0;
  // All pairwise distances of a sample of vertices are preserved.
  for (int i = 0; i < m.num_vertices(); i += 7) {
    for (int j = i + 1; j < m.num_vertices(); j += 5) {
      const double d3 = (m.vertices[i] - m.vertices[j]).norm();
      const double d2 = (r.uv[i] - r.uv[j]).norm();
      worst = std::max(worst, std::abs(d3 - d2) / 60.0);
    }
  }
  EXPECT_LT(worst, 1e-6);
  EXPECT_TRUE(r.flipped_faces.empty());
}

TEST(ArapFlatten, EqualXConstraintHoldsExactly) {
  const TriMesh m = hemisphere(30.0, 6.0);
  ArapFlattenOptions opt;
  opt.equal_x = {{0, 5}, {5, 9}};
  opt.equal_y = {{3, 7}};
  const ArapFlattenResult r = arap_flatten(m, opt);
  EXPECT_NEAR(r.uv[0].x(), r.uv[5].x(), 1e-9);
  EXPECT_NEAR(r.uv[9].x(), r.uv[5].x(), 1e-9);
  EXPECT_NEAR(r.uv[3].y(), r.uv[7].y(), 1e-9);
}

TEST(ArapFlatten, BadOptionsThrow) {
  const TriMesh m = flat_disk(20.0, 5.0);
  ArapFlattenOptions opt;
  opt.initial.assign(3, Vec2::Zero());
  EXPECT_THROW(arap_flatten(m, opt), InvalidInput);
  ArapFlattenOptions opt2;
  opt2.equal_x = {{0, m.num_vertices()}};
  EXPECT_THROW(arap_flatten(m, opt2), InvalidInput);
}

TEST(ArapFlatten, HemisphereLowersEnergyFromTutte) {
  const TriMesh m = hemisphere(30.0, 5.0);
  const ArapFlattenResult r = arap_flatten(m);
  EXPECT_LT(r.energy, 0.5 * r.initial_energy);
  EXPECT_TRUE(r.flipped_faces.empty());
  EXPECT_TRUE(r.converged);
}

}  // namespace
}  // namespace knitforge
