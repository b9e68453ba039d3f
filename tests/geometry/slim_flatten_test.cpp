#include <cmath>

#include <gtest/gtest.h>

#include "knitforge/design/flatten/flattening_distortion.h"
#include "knitforge/geometry/arap_flatten.h"
#include "knitforge/geometry/shapes.h"
#include "knitforge/geometry/slim_flatten.h"
#include "knitforge/geometry/tutte_embedding.h"
#include "knitforge/util/errors.h"

namespace knitforge {
namespace {

bool all_positive(const TriMesh& m, const std::vector<Vec2>& uv) {
  for (int f = 0; f < m.num_faces(); ++f) {
    if (!(signed_uv_area(m, uv, f) > 0.0)) return false;
  }
  return true;
}

TEST(SlimFlatten, FlatDiskFromTutteBecomesIsometric) {
  // Tutte's map of a flat disk is injective but distorted; the minimum of
  // the symmetric Dirichlet energy is the isometry (energy ratio 1).
  const TriMesh m = flat_disk(40.0, 5.0);
  SlimFlattenOptions opt;
  opt.initial = tutte_embedding(m).uv;
  opt.tolerance = 1e-10;
  const SlimFlattenResult r = slim_flatten(m, opt);
  EXPECT_GT(r.initial_energy, 1.001);
  EXPECT_LT(r.energy, 1.0 + 1e-6);
  EXPECT_TRUE(r.flipped_faces.empty());
  const auto d = flattening_distortion(m, r.uv);
  for (const auto& fd : d) {
    EXPECT_NEAR(fd.sigma1, 1.0, 1e-3);
    EXPECT_NEAR(fd.sigma2, 1.0, 1e-3);
  }
}

TEST(SlimFlatten, HemisphereStaysInjectiveAndLowersTheEnergy) {
  // From Tutte's map (injective, strongly distorted) every iterate keeps all
  // triangles positive, and the energy goes down.
  const TriMesh m = hemisphere(40.0, 4.0);
  SlimFlattenOptions opt;
  opt.initial = tutte_embedding(m).uv;
  const SlimFlattenResult r = slim_flatten(m, opt);
  EXPECT_TRUE(r.flipped_faces.empty());
  EXPECT_TRUE(all_positive(m, r.uv));
  EXPECT_LT(r.energy, r.initial_energy);
  EXPECT_GT(r.energy, 1.0);  // a hemisphere is not developable
}

TEST(SlimFlatten, ConstraintsAreMetFromAStartThatViolatesThem) {
  const TriMesh m = flat_disk(40.0, 5.0);
  SlimFlattenOptions opt;
  opt.initial = tutte_embedding(m).uv;
  // The leftmost vertex must share its x with the topmost and with the
  // bottommost one: no rotation of the disk does both, so the pattern must
  // distort, and the start (Tutte's circle) violates both by ~40 mm.
  int left = 0, top = 0, bottom = 0;
  for (int v = 0; v < m.num_vertices(); ++v) {
    if (m.vertices[v].x() < m.vertices[left].x()) left = v;
    if (m.vertices[v].y() > m.vertices[top].y()) top = v;
    if (m.vertices[v].y() < m.vertices[bottom].y()) bottom = v;
  }
  opt.equal_x = {{left, top}, {left, bottom}};
  ASSERT_GT(std::abs(opt.initial[left].x() - opt.initial[top].x()), 10.0);
  const SlimFlattenResult r = slim_flatten(m, opt);
  EXPECT_TRUE(r.constraints_met);
  EXPECT_LE(std::abs(r.uv[left].x() - r.uv[top].x()), 1e-9 * 80.0);
  EXPECT_LE(std::abs(r.uv[left].x() - r.uv[bottom].x()), 1e-9 * 80.0);
  EXPECT_LE(r.constraint_residual, 1e-9 * 80.0);
  EXPECT_TRUE(all_positive(m, r.uv));
  EXPECT_GT(r.energy, 1.0 + 1e-3);  // the constraints cost distortion
}

TEST(SlimFlatten, FlippedStartAndBadOptionsAreRejected) {
  const TriMesh m = flat_disk(20.0, 5.0);
  SlimFlattenOptions opt;
  opt.initial = tutte_embedding(m).uv;
  for (auto& p : opt.initial) p.x() = -p.x();  // mirrored: every face flipped
  EXPECT_THROW(slim_flatten(m, opt), InvalidInput);
  opt.initial = tutte_embedding(m).uv;
  opt.initial.pop_back();
  EXPECT_THROW(slim_flatten(m, opt), InvalidInput);
  opt.initial = tutte_embedding(m).uv;
  opt.equal_x = {{0, m.num_vertices()}};
  EXPECT_THROW(slim_flatten(m, opt), InvalidInput);
  opt.equal_x.clear();
  opt.max_iterations = -1;
  EXPECT_THROW(slim_flatten(m, opt), InvalidInput);
}

}  // namespace
}  // namespace knitforge
