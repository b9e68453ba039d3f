// The initial fields of seed §3.3.8 for the tube route and the choice among
// them (design/tube/tube_field_candidates.h, design_tube.h).
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include <Eigen/Dense>

#include "knitforge/design/tube/design_tube.h"
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

}  // namespace
}  // namespace knitforge
