// The boundary optimisation of seed §3.3.5 on a real surface
// (optimise_boundary.h), and the exact feasibility of what it evaluates.
#include "knitforge/design/shortcolumn/optimise_boundary.h"

#include <algorithm>

#include <gtest/gtest.h>

#include "knitforge/design/shortcolumn/divergence_metric.h"
#include "knitforge/design/shortcolumn/feasible_set.h"
#include "knitforge/design/shortcolumn/harmonic_field.h"
#include "knitforge/geometry/cut_to_disk.h"
#include "knitforge/geometry/geodesic_source.h"
#include "knitforge/geometry/mesh_measures.h"
#include "knitforge/geometry/shapes.h"
#include "knitforge/util/errors.h"

namespace knitforge {
namespace {

TEST(SnapFeasible, RoundingViolationsAreRemovedAndRealOnesRefused) {
  // b3 a hair below b2 (what the projection's rounding leaves).
  const BoundaryVector b{0.167426, 0.531390, 0.532390, 0.532390 - 1e-13};
  EXPECT_FALSE(is_feasible(b));
  const BoundaryVector s = snap_feasible(b);
  EXPECT_TRUE(is_feasible(s));
  for (int i = 0; i < 4; ++i) EXPECT_NEAR(s[static_cast<size_t>(i)], b[static_cast<size_t>(i)], 1e-12);
  EXPECT_EQ(snap_feasible({0.1, 0.2, 0.5, 0.6}), (BoundaryVector{0.1, 0.2, 0.5, 0.6}));
  EXPECT_THROW(snap_feasible({0.3, 0.2, 0.5, 0.6}), InvalidInput);
}

TEST(OptimiseBoundary, HemisphereBeatsTheInitialDesignAndIsDeterministic) {
  const TriMesh surface = hemisphere(75.0, 6.0);
  BoundaryOptimisationOptions o;
  o.stitch_width = 3.5;
  o.turbo.max_evaluations = 24;
  o.turbo.seed = 3;
  o.proxy_faces = 0;  // the surface itself, so the value can be checked below
  int calls = 0;
  o.progress = [&](const BoundaryEvaluation&, int i) { EXPECT_EQ(i, calls++); };
  const BoundaryOptimisation r = optimise_boundary(surface, o);
  ASSERT_EQ(r.history.size(), 24u);
  EXPECT_EQ(calls, 24);
  double best = 1e300, initial_worst = -1e300;
  for (const BoundaryEvaluation& e : r.history) {
    EXPECT_TRUE(is_feasible(e.evaluated));
    best = std::min(best, e.value);
    EXPECT_DOUBLE_EQ(e.best, best);
    if (e.initial) initial_worst = std::max(initial_worst, e.value);
  }
  EXPECT_DOUBLE_EQ(r.best_value, best);
  EXPECT_LT(r.best_value, initial_worst);
  // The best b's field has the reported value: 3/2 I / sw.
  const HarmonicField h = harmonic_field(surface, r.best);
  EXPECT_NEAR(1.5 * divergence_metric(surface, h.value).total / 3.5, r.best_value, 1e-6 * (1 + r.best_value));
  // Alternatives: distinct, best first.
  ASSERT_FALSE(r.alternatives.empty());
  EXPECT_DOUBLE_EQ(r.history[static_cast<size_t>(r.alternatives[0])].value, r.best_value);
  for (size_t i = 0; i < r.alternatives.size(); ++i)
    for (size_t j = i + 1; j < r.alternatives.size(); ++j)
      EXPECT_GE(boundary_distance(r.history[static_cast<size_t>(r.alternatives[i])].evaluated,
                                  r.history[static_cast<size_t>(r.alternatives[j])].evaluated),
                o.distinct_distance);
  o.progress = nullptr;
  const BoundaryOptimisation again = optimise_boundary(surface, o);
  EXPECT_EQ(again.best, r.best);
}

}  // namespace
}  // namespace knitforge

namespace knitforge {
namespace {

TEST(OptimiseBoundary, BoundaryVectorsTheProxyCannotPlaceScoreAsTheWorst) {
  // The built-in cap cut into a disk (as `knitforge shortcolumn cap` does):
  // on its 3000-face proxy some suggestions squeeze R_e next to R_s between
  // two boundary vertices (b2 = b1 + margin, where the projection puts
  // them); they have no field and must not stop the optimisation.
  const TriMesh cap = make_shape("cap");
  const BoundingBox box = bounding_box(cap);
  CutToDiskOptions co;
  co.source = source_from_plane(cap, Vec3(1, 0, 0), 0.5 * (box.min.x() + box.max.x()));
  const TriMesh surface = cut_to_disk(cap, co).mesh;
  BoundaryOptimisationOptions o;
  o.turbo.max_evaluations = 100;
  const BoundaryOptimisation r = optimise_boundary(surface, o);
  ASSERT_EQ(r.history.size(), 100u);
  EXPECT_GT(r.unplaceable, 0);
  double worst = 0.0;
  for (const BoundaryEvaluation& e : r.history) worst = std::max(worst, e.value);
  EXPECT_LT(r.best_value, worst);
  EXPECT_NO_THROW(harmonic_field(surface, r.best)) << "the best b has a field on the surface too";
}

}  // namespace
}  // namespace knitforge
