// The initial fields of seed §3.3.8 for the tube route and the choice among
// them (design/tube/tube_field_candidates.h, design_tube.h).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <numbers>

#include <Eigen/Dense>

#include "knitforge/design/tube/design_tube.h"
#include "knitforge/design/tube/tube_field.h"
#include "knitforge/design/tube/tube_field_candidates.h"
#include "knitforge/geometry/laplacian_eigenvectors.h"
#include "knitforge/geometry/shapes.h"
#include "knitforge/util/errors.h"

namespace knitforge {
namespace {

// A surface of revolution round z: the open tube with its radius varied
// along z (r 25 +- 8 mm, 240 mm long).
TriMesh vase() {
  TriMesh m = open_tube(25.0, 240.0, 5.0);
  for (Vec3& p : m.vertices) {
    const double r = 25.0 + 8.0 * std::sin(2.0 * std::numbers::pi * p.z() / 240.0);
    p.x() *= r / 25.0;
    p.y() *= r / 25.0;
  }
  return m;
}

TEST(TubeFieldCandidates, TheOrthogonalFieldsIsocurvesOnASurfaceOfRevolutionAreMeridians) {
  const TriMesh m = vase();
  const InitialFields f = initial_fields(m);
  ASSERT_TRUE(f.converged);
  std::vector<double> z(m.vertices.size());
  for (size_t v = 0; v < z.size(); ++v) z[v] = m.vertices[v].z();
  // The Fiedler vector: the diameter direction, along the axis.
  EXPECT_GT(gradient_alignment(m, f.fiedler, z), 0.95);
  // The orthogonal field depends on the angle round the axis only: it is
  // a cos(theta) + b sin(theta) + c (least squares) up to discretisation,
  // so each of its levels is a pair of meridians; its gradient runs round
  // the tube, orthogonal to the Fiedler vector's.
  const int n = m.num_vertices();
  Eigen::MatrixXd A(n, 3);
  Eigen::VectorXd y(n);
  for (int v = 0; v < n; ++v) {
    const double th =
        std::atan2(m.vertices[static_cast<size_t>(v)].y(), m.vertices[static_cast<size_t>(v)].x());
    A(v, 0) = std::cos(th), A(v, 1) = std::sin(th), A(v, 2) = 1.0;
    y[v] = f.orthogonal[static_cast<size_t>(v)];
  }
  const Eigen::VectorXd coef = A.colPivHouseholderQr().solve(y);
  const double residual = (A * coef - y).squaredNorm(), total = (y.array() - y.mean()).matrix().squaredNorm();
  EXPECT_LT(residual / total, 0.01) << "not a function of the angle round the axis";
  // (mean |cos| of the angle between the gradients: not exactly 0 where
  // cos(theta) is extreme and its discrete gradient small and noisy)
  EXPECT_LT(gradient_alignment(m, f.orthogonal, z), 0.1);
  EXPECT_LT(f.orthogonal_alignment, 0.1);
}

TEST(TubeFieldCandidates, NamesParseAndBadNamesAreRefusedWithTheList) {
  for (TubeFieldKind k :
       {TubeFieldKind::Auto, TubeFieldKind::Harmonic, TubeFieldKind::Fiedler, TubeFieldKind::Orthogonal})
    EXPECT_EQ(parse_tube_field(tube_field_name(k)), k);
  try {
    parse_tube_field("geodesic");
    FAIL() << "accepted";
  } catch (const InvalidInput& e) {
    EXPECT_NE(
        std::string(e.what()).find("auto (the lowest-scoring knittable one), harmonic, fiedler, orthogonal"),
        std::string::npos)
        << e.what();
  }
}

TEST(TubeFieldCandidates, TheRouteScoresEveryCandidateAndKnitsTheChosenOne) {
  const TriMesh m = open_tube(30.0, 150.0, 5.0);
  TubeDesignOptions o;
  o.params = {7.0, 5.6};
  const TubeDesign d = design_tube(m, o);
  ASSERT_EQ(d.candidates.size(), 3u);
  // A straight tube: the harmonic field and the Fiedler vector both run
  // along it with no shaping; the orthogonal one runs round it and its two
  // rims lie on one level: not knittable in rounds.
  EXPECT_EQ(d.field_kind, TubeFieldKind::Harmonic);
  EXPECT_TRUE(d.candidates[0].knittable);
  EXPECT_LT(d.candidates[0].estimate, 1.0);
  EXPECT_TRUE(d.candidates[1].knittable) << d.candidates[1].why_not;
  EXPECT_LT(d.candidates[1].estimate, 1.0);
  EXPECT_FALSE(d.candidates[2].knittable);
  EXPECT_NE(d.candidates[2].why_not.find("same level"), std::string::npos) << d.candidates[2].why_not;
  // Forced: the Fiedler vector is knitted (rims on its levels), the
  // orthogonal field refused naming why.
  o.field = TubeFieldKind::Fiedler;
  const TubeDesign f = design_tube(m, o);
  EXPECT_EQ(f.field_kind, TubeFieldKind::Fiedler);
  EXPECT_TRUE(f.map_check.ok()) << f.map_check.text();
  EXPECT_NE(f.field.value, d.field.value);
  o.field = TubeFieldKind::Orthogonal;
  try {
    design_tube(m, o);
    FAIL() << "the orthogonal field was knitted";
  } catch (const InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find("the orthogonal field cannot be knitted in rounds"),
              std::string::npos)
        << e.what();
  }
  o.field = TubeFieldKind::Auto;
  o.crown_directions = 0;
  EXPECT_THROW(design_tube(m, o), InvalidInput);
}

// The auto choice is the lowest-scoring knittable candidate: none scores
// lower than the chosen one by a stitch or more.
TEST(TubeFieldCandidates, AutoPicksTheLowestKnittableEstimate) {
  TubeDesignOptions o;
  o.params = {7.0, 5.6};
  for (const TriMesh& m : {sleeve(SleeveShape{}, 6.0), sock(SockShape{}, 6.0)}) {
    const TubeDesign d = design_tube(m, o);
    const TubeFieldCandidate& chosen = d.candidates[static_cast<size_t>(d.field_kind) - 1];
    ASSERT_TRUE(chosen.knittable);
    for (const TubeFieldCandidate& c : d.candidates) {
      if (c.knittable) {
        EXPECT_GT(c.estimate, chosen.estimate - 1.0) << tube_field_name(c.kind);
      }
    }
    EXPECT_NEAR(d.divergence.transfer_estimate(o.params.stitch_width), chosen.estimate, 1e-9);
  }
}

// An eigenvector has free rims, so it is flat there: cos(pi z / h) on a
// straight tube. The levels beside a rim must not be decided by noise:
// two candidates differing by noise of 3e-4 of their range (far above an
// eigen-solver's) give nearly the same field, a round at every level,
// with the rings of z as its isocurves.
TEST(TubeFieldCandidates, ACandidateFlatAtItsRimsIsLevelledIndependentlyOfRoundOff) {
  const double h = 100.0;
  const TriMesh m = open_tube(40.0, h, 2.5);  // the built-in tube at the route's edge
  const TubeField harmonic = tube_field(m, "tube");
  auto candidate = [&](std::uint64_t state) {
    std::vector<double> f(m.vertices.size());
    for (size_t v = 0; v < f.size(); ++v) {
      state = state * 6364136223846793005ull + 1442695040888963407ull;
      const double noise = static_cast<double>(state >> 11) / 9007199254740992.0 - 0.5;  // [-0.5, 0.5)
      f[v] = std::cos(std::numbers::pi * m.vertices[v].z() / h) + 3e-4 * noise;;
    }
    return f;
  };
  const TubeField a = levelled_field(m, candidate(1), harmonic);
  const TubeField b = levelled_field(m, candidate(2), harmonic);
  EXPECT_EQ(a.start_loop, harmonic.start_loop);
  EXPECT_EQ(a.interior_extrema, 0);
  EXPECT_EQ(b.interior_extrema, 0);
  double apart = 0.0, off = 0.0;
  for (size_t v = 0; v < a.value.size(); ++v) {
    apart = std::max(apart, std::abs(a.value[v] - b.value[v]));
    off = std::max(off, std::abs(a.value[v] - harmonic.value[v]));
  }
  EXPECT_LT(apart, 3e-3);
  EXPECT_LT(off, 3e-3);  // with unweighted tangents: 0.013, the rim's flat band steered by the noise
  for (const TubeField* u : {&a, &b}) EXPECT_NO_THROW(round_levels(m, *u, 2.8));
  // What is not a candidate for rounds is refused, naming why.
  std::vector<double> round(m.vertices.size()), tilted(m.vertices.size());
  for (size_t v = 0; v < round.size(); ++v) {
    round[v] = m.vertices[v].x();                               // runs round the tube
    tilted[v] = m.vertices[v].z() + 0.2 * m.vertices[v].x();  // its rims are not its levels
  }
  auto refusal = [&](const std::vector<double>& f) {
    try {
      levelled_field(m, f, harmonic);
    } catch (const InvalidInput& e) {
      return std::string(e.what());
    }
    return std::string("(accepted)");
  };
  EXPECT_NE(refusal(round).find("same level"), std::string::npos) << refusal(round);
  EXPECT_NE(refusal(tilted).find("not levels of it"), std::string::npos) << refusal(tilted);
  EXPECT_THROW(levelled_field(m, std::vector<double>(5, 0.0), harmonic), InvalidInput);
}

// The built-in tube (h 100 < pi r 126) is short and wide: its Fiedler
// vector runs round it, the orthogonal field along it, with rings for
// levels as the harmonic field's: next to no shaping.
TEST(TubeFieldCandidates, TheBuiltInTubesOrthogonalFieldRunsAlongIt) {
  TubeDesignOptions o;
  o.params = {3.5, 2.8};
  const TubeDesign d = design_tube(make_shape("tube", 2.5), o);
  ASSERT_EQ(d.candidates.size(), 3u);
  EXPECT_FALSE(d.candidates[1].knittable);
  EXPECT_NE(d.candidates[1].why_not.find("same level"), std::string::npos) << d.candidates[1].why_not;
  ASSERT_TRUE(d.candidates[2].knittable) << d.candidates[2].why_not;
  EXPECT_LT(d.candidates[2].estimate, 5.0);
  EXPECT_EQ(d.field_kind, TubeFieldKind::Harmonic);
}

}  // namespace
}  // namespace knitforge
